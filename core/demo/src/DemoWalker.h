#pragma once

#include <functional>
#include <string>
#include <vector>

#include "DemoTake.h"
#include "boneless/TriMesh.h"

namespace boneless {

// The project's demo subject, made entirely in code: a closed, smooth human body (torso, head,
// arms, hands, legs, feet; metres, z up, facing −y) walking on the spot, every vertex of every
// frame known so that a reconstruction can be checked against the truth. The body is a
// Catmull–Clark surface of a box-modelled cage; the walk poses the cage with a skeleton
// (which Boneless never sees) and subdivides each posed cage.
struct DemoWalker {
    TriMesh rest;
    // frames[t] is the true pose at frame t (#V by 3); frames[0] is the rest pose.
    std::vector<Positions> frames;
    double framesPerSecond = 30;
    // Where a Plug-in Gait style marker set sits: label (LFHD, C7, LKNE, ...) and skin vertex.
    std::vector<std::pair<std::string, int>> markerVertices;
};

// subdivisions: Catmull–Clark steps of the cage, each 4× the faces (2: 6,848 faces). With
// `onFrame`, each frame goes to it as it is made and `frames` stays empty.
DemoWalker makeDemoWalker(int frameCount = 60, int subdivisions = 2,
                          const std::function<void(int, const Positions&)>& onFrame = {});

// The walk as a capture session records it: the marker set `offsetMm` off the skin, in
// millimetres, seen from a capture volume turned and shifted from the mesh's axes, with
// occlusion gaps; and the correspondence file that maps it.
DemoTake makeDemoWalkerTake(const DemoWalker& walker, double offsetMm = 10.0);

struct DemoCapture;
// How that session sees the walker (DemoCapture.h), for recording it a frame at a time.
DemoCapture demoWalkerCapture(const DemoWalker& walker);

}  // namespace boneless
