#include "FrameOutput.h"

#include <cstdio>
#include <filesystem>

#include "boneless/GltfWriter.h"
#include "boneless/MddWriter.h"
#include "boneless/ObjWriter.h"
#include "boneless/OutputFolder.h"
#include "boneless/PointCacheWriter.h"
#include "boneless/TakeExport.h"

namespace boneless {

FrameOutput openFrameOutput(ExportFormat format, const std::string& outDir, const std::string& stem,
                            const TriMesh& mesh, int first, double rate,
                            const std::string& objComment, const GltfPlacement& glb,
                            std::shared_ptr<const SourceFaces> objFaces) {
    const std::filesystem::path out(outDir);
    const std::string path = (out / (stem + exportFormatInfo(format).extension)).string();
    // Times in the take: frame f is at f / rate seconds, whatever range is exported.
    const double period = rate > 0 ? 1.0 / rate : 0.0;
    FrameOutput o;
    switch (format) {
        case ExportFormat::Obj:
            o.append = [out, stem, &mesh, objComment, objFaces](int f, const Positions& V) {
                writeObj((out / objFrameFile(stem, f)).string(), V, mesh.F,
                         objComment + " frame " + std::to_string(f), objFaces.get());
            };
            o.finish = [] {};
            break;
        case ExportFormat::Pc2: {
            auto w = std::make_shared<PointCacheWriter>(path, mesh.vertexCount(), first, 1.0);
            o.append = [w](int, const Positions& V) { w->append(V); };
            o.finish = [w] { w->finish(); };
            o.writer = w;
            break;
        }
        case ExportFormat::Mdd: {
            auto w = std::make_shared<MddWriter>(path, mesh.vertexCount());
            o.append = [w, period](int f, const Positions& V) { w->append(f * period, V); };
            o.finish = [w] { w->finish(); };
            o.writer = w;
            break;
        }
        case ExportFormat::Glb: {
            auto w = std::make_shared<GltfWriter>(path, mesh, stem, glb);
            o.append = [w, period](int f, const Positions& V) { w->append(f, f * period, V); };
            o.finish = [w] { w->finish(); };
            o.writer = w;
            break;
        }
    }
    return o;
}

}  // namespace boneless
