#include "boneless/DemoFiles.h"

#include <cstdio>
#include <filesystem>

#include "boneless/C3dWriter.h"
#include "boneless/DemoCreature.h"
#include "boneless/DemoTake.h"
#include "boneless/Error.h"
#include "boneless/ObjWriter.h"

namespace boneless {

DemoFiles writeDemoFiles(const std::string& folder, int frames, double offsetMm, bool withTruth,
                         int detail) {
    namespace fs = std::filesystem;
    const fs::path out(folder), truth = out / "truth";
    std::error_code ec;
    fs::create_directories(withTruth ? truth : out, ec);
    if (ec) throw Error(folder + ": cannot create the folder (" + ec.message() + ")");
    if (detail < 1)
        throw Error("demo detail must be at least 1 (got " + std::to_string(detail) + ")");
    const DemoCreature demo = makeDemoCreature(frames, 48 * detail, 24 * detail);
    const DemoTake take = makeDemoTake(demo, 30, offsetMm);

    DemoFiles files;
    files.folder = folder;
    files.mesh = (out / "creature.obj").string();
    files.take = (out / "creature.c3d").string();
    files.map = (out / "creature.map.json").string();
    writeObj(files.mesh, demo.rest.V, demo.rest.F,
             "Boneless generated demo creature, rest pose (decimetres, z up)");
    writeC3d(take.take, files.take);
    take.map.write(files.map);
    if (withTruth) {
        files.truthFolder = truth.string();
        for (int t = 0; t < static_cast<int>(demo.frames.size()); ++t) {
            char name[32];
            std::snprintf(name, sizeof name, "creature_%04d.obj", t);
            writeObj((truth / name).string(), demo.frames[t], demo.rest.F,
                     "Boneless generated demo creature, true pose of frame " + std::to_string(t));
        }
    }
    files.vertices = demo.rest.vertexCount();
    files.faces = demo.rest.faceCount();
    files.markers = static_cast<int>(take.take.points.size());
    files.frames = static_cast<int>(take.take.frameCount());
    files.rate = take.take.rate;
    return files;
}

}  // namespace boneless
