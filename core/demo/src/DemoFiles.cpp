#include "boneless/DemoFiles.h"

#include <cstdio>
#include <filesystem>

#include "DemoCreature.h"
#include "DemoTake.h"
#include "DemoWalker.h"
#include "boneless/C3dWriter.h"
#include "boneless/Error.h"
#include "boneless/ObjWriter.h"

namespace boneless {

DemoFiles writeDemoFiles(const std::string& folder, int frames, double offsetMm, bool withTruth,
                         int detail, DemoSubject subject) {
    namespace fs = std::filesystem;
    const fs::path out(folder), truth = out / "truth";
    std::error_code ec;
    fs::create_directories(withTruth ? truth : out, ec);
    if (ec) throw Error(folder + ": cannot create the folder (" + ec.message() + ")");
    if (detail < 1)
        throw Error("demo detail must be at least 1 (got " + std::to_string(detail) + ")");
    TriMesh rest;
    std::vector<Positions> truthFrames;
    DemoTake take;
    std::string name, units;
    if (subject == DemoSubject::Walker) {
        if (detail > 4)
            throw Error("the walker's detail is at most 4 (got " + std::to_string(detail) + ")");
        DemoWalker walker = makeDemoWalker(frames, 1 + detail);
        take = makeDemoWalkerTake(walker, offsetMm);
        rest = std::move(walker.rest);
        truthFrames = std::move(walker.frames);
        name = "walker";
        units = "metres";
    } else {
        DemoCreature creature = makeDemoCreature(frames, 48 * detail, 24 * detail);
        take = makeDemoTake(creature, 30, offsetMm);
        rest = std::move(creature.rest);
        truthFrames = std::move(creature.frames);
        name = "creature";
        units = "decimetres";
    }

    DemoFiles files;
    files.folder = folder;
    files.mesh = (out / (name + ".obj")).string();
    files.take = (out / (name + ".c3d")).string();
    files.map = (out / (name + ".map.json")).string();
    writeObj(files.mesh, rest.V, rest.F,
             "Boneless generated demo " + name + ", rest pose (" + units + ", z up)");
    writeC3d(take.take, files.take);
    take.map.write(files.map);
    if (withTruth) {
        files.truthFolder = truth.string();
        for (int t = 0; t < static_cast<int>(truthFrames.size()); ++t) {
            char file[64];
            std::snprintf(file, sizeof file, "%s_%04d.obj", name.c_str(), t);
            writeObj(
                (truth / file).string(), truthFrames[t], rest.F,
                "Boneless generated demo " + name + ", true pose of frame " + std::to_string(t));
        }
    }
    files.vertices = rest.vertexCount();
    files.faces = rest.faceCount();
    files.markers = static_cast<int>(take.take.points.size());
    files.frames = static_cast<int>(take.take.frameCount());
    files.rate = take.take.rate;
    return files;
}

}  // namespace boneless
