#include <gtest/gtest.h>

#include "TestMeshes.h"
#include "boneless/Metrics.h"

using namespace boneless;
using namespace boneless::testing;

TEST(Metrics, ErrorsOfAKnownDisplacement) {
    const TriMesh mesh = icosphere(1);
    Positions moved = mesh.V;
    moved(3, 0) += 0.3;
    moved(7, 1) -= 0.4;
    EXPECT_DOUBLE_EQ(maxVertexError(moved, mesh.V), 0.4);
    EXPECT_NEAR(rmsVertexError(moved, mesh.V), std::sqrt((0.09 + 0.16) / mesh.vertexCount()),
                1e-15);
    EXPECT_EQ(rmsVertexError(mesh.V, mesh.V), 0.0);
}

namespace {
// A flat n x n grid in the xy plane, faces facing +z.
TriMesh grid(int n) {
    TriMesh m;
    m.V.resize(n * n, 3);
    for (int i = 0; i < n; ++i)
        for (int j = 0; j < n; ++j) m.V.row(i * n + j) << j, i, 0;
    m.F.resize(2 * (n - 1) * (n - 1), 3);
    int f = 0;
    for (int i = 0; i + 1 < n; ++i)
        for (int j = 0; j + 1 < n; ++j) {
            const int a = i * n + j;
            m.F.row(f++) << a, a + 1, a + n + 1;
            m.F.row(f++) << a, a + n + 1, a + n;
        }
    return m;
}
}  // namespace

TEST(Metrics, FlippedFacesAreThoseFacingAgainstTheTruth) {
    const TriMesh mesh = grid(5);
    EXPECT_EQ(flippedFaceCount(mesh.F, mesh.V, mesh.V), 0);
    Positions mirrored = mesh.V;
    mirrored.col(0) *= -1;  // a mirror image turns every face of the sheet over
    EXPECT_EQ(flippedFaceCount(mesh.F, mirrored, mesh.V), mesh.faceCount());
    Positions dragged = mesh.V;
    dragged.row(12) << 3.5, 2.0, 0;  // the centre vertex dragged past its right neighbour
    const int flipped = flippedFaceCount(mesh.F, dragged, mesh.V);
    EXPECT_GE(flipped, 1);
    EXPECT_LE(flipped, 6);  // only its own fan can turn over
}

TEST(Metrics, EdgeLengthDistortionOfAUniformScale) {
    const TriMesh mesh = icosphere(1);
    EXPECT_NEAR(edgeLengthDistortion(mesh.F, 1.1 * mesh.V, mesh.V), 0.1, 1e-12);
}

TEST(Metrics, ATurnedMeshFoldsNothingAPinchedVertexFolds) {
    const TriMesh mesh = icosphere(2);
    // Upside down as a whole: every face's normal turned, none folded.
    const Eigen::Matrix3d R =
        Eigen::AngleAxisd(3.0, Eigen::Vector3d(1, 2, 3).normalized()).matrix();
    const Positions turned = (mesh.V * R.transpose()).eval();
    EXPECT_GT(flippedFaceCount(mesh.F, turned, mesh.V), 0);
    EXPECT_EQ(foldedFaceCount(mesh.F, turned, mesh.V), 0);
    // One vertex dragged across a neighbour, past its own ring: the faces it drags over fold.
    Positions pinched = turned;
    const int a = mesh.F(0, 0), b = mesh.F(0, 1);
    pinched.row(a) = 2.5 * turned.row(b) - 1.5 * turned.row(a);
    const int folded = foldedFaceCount(mesh.F, pinched, mesh.V);
    EXPECT_GE(folded, 1);
    EXPECT_LE(folded, 12);
}

// A sliver whose corners lie on a line up to rounding has no side: lifted off its line either way,
// it turns over nothing (the walker with a stray sliver reported "folded faces 1").
TEST(Metrics, AFaceWithNoAreaAtRestNeverFolds) {
    TriMesh mesh = icosphere(1);
    const int n = mesh.vertexCount();
    mesh.V.conservativeResize(n + 3, 3);
    const Vec3 start(5.1, 0.3, 0.7), step = Vec3(0.1, 0.2, 0.3) / 3.0;
    for (int i = 0; i < 3; ++i) mesh.V.row(n + i) = (start + i * step).transpose();
    mesh.F.conservativeResize(mesh.faceCount() + 1, 3);
    mesh.F.row(mesh.faceCount() - 1) << n, n + 1, n + 2;
    for (const double side : {-0.05, 0.05}) {
        Positions lifted = mesh.V;
        lifted.row(n + 1) += side * Vec3(1, -1, 0.3).normalized().transpose();
        EXPECT_EQ(foldedFaceCount(mesh.F, lifted, mesh.V), 0) << "lifted by " << side;
    }
}

TEST(Metrics, OnlyTheEdgesAlongAFoldAreBent) {
    const int n = 9;
    const TriMesh mesh = grid(n);
    const Eigen::Matrix3d R =
        Eigen::AngleAxisd(1.2, Eigen::Vector3d(2, -1, 0.5).normalized()).matrix();
    EXPECT_EQ(bentEdgeShare(mesh.F, (mesh.V * R.transpose()).eval(), mesh.V, 1.0), 0.0);

    // Fold the half x > 4 up about the line x = 4 by 30 degrees: the n − 1 edges on that line bend.
    Positions folded = mesh.V;
    const double angle = 30 * M_PI / 180;
    for (int v = 0; v < folded.rows(); ++v)
        if (mesh.V(v, 0) > 4) {
            const double d = mesh.V(v, 0) - 4;
            folded(v, 0) = 4 + d * std::cos(angle);
            folded(v, 2) = d * std::sin(angle);
        }
    const int interior = 3 * (n - 1) * (n - 1) - 2 * (n - 1);  // edges shared by two faces
    EXPECT_NEAR(bentEdgeShare(mesh.F, folded, mesh.V, 20), double(n - 1) / interior, 1e-12);
    EXPECT_EQ(bentEdgeShare(mesh.F, folded, mesh.V, 40), 0.0);
    // Folded the other way, the same edges bend by the same angle.
    Positions down = folded;
    down.col(2) *= -1;
    EXPECT_NEAR(bentEdgeShare(mesh.F, down, mesh.V, 20), double(n - 1) / interior, 1e-12);
    // A fold pushed through from +30 to −30 degrees bends its edges by 60 against the first.
    EXPECT_NEAR(bentEdgeShare(mesh.F, down, folded, 50), double(n - 1) / interior, 1e-12);
}
