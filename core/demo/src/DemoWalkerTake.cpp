#include <array>
#include <string>

#include "DemoWalker.h"
#include "boneless/MeshTopology.h"
#include "boneless/ShapeEncoding.h"

namespace boneless {

namespace {
constexpr double kMmPerMeshUnit = 1000.0;  // the walker is modelled in metres
}

DemoTake makeDemoWalkerTake(const DemoWalker& walker, double offsetMm) {
    const MeshTopology topology(walker.rest);
    const ShapeEncoding encoding(walker.rest, topology);
    const int K = static_cast<int>(walker.markerVertices.size());
    const int frames = static_cast<int>(walker.frames.size());

    DemoTake out;
    C3dTake& take = out.take;
    take.file = "walker.c3d";
    take.rate = walker.framesPerSecond;
    take.units = "mm";
    take.pointScale = -1.0;
    take.samples = C3dSamples(frames, K);
    out.map.meshFile = "walker.obj";
    out.map.meshVertices = walker.rest.vertexCount();
    for (const auto& [label, vertex] : walker.markerVertices) {
        C3dPoint p;
        p.label = "walker:" + label;
        splitC3dLabel(p.label, p.subject, p.name);
        take.points.push_back(p);
        out.map.markers.push_back({label, vertex, offsetMm, "{}"});
    }
    // The capture volume's axes are not the mesh's: a quarter turn about z and an offset.
    const Mat3 R = Eigen::AngleAxisd(0.5 * 3.14159265358979323846, Vec3::UnitZ()).matrix();
    const Vec3 shift(1200.0, -300.0, 0.0);
    const double offset = offsetMm / kMmPerMeshUnit;
    for (int t = 0; t < frames; ++t)
        for (int k = 0; k < K; ++k) {
            const int v = walker.markerVertices[k].second;
            const Vec3 onSkin = walker.frames[t].row(v).transpose();
            const Vec3 x = onSkin + offset * encoding.ringNormal(v, walker.frames[t]);
            const Vec3 y = kMmPerMeshUnit * (R * x) + shift;
            take.samples.set(t, k, y.x(), y.y(), y.z(), 0.5f);
        }
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
