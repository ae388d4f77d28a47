#pragma once

// What the demo subjects share of a capture session (DemoTake.cpp, DemoWalkerTake.cpp).

#include <string>
#include <utility>
#include <vector>

#include "DemoTake.h"
#include "boneless/MeshTopology.h"
#include "boneless/ShapeEncoding.h"
#include "boneless/TriMesh.h"

namespace boneless {

// How a capture session sees a subject: its markers (label, skin vertex), in millimetres with the
// mesh unit `mmPerMeshUnit` mm, from a capture volume turned a quarter about z and shifted by
// `shiftMm`, each marker missing over its gaps (marker index, first frame, frame after the last).
struct DemoCapture {
    std::string subject;  // labels "<subject>:<label>", the take <subject>.c3d, the map's mesh
    double framesPerSecond = 30;
    std::vector<std::pair<std::string, int>> markers;
    double mmPerMeshUnit = 1000;
    Vec3 shiftMm = Vec3::Zero();
    struct Gap {
        int marker, first, end;
    };
    std::vector<Gap> gaps;
};

// An animated mesh recorded a frame at a time, as the capture says, each marker `offsetMm` off
// the skin along its ring's normal: a caller that writes each frame's truth as it is made holds
// none of them (a 100,000-frame demo). `take` is complete once every frame is recorded.
class DemoRecorder {
  public:
    DemoRecorder(const TriMesh& rest, DemoCapture capture, int frameCount, double offsetMm);
    DemoRecorder(const DemoRecorder&) = delete;  // the encoding points at the topology
    DemoRecorder& operator=(const DemoRecorder&) = delete;
    void record(int frame, const Positions& pose);
    DemoTake take;

  private:
    DemoCapture capture_;
    MeshTopology topology_;
    ShapeEncoding encoding_;
    double offset_;  // in mesh units
};

// Every frame of `frames` recorded as `capture` says: the take of a demo held whole in memory.
DemoTake recordDemoTake(const TriMesh& rest, const std::vector<Positions>& frames,
                        DemoCapture capture, double offsetMm);

}  // namespace boneless
