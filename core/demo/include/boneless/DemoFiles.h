#pragma once

#include <string>
#include <vector>

namespace boneless {

// Who the generated demo shows. The walker (a human body walking, a Plug-in Gait style marker
// set) is the demo of the application and of `boneless-cli demo`; the creature (a swimming
// capsule, 30 sampled markers) is the subject the solver's tests were measured on.
enum class DemoSubject { Walker, Creature };

// The generated demo as files, the way a user would get them from a capture session:
// <subject>.obj (rest pose), <subject>.c3d (markers with gaps), <subject>.map.json (the
// correspondence) and, when asked, truth/<subject>_<frame:04>.obj (the true motion), where
// <subject> is walker or creature.
struct DemoFiles {
    std::string folder, mesh, take, map, truthFolder;
    int vertices = 0, faces = 0, markers = 0, frames = 0;
    double rate = 0;
};

// Writes the demo into `folder` (created if missing), replacing its files there (see
// demoFilesThatDiffer) and removing its truth frames past `frames` (truth/<name>_NNNN.obj) that a
// longer demo left. Throws Error naming the folder on failure. detail = 1 is the shipped
// resolution, more is finer, for runs that need a mesh large enough for the local/global
// method's coarse level: the creature has d² times the faces (2,784 at 1), the walker 4^(d−1)
// times (6,848 at 1).
DemoFiles writeDemoFiles(const std::string& folder, int frames = 60, double offsetMm = 10.0,
                         bool withTruth = true, int detail = 1,
                         DemoSubject subject = DemoSubject::Creature);

// The files writeDemoFiles with these arguments would replace in `folder` with other bytes (a
// map edited since, a take of another length) or remove (its truth frames past `frames`, last),
// named as in the folder ("walker.map.json", "truth/walker_0003.obj"); none when the folder
// holds none of the demo's files, or holds them as this demo would write them.
std::vector<std::string> demoFilesThatDiffer(const std::string& folder, int frames, double offsetMm,
                                             bool withTruth, int detail, DemoSubject subject);

}  // namespace boneless
