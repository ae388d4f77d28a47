#include "DemoTake.h"

#include <cstdio>

#include "boneless/MeshTopology.h"
#include "boneless/Sampling.h"
#include "boneless/ShapeEncoding.h"

namespace boneless {

namespace {
constexpr double kMmPerMeshUnit = 100.0;  // the creature is modelled in decimetres
}

DemoTake makeDemoTake(const DemoCreature& demo, int markerCount, double offsetMm) {
    const MeshTopology topology(demo.rest);
    const ShapeEncoding encoding(demo.rest, topology);
    const std::vector<int> vertices = geodesicFarthestPoints(demo.rest, markerCount, 0);
    const int K = static_cast<int>(vertices.size());
    const int frames = static_cast<int>(demo.frames.size());

    DemoTake out;
    C3dTake& take = out.take;
    take.file = "creature.c3d";
    take.rate = demo.framesPerSecond;
    take.units = "mm";
    take.pointScale = -1.0;
    take.samples = C3dSamples(frames, K);
    out.map.meshFile = "creature.obj";
    out.map.meshVertices = demo.rest.vertexCount();
    for (int k = 0; k < K; ++k) {
        char name[16];
        std::snprintf(name, sizeof name, "M%02d", k + 1);
        C3dPoint p;
        p.label = std::string("creature:") + name;
        splitC3dLabel(p.label, p.subject, p.name);
        take.points.push_back(p);
        out.map.markers.push_back({name, vertices[k], offsetMm, "{}"});
    }
    // The capture volume's axes are not the mesh's: a quarter turn about z and an offset.
    const Mat3 R = Eigen::AngleAxisd(0.5 * 3.14159265358979323846, Vec3::UnitZ()).matrix();
    const Vec3 shift(1200.0, -300.0, 50.0);
    const double offset = offsetMm / kMmPerMeshUnit;
    for (int t = 0; t < frames; ++t)
        for (int k = 0; k < K; ++k) {
            const int v = vertices[k];
            const Vec3 onSkin = demo.frames[t].row(v).transpose();
            const Vec3 x = onSkin + offset * encoding.ringNormal(v, demo.frames[t]);
            const Vec3 y = kMmPerMeshUnit * (R * x) + shift;
            take.samples.set(t, k, y.x(), y.y(), y.z(), 0.5f);
        }
    // Occlusions: three markers vanish for a while, as markers do.
    const int gaps[][3] = {{3, 20, 28}, {11, 35, 45}, {17, 5, 9}};
    for (const auto& g : gaps)
        for (int t = g[1]; t < g[2] && t < frames; ++t)
            if (g[0] < K) take.samples.setMissing(t, g[0]);
    return out;
}

}  // namespace boneless
