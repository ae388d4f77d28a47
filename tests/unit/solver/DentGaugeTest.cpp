// The dent ratio (DentGauge) tells a dent of a marker's size from a gentle bend, and gives the
// same answer on a coarse and a fine mesh of the same surface.
#include <gtest/gtest.h>

#include <cmath>
#include <functional>

#include "boneless/DentGauge.h"
#include "boneless/MeshTopology.h"
#include "boneless/ShapeEncoding.h"

using namespace boneless;

namespace {

constexpr double kRadius = 0.25;  // the gauge's radius: a marker's patch

// A flat square sheet [-1, 1]² of n by n vertices.
TriMesh sheet(int n) {
    TriMesh m;
    m.V.resize(n * n, 3);
    for (int i = 0; i < n; ++i)
        for (int j = 0; j < n; ++j)
            m.V.row(i * n + j) << -1 + 2.0 * j / (n - 1), -1 + 2.0 * i / (n - 1), 0;
    m.F.resize(2 * (n - 1) * (n - 1), 3);
    int f = 0;
    for (int i = 0; i + 1 < n; ++i)
        for (int j = 0; j + 1 < n; ++j) {
            const int a = i * n + j, b = a + 1, c = a + n, d = c + 1;
            m.F.row(f++) << a, b, d;
            m.F.row(f++) << a, d, c;
        }
    return m;
}

// The worst ratio of one marker at the sheet's centre when the sheet is moved by `shape`.
double centreRatio(int n, const std::function<Vec3(const Vec3&)>& shape) {
    const TriMesh rest = sheet(n);
    const MeshTopology topology(rest);
    const ShapeEncoding encoding(rest, topology);
    SurfacePoint centre;
    centre.vertex = (n / 2) * n + n / 2;
    const DentGauge gauge(rest, topology, encoding, {centre}, kRadius);
    Positions V = rest.V;
    for (int v = 0; v < V.rows(); ++v) V.row(v) = shape(rest.V.row(v).transpose()).transpose();
    return gauge.worstRatio(V);
}

// Rolled onto a cylinder of radius R about the y axis.
std::function<Vec3(const Vec3&)> rolled(double R) {
    return [R](const Vec3& x) {
        return Vec3(R * std::sin(x.x() / R), x.y(), R * (1 - std::cos(x.x() / R)));
    };
}

// A dimple of the marker's size, `depth` deep, at the centre.
std::function<Vec3(const Vec3&)> dimpled(double depth) {
    return [depth](const Vec3& x) {
        const double s = std::min(1.0, x.head<2>().norm() / kRadius);
        return Vec3(x.x(), x.y(), -depth * (1 - s * s) * (1 - s * s));
    };
}

}  // namespace

TEST(DentGauge, ADimpleOfTheMarkersSizeInAFlatSheetIsADent) {
    for (int n : {21, 41}) EXPECT_GT(centreRatio(n, dimpled(0.3 * kRadius)), 2.0) << n;
}

TEST(DentGauge, AFlatSheetBentGentlyIsNoDentOnACoarseOrAFineMesh) {
    // A bend ten times wider than the marker's patch: a flank as the trunk bends.
    const double coarse = centreRatio(11, rolled(10 * kRadius));
    const double fine = centreRatio(41, rolled(10 * kRadius));
    EXPECT_LE(coarse, 1.0);
    EXPECT_LE(fine, 1.0);
    EXPECT_NEAR(coarse, fine, 0.25 * fine);
    // Rolled tightly, to the patch's own size, it is as curved as a dent.
    EXPECT_GT(centreRatio(41, rolled(kRadius)), 2.0);
}

TEST(DentGauge, ARigidMotionOfTheRestIsNoDent) {
    for (int n : {11, 41}) {
        const double atRest = centreRatio(n, [](const Vec3& x) { return x; });
        EXPECT_LE(atRest, 1.0);
        const Eigen::Matrix3d R =
            Eigen::AngleAxisd(0.7, Vec3(1, 2, 3).normalized()).toRotationMatrix();
        EXPECT_NEAR(centreRatio(n, [&](const Vec3& x) { return Vec3(R * x + Vec3(1, 2, 3)); }),
                    atRest, 1e-9);
    }
}
