#include "boneless/ExportFormat.h"

namespace boneless {

const std::vector<ExportFormatInfo>& exportFormats() {
    static const std::vector<ExportFormatInfo> formats = {
        {ExportFormat::Obj, "obj", ".obj", "OBJ sequence: one mesh file per frame", false},
        // Those docs/export.md says read it as it is: Maya needs a plug-in.
        {ExportFormat::Pc2, "pc2", ".pc2", "PC2 point cache (Blender Mesh Cache, 3ds Max)", false},
        {ExportFormat::Mdd, "mdd", ".mdd",
         "MDD point cache (LightWave, Cinema 4D, Blender Mesh Cache, Houdini)", true},
        {ExportFormat::Glb, "glb", ".glb",
         "glTF 2.0 binary: the mesh with a morph-target animation (Blender, Unity, web viewers)",
         true},
    };
    return formats;
}

const ExportFormatInfo& exportFormatInfo(ExportFormat format) {
    for (const ExportFormatInfo& info : exportFormats())
        if (info.format == format) return info;
    return exportFormats().front();  // unreachable: every enumerator is in the table
}

std::optional<ExportFormat> findExportFormat(std::string_view name) {
    for (const ExportFormatInfo& info : exportFormats())
        if (name == info.name) return info.format;
    return std::nullopt;
}

}  // namespace boneless
