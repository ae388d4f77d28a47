#pragma once

#include <optional>
#include <string_view>
#include <vector>

namespace boneless {

// What a solved take can be written as. The table below is the one list the CLI's --format, the
// sidecar's "output" and the application's Export dialog read, so a new format appears everywhere.
enum class ExportFormat { Obj, Pc2, Mdd, Glb };

struct ExportFormatInfo {
    ExportFormat format;
    const char* name;         // --format value and sidecar "output": "obj", "pc2", "mdd", "glb"
    const char* extension;    // with the dot; an OBJ sequence is one file per frame
    const char* description;  // one line for a file dialog or --help
    // Keys each frame at its time in the take (frame / rate), so it needs the take's frame rate;
    // OBJ frames and PC2 samples are numbered by frame.
    bool timed;
};

// In the order a user is offered them.
const std::vector<ExportFormatInfo>& exportFormats();
const ExportFormatInfo& exportFormatInfo(ExportFormat format);
std::optional<ExportFormat> findExportFormat(std::string_view name);

}  // namespace boneless
