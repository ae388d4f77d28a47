#include "DemoCapture.h"

namespace boneless {

DemoRecorder::DemoRecorder(const TriMesh& rest, DemoCapture capture, int frameCount,
                           double offsetMm)
    : capture_(std::move(capture)),
      topology_(rest),
      encoding_(rest, topology_),
      offset_(offsetMm / capture_.mmPerMeshUnit) {
    C3dTake& c3d = take.take;
    c3d.file = capture_.subject + ".c3d";
    c3d.rate = capture_.framesPerSecond;
    c3d.units = "mm";
    c3d.pointScale = -1.0;
    c3d.samples = C3dSamples(frameCount, static_cast<int>(capture_.markers.size()));
    take.map.meshFile = capture_.subject + ".obj";
    take.map.meshVertices = rest.vertexCount();
    for (const auto& [label, vertex] : capture_.markers) {
        C3dPoint p;
        p.label = capture_.subject + ":" + label;
        splitC3dLabel(p.label, p.subject, p.name);
        c3d.points.push_back(p);
        take.map.markers.push_back({label, vertex, offsetMm, "{}"});
    }
}

void DemoRecorder::record(int t, const Positions& pose) {
    const Mat3 R = Eigen::AngleAxisd(0.5 * 3.14159265358979323846, Vec3::UnitZ()).matrix();
    for (int k = 0; k < static_cast<int>(capture_.markers.size()); ++k) {
        const int v = capture_.markers[k].second;
        const Vec3 onSkin = pose.row(v).transpose();
        const Vec3 x = onSkin + offset_ * encoding_.ringNormal(v, pose);
        const Vec3 y = capture_.mmPerMeshUnit * (R * x) + capture_.shiftMm;
        take.take.samples.set(t, k, y.x(), y.y(), y.z(), 0.5f);
    }
    for (const DemoCapture::Gap& g : capture_.gaps)
        if (t >= g.first && t < g.end) take.take.samples.setMissing(t, g.marker);
}

DemoTake recordDemoTake(const TriMesh& rest, const std::vector<Positions>& frames,
                        DemoCapture capture, double offsetMm) {
    const int count = static_cast<int>(frames.size());
    DemoRecorder recorder(rest, std::move(capture), count, offsetMm);
    for (int t = 0; t < count; ++t) recorder.record(t, frames[t]);
    return std::move(recorder.take);
}

}  // namespace boneless
