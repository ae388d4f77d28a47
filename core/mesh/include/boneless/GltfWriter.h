#pragma once

#include <array>
#include <cstdio>
#include <string>
#include <vector>

#include "boneless/TriMesh.h"

namespace boneless {

// Streams frames into a glTF 2.0 binary (.glb): the rest mesh (positions and triangles only, one
// glTF vertex per mesh vertex in the mesh's order, so importers keep the vertex count and order),
// one morph target per frame holding that frame's offsets from the rest pose, and an animation on
// the morph weights keyed at each frame's time in the take (LINEAR: frame k has weight 1 at its
// time, and playback between two frames blends them). The weight keys are a sparse accessor, so
// they grow with the frame count rather than its square. Coordinates and units are the mesh's own.
// Frames are spooled to a file; finish() writes the .glb under a temporary name and renames it.
class GltfWriter {
  public:
    GltfWriter(std::string path, const TriMesh& rest, std::string name);
    ~GltfWriter();  // an unfinished file is removed
    GltfWriter(const GltfWriter&) = delete;
    GltfWriter& operator=(const GltfWriter&) = delete;

    void append(double seconds, const Positions& positions);  // #vertices by 3
    void finish();

  private:
    std::string path_, spool_, name_;
    const TriMesh& rest_;
    std::FILE* file_ = nullptr;
    std::vector<float> times_;
    std::vector<std::array<double, 6>> bounds_;  // per frame: min xyz, max xyz of the offsets
};

}  // namespace boneless
