#pragma once

#include <functional>
#include <vector>

#include "boneless/TriMesh.h"

namespace boneless {

// A subject made entirely in code for the solver's tests (the demo users see is DemoWalker): a
// closed, capsule-shaped creature lying along x (a tube with hemispherical caps, a bulging head,
// a tapered tail), and a swimming motion whose every vertex is known, so a reconstruction of it
// can be checked against the truth.
struct DemoCreature {
    TriMesh rest;
    // frames[t] is the true pose at frame t (#V by 3); frames[0] is the rest pose.
    std::vector<Positions> frames;
    double framesPerSecond = 30;
};

// rings × segments controls the resolution: faces = 2 · segments · (rings + 2 · capRings − 2),
// capRings = segments / 4 (2,784 faces by default).
// With `onFrame`, each frame goes to it as it is made and `frames` stays empty.
DemoCreature makeDemoCreature(int frameCount = 60, int rings = 48, int segments = 24,
                              const std::function<void(int, const Positions&)>& onFrame = {});

}  // namespace boneless
