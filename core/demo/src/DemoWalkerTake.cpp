#include <array>
#include <string>

#include "DemoCapture.h"
#include "DemoWalker.h"

namespace boneless {

namespace {
constexpr double kMmPerMeshUnit = 1000.0;  // the walker is modelled in metres
}

DemoTake makeDemoWalkerTake(const DemoWalker& walker, double offsetMm) {
    const int K = static_cast<int>(walker.markerVertices.size());
    const int frames = static_cast<int>(walker.frames.size());
    // The capture volume's axes are not the mesh's: a quarter turn about z and an offset.
    DemoTake out =
        recordDemoTake(walker.rest, walker.frames, walker.framesPerSecond, "walker",
                       walker.markerVertices, kMmPerMeshUnit, offsetMm, Vec3(1200.0, -300.0, 0.0));
    C3dTake& take = out.take;
    // Occlusions where a walk hides markers from cameras: a wrist passing the hip, the sacrum,
    // a heel behind the other leg, a finger.
    const std::pair<std::string, std::array<int, 2>> gaps[] = {
        {"LWRB", {14, 22}}, {"RPSI", {30, 37}}, {"LHEE", {41, 45}}, {"RFIN", {5, 12}}};
    for (const auto& [label, span] : gaps)
        for (int k = 0; k < K; ++k)
            if (walker.markerVertices[k].first == label)
                for (int t = span[0]; t < span[1] && t < frames; ++t) take.samples.setMissing(t, k);
    return out;
}

}  // namespace boneless
