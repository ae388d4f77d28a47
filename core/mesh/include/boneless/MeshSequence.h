#pragma once

#include <string>
#include <vector>

#include "boneless/TriMesh.h"

namespace boneless {

// A ground-truth animation: one mesh file per frame, same connectivity, frames in the order of
// the numbers in their names (frame_2.obj before frame_10.obj); frame 0 is the rest pose.
struct MeshSequence {
    TriMesh rest;                   // frame 0
    std::vector<Positions> frames;  // every frame, frame 0 included
    std::vector<std::string> files;
};

// Reads every .obj in `directory`; throws MeshError naming the file whose vertex count or faces
// differ from the first one's, or the folder and two files whose names give no order (named
// differently, or carrying the same number).
MeshSequence readMeshSequence(const std::string& directory);

}  // namespace boneless
