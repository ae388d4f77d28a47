#pragma once

#include "DemoCreature.h"
#include "boneless/C3dTake.h"
#include "boneless/Correspondence.h"

namespace boneless {

// The demo creature's motion as a motion-capture session would record it: `markerCount` markers
// (farthest-point sampled vertices) sitting `offsetMm` off the skin, in millimetres with the
// creature taken to be in decimetres, seen from a rotated and shifted capture volume, with a few
// gaps where markers are occluded; and the correspondence file that maps them.
struct DemoTake {
    C3dTake take;
    Correspondence map;
};

DemoTake makeDemoTake(const DemoCreature& demo, int markerCount = 30, double offsetMm = 10.0);

struct DemoCapture;
// How that session sees the creature (DemoCapture.h), for recording it a frame at a time.
DemoCapture demoCreatureCapture(const DemoCreature& demo, int markerCount = 30);

}  // namespace boneless
