#include <gtest/gtest.h>

#include <random>

#include "TestMeshes.h"
#include "boneless/Alignment.h"
#include "boneless/C3dTake.h"
#include "boneless/Error.h"

using namespace boneless;
using namespace boneless::testing;

TEST(Alignment, RecoversAKnownSimilarity) {
    std::mt19937 rng(2);
    std::uniform_real_distribution<double> u(-1, 1);
    Positions mesh(8, 3);
    for (int i = 0; i < 8; ++i) mesh.row(i) << u(rng), u(rng), u(rng);
    // The take: millimetres, another orientation, another origin.
    const Mat3 R = randomRotation(rng);
    Positions take(8, 3);
    const Vec3 origin(500, -200, 30);
    for (int i = 0; i < 8; ++i)
        take.row(i) = (1000.0 * R * mesh.row(i).transpose() + origin).transpose();
    take.row(3).setConstant(std::nan(""));  // a missing marker is skipped, not used
    const Similarity s = fitSimilarity(take, mesh);
    EXPECT_NEAR(s.scale, 1e-3, 1e-12);
    EXPECT_LT((s.R - R.transpose()).norm(), 1e-9);
    EXPECT_LT((s.apply(origin) - Vec3::Zero()).norm(), 1e-9);
    EXPECT_LT(alignmentResidual(s, take, mesh), 1e-9);
}

TEST(Alignment, RefusesTooFewOrCollinearMarkers) {
    Positions a(3, 3), b(3, 3);
    a << 0, 0, 0, 1, 0, 0, 2, 0, 0;
    b = a;
    EXPECT_THROW(fitSimilarity(a, b), Error);
    EXPECT_THROW(fitSimilarity(a.topRows(2), b.topRows(2)), Error);
}

TEST(Alignment, CalibrationPicksTheFrameClosestToTheRestPose) {
    const TriMesh mesh = icosphere(1);
    const std::vector<int> ids{0, 5, 9, 11, 20, 33};
    const Positions rest = rows(mesh.V, ids);
    C3dTake take;
    take.file = "synthetic.c3d";
    take.points.resize(ids.size());
    take.samples = C3dSamples(5, ids.size());
    std::mt19937 rng(4);
    for (int f = 0; f < 5; ++f)
        for (size_t k = 0; k < ids.size(); ++k) {
            // Frame 3 is a scaled, moved copy of the rest pose; the others are squashed.
            const double squash = (f == 3) ? 1.0 : 0.7;
            const Vec3 p = rest.row(k).transpose();
            take.samples.set(f, k, 10 * p.x() + 1, 10 * p.y() * squash, 10 * p.z() + f);
        }
    take.samples.setMissing(1, 2);
    std::vector<std::size_t> points(ids.size());
    for (size_t k = 0; k < points.size(); ++k) points[k] = k;
    const Calibration c = calibrate(take, points, rest);
    EXPECT_EQ(c.frame, 3);
    EXPECT_NEAR(c.takeToMesh.scale, 0.1, 1e-12);
    EXPECT_LT(c.residual, 1e-9);
    EXPECT_EQ(c.visibleMarkers, 6);
}
