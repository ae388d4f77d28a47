#pragma once

#include <string>

namespace boneless {

// The generated demo as files, the way a user would get them from a capture session:
// creature.obj (rest pose), creature.c3d (markers with gaps), creature.map.json (the
// correspondence) and, when asked, truth/creature_<frame:04>.obj (the true motion).
struct DemoFiles {
    std::string folder, mesh, take, map, truthFolder;
    int vertices = 0, faces = 0, markers = 0, frames = 0;
    double rate = 0;
};

// Writes the demo into `folder` (created if missing). Throws Error naming the folder on failure.
// detail = 1 is the shipped demo (2,784 faces); detail d has d² times as many faces, for runs
// that need a mesh large enough for the local/global method's coarse level.
DemoFiles writeDemoFiles(const std::string& folder, int frames = 60, double offsetMm = 10.0,
                         bool withTruth = true, int detail = 1);

}  // namespace boneless
