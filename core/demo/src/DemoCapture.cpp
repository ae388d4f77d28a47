#include "DemoCapture.h"

#include "boneless/MeshTopology.h"
#include "boneless/ShapeEncoding.h"

namespace boneless {

DemoTake recordDemoTake(const TriMesh& rest, const std::vector<Positions>& frames,
                        double framesPerSecond, const std::string& subject,
                        const std::vector<std::pair<std::string, int>>& markers,
                        double mmPerMeshUnit, double offsetMm, const Vec3& shiftMm) {
    const MeshTopology topology(rest);
    const ShapeEncoding encoding(rest, topology);
    const int K = static_cast<int>(markers.size());
    const int frameCount = static_cast<int>(frames.size());

    DemoTake out;
    C3dTake& take = out.take;
    take.file = subject + ".c3d";
    take.rate = framesPerSecond;
    take.units = "mm";
    take.pointScale = -1.0;
    take.samples = C3dSamples(frameCount, K);
    out.map.meshFile = subject + ".obj";
    out.map.meshVertices = rest.vertexCount();
    for (const auto& [label, vertex] : markers) {
        C3dPoint p;
        p.label = subject + ":" + label;
        splitC3dLabel(p.label, p.subject, p.name);
        take.points.push_back(p);
        out.map.markers.push_back({label, vertex, offsetMm, "{}"});
    }
    const Mat3 R = Eigen::AngleAxisd(0.5 * 3.14159265358979323846, Vec3::UnitZ()).matrix();
    const double offset = offsetMm / mmPerMeshUnit;
    for (int t = 0; t < frameCount; ++t)
        for (int k = 0; k < K; ++k) {
            const int v = markers[k].second;
            const Vec3 onSkin = frames[t].row(v).transpose();
            const Vec3 x = onSkin + offset * encoding.ringNormal(v, frames[t]);
            const Vec3 y = mmPerMeshUnit * (R * x) + shiftMm;
            take.samples.set(t, k, y.x(), y.y(), y.z(), 0.5f);
        }
    return out;
}

}  // namespace boneless
