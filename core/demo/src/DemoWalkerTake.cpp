#include <array>
#include <string>

#include "DemoCapture.h"
#include "DemoWalker.h"

namespace boneless {

namespace {
constexpr double kMmPerMeshUnit = 1000.0;  // the walker is modelled in metres
}

DemoCapture demoWalkerCapture(const DemoWalker& walker) {
    DemoCapture capture;
    capture.subject = "walker";
    capture.framesPerSecond = walker.framesPerSecond;
    capture.markers = walker.markerVertices;
    capture.mmPerMeshUnit = kMmPerMeshUnit;
    // The capture volume's axes are not the mesh's: a quarter turn about z and an offset.
    capture.shiftMm = Vec3(1200.0, -300.0, 0.0);
    // Occlusions where a walk hides markers from cameras: a wrist passing the hip, the sacrum,
    // a heel behind the other leg, a finger.
    const std::pair<std::string, std::array<int, 2>> gaps[] = {
        {"LWRB", {14, 22}}, {"RPSI", {30, 37}}, {"LHEE", {41, 45}}, {"RFIN", {5, 12}}};
    for (const auto& [label, span] : gaps)
        for (int k = 0; k < static_cast<int>(capture.markers.size()); ++k)
            if (capture.markers[k].first == label) capture.gaps.push_back({k, span[0], span[1]});
    return capture;
}

DemoTake makeDemoWalkerTake(const DemoWalker& walker, double offsetMm) {
    return recordDemoTake(walker.rest, walker.frames, demoWalkerCapture(walker), offsetMm);
}

}  // namespace boneless
