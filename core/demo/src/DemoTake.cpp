#include "DemoTake.h"

#include <cstdio>

#include "DemoCapture.h"
#include "boneless/Sampling.h"

namespace boneless {

namespace {
constexpr double kMmPerMeshUnit = 100.0;  // the creature is modelled in decimetres
}

DemoTake makeDemoTake(const DemoCreature& demo, int markerCount, double offsetMm) {
    const std::vector<int> vertices = geodesicFarthestPoints(demo.rest, markerCount, 0);
    const int K = static_cast<int>(vertices.size());
    const int frames = static_cast<int>(demo.frames.size());
    std::vector<std::pair<std::string, int>> markers;
    for (int k = 0; k < K; ++k) {
        char name[16];
        std::snprintf(name, sizeof name, "M%02d", k + 1);
        markers.emplace_back(name, vertices[k]);
    }
    // The capture volume's axes are not the mesh's: a quarter turn about z and an offset.
    DemoTake out = recordDemoTake(demo.rest, demo.frames, demo.framesPerSecond, "creature", markers,
                                  kMmPerMeshUnit, offsetMm, Vec3(1200.0, -300.0, 50.0));
    C3dTake& take = out.take;
    // Occlusions: three markers vanish for a while, as markers do.
    const int gaps[][3] = {{3, 20, 28}, {11, 35, 45}, {17, 5, 9}};
    for (const auto& g : gaps)
        for (int t = g[1]; t < g[2] && t < frames; ++t)
            if (g[0] < K) take.samples.setMissing(t, g[0]);
    return out;
}

}  // namespace boneless
