#pragma once

#include <functional>
#include <string>
#include <vector>

#include "boneless/TriMesh.h"

namespace boneless {

// A ground-truth animation: one mesh file per frame, same connectivity, frames in the order of
// the numbers in their names (frame_2.obj before frame_10.obj); frame 0 is the rest pose.
struct MeshSequence {
    TriMesh rest;                   // frame 0
    std::vector<Positions> frames;  // every frame, frame 0 included; those not read are empty
    std::vector<std::string> files;
};

// The .obj files of `directory` in frame order, unread; throws MeshError as readMeshSequence.
std::vector<std::string> meshSequenceFiles(const std::string& directory);

// Reads every .obj in `directory`; throws MeshError naming the file whose vertex count or faces
// differ from the first one's, or the folder and two files whose names give no order (named
// differently, or carrying the same number).
// Frame 0 and the frames `wanted` accepts are read (all when it is empty), the others left
// empty: evaluating a few frames of a long sequence reads a few files.
MeshSequence readMeshSequence(const std::string& directory,
                              const std::function<bool(int frame)>& wanted = {});

}  // namespace boneless
