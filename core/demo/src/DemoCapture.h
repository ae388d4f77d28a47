#pragma once

// What the demo subjects share of a capture session (DemoTake.cpp, DemoWalkerTake.cpp).

#include <string>
#include <utility>
#include <vector>

#include "DemoTake.h"
#include "boneless/TriMesh.h"

namespace boneless {

// An animated mesh as a capture session records its markers: each marker (label, skin vertex)
// `offsetMm` off the skin along its ring's normal, in millimetres with the mesh unit
// `mmPerMeshUnit` mm, seen from a capture volume turned a quarter about z and shifted by
// `shiftMm`. The take is <subject>.c3d with labels "<subject>:<label>", the map is for
// <subject>.obj. No gaps: each subject adds its own.
DemoTake recordDemoTake(const TriMesh& rest, const std::vector<Positions>& frames,
                        double framesPerSecond, const std::string& subject,
                        const std::vector<std::pair<std::string, int>>& markers,
                        double mmPerMeshUnit, double offsetMm, const Vec3& shiftMm);

}  // namespace boneless
