#include "DemoTake.h"

#include <cstdio>

#include "DemoCapture.h"
#include "boneless/Sampling.h"

namespace boneless {

namespace {
constexpr double kMmPerMeshUnit = 100.0;  // the creature is modelled in decimetres
}

DemoCapture demoCreatureCapture(const DemoCreature& demo, int markerCount) {
    DemoCapture capture;
    capture.subject = "creature";
    capture.framesPerSecond = demo.framesPerSecond;
    capture.mmPerMeshUnit = kMmPerMeshUnit;
    // The capture volume's axes are not the mesh's: a quarter turn about z and an offset.
    capture.shiftMm = Vec3(1200.0, -300.0, 50.0);
    const std::vector<int> vertices = geodesicFarthestPoints(demo.rest, markerCount, 0);
    const int K = static_cast<int>(vertices.size());
    for (int k = 0; k < K; ++k) {
        char name[16];
        std::snprintf(name, sizeof name, "M%02d", k + 1);
        capture.markers.emplace_back(name, vertices[k]);
    }
    // Occlusions: three markers vanish for a while, as markers do.
    for (const DemoCapture::Gap& g : {DemoCapture::Gap{3, 20, 28}, {11, 35, 45}, {17, 5, 9}})
        if (g.marker < K) capture.gaps.push_back(g);
    return capture;
}

DemoTake makeDemoTake(const DemoCreature& demo, int markerCount, double offsetMm) {
    return recordDemoTake(demo.rest, demo.frames, demoCreatureCapture(demo, markerCount), offsetMm);
}

}  // namespace boneless
