#include <gtest/gtest.h>

#include <random>

#include "TestMeshes.h"
#include "boneless/MeshTopology.h"
#include "boneless/ShapeEncoding.h"

using namespace boneless;
using namespace boneless::testing;

namespace {

Vec3 combine(const std::vector<Vec3>& p, const std::vector<double>& w) {
    Vec3 x = Vec3::Zero();
    for (size_t k = 0; k < p.size(); ++k) x += w[k] * p[k];
    return x;
}

std::vector<double> weightsOf(const std::vector<Vec3>& p, const Vec3& x) {
    std::vector<double> w(p.size());
    meanValueWeights(p.data(), static_cast<int>(p.size()), x, Vec3::UnitZ(), w.data());
    return w;
}

}  // namespace

TEST(MeanValueWeights, ReproduceThePointInsideConvexAndNonConvexPolygons) {
    const std::vector<Vec3> square{{0, 0, 0}, {2, 0, 0}, {2, 2, 0}, {0, 2, 0}};
    const std::vector<Vec3> arrow{{0, 0, 0}, {4, 0, 0}, {1, 1, 0}, {4, 2, 0}, {0, 2, 0}};
    for (const Vec3& x : {Vec3(0.5, 0.7, 0), Vec3(1.9, 0.1, 0), Vec3(1, 1, 0)}) {
        auto w = weightsOf(square, x);
        EXPECT_LT((combine(square, w) - x).norm(), 1e-12);
    }
    // Inside the arrow's notch, inside the arrow but not in its kernel, and outside it entirely.
    for (const Vec3& x : {Vec3(0.5, 1, 0), Vec3(3, 0.3, 0), Vec3(3, 1, 0), Vec3(-1, 5, 0)}) {
        auto w = weightsOf(arrow, x);
        double sum = 0;
        for (double a : w) sum += a;
        EXPECT_NEAR(sum, 1.0, 1e-12);
        EXPECT_LT((combine(arrow, w) - x).norm(), 1e-10) << x.transpose();
    }
}

TEST(MeanValueWeights, AreInterpolatingOnVerticesAndEdges) {
    const std::vector<Vec3> square{{0, 0, 0}, {2, 0, 0}, {2, 2, 0}, {0, 2, 0}};
    auto w = weightsOf(square, {2, 2, 0});
    EXPECT_DOUBLE_EQ(w[2], 1.0);
    EXPECT_DOUBLE_EQ(w[0] + w[1] + w[3], 0.0);
    w = weightsOf(square, {2, 0.5, 0});  // on edge 1-2, a quarter of the way
    EXPECT_NEAR(w[1], 0.75, 1e-12);
    EXPECT_NEAR(w[2], 0.25, 1e-12);
    EXPECT_NEAR(w[0], 0.0, 1e-12);
}

TEST(MeanValueWeights, ArePositiveInsideAConvexPolygon) {
    const std::vector<Vec3> hexagon{{1, 0, 0},  {0.5, 0.9, 0},   {-0.5, 0.9, 0},
                                    {-1, 0, 0}, {-0.5, -0.9, 0}, {0.5, -0.9, 0}};
    auto w = weightsOf(hexagon, {0.2, -0.3, 0});
    for (double a : w) EXPECT_GT(a, 0.0);
}

TEST(ShapeEncoding, DecodesTheRestPoseExactly) {
    for (const TriMesh& mesh : {icosphere(2), tube(6, 10, 3.0)}) {
        MeshTopology topo(mesh);
        ShapeEncoding code(mesh, topo);
        ASSERT_EQ(code.encodedCount(), mesh.vertexCount());
        for (int v = 0; v < mesh.vertexCount(); ++v)
            EXPECT_LT((code.decode(v, mesh.V) - mesh.V.row(v).transpose()).norm(), 1e-12) << v;
    }
}

TEST(ShapeEncoding, IsInvariantUnderRigidMotion) {
    const TriMesh mesh = tube(5, 8, 2.0);
    MeshTopology topo(mesh);
    ShapeEncoding code(mesh, topo);
    std::mt19937 rng(7);
    const Mat3 R = randomRotation(rng);
    const Vec3 t(3, -1, 2);
    const Positions bentV = bent(mesh.V, 0.4);
    Positions moved(bentV.rows(), 3);
    for (int v = 0; v < bentV.rows(); ++v)
        moved.row(v) = (R * bentV.row(v).transpose() + t).transpose();
    for (int v = 0; v < mesh.vertexCount(); ++v) {
        const Vec3 expected = R * code.decode(v, bentV) + t;
        EXPECT_LT((code.decode(v, moved) - expected).norm(), 1e-12);
    }
}

TEST(ShapeEncoding, JacobianMatchesFiniteDifferences) {
    const TriMesh mesh = tube(5, 7, 2.0);  // interior and boundary rings
    MeshTopology topo(mesh);
    ShapeEncoding code(mesh, topo);
    Positions V = bent(mesh.V, 0.5);
    std::mt19937 rng(3);
    std::uniform_real_distribution<double> jitter(-0.05, 0.05);
    for (int i = 0; i < V.rows(); ++i)
        for (int c = 0; c < 3; ++c) V(i, c) += jitter(rng);
    const double h = 1e-6;
    double worst = 0;
    for (int v = 0; v < mesh.vertexCount(); ++v) {
        Vec3 F;
        std::vector<Mat3> J;
        ASSERT_TRUE(code.decodeWithJacobian(v, V, F, J));
        EXPECT_LT((F - code.decode(v, V)).norm(), 1e-14);
        Mat3 sum = Mat3::Zero();
        for (int k = 0; k < topo.valence(v); ++k) {
            sum += J[k];
            const int p = topo.ring(v)[k];
            for (int c = 0; c < 3; ++c) {
                Positions plus = V, minus = V;
                plus(p, c) += h;
                minus(p, c) -= h;
                const Vec3 fd = (code.decode(v, plus) - code.decode(v, minus)) / (2 * h);
                worst = std::max(worst, (fd - J[k].col(c)).norm());
            }
        }
        // Translating the whole ring translates F: the blocks sum to the identity.
        EXPECT_LT((sum - Mat3::Identity()).norm(), 1e-10);
    }
    EXPECT_LT(worst, 1e-7);
}

TEST(ShapeEncoding, RingNormalJacobianMatchesFiniteDifferences) {
    const TriMesh mesh = tube(5, 7, 2.0);
    MeshTopology topo(mesh);
    ShapeEncoding code(mesh, topo);
    const Positions V = bent(mesh.V, 0.4);
    const double h = 1e-6;
    for (int v : {3, 10, 17}) {
        std::vector<Mat3> dn;
        const Vec3 n = code.ringNormal(v, V, &dn);
        EXPECT_NEAR(n.norm(), 1.0, 1e-14);
        for (int k = 0; k < topo.valence(v); ++k)
            for (int c = 0; c < 3; ++c) {
                Positions plus = V, minus = V;
                plus(topo.ring(v)[k], c) += h;
                minus(topo.ring(v)[k], c) -= h;
                const Vec3 fd = (code.ringNormal(v, plus) - code.ringNormal(v, minus)) / (2 * h);
                EXPECT_LT((fd - dn[k].col(c)).norm(), 1e-7) << v << " " << k << " " << c;
            }
    }
}

TEST(ShapeEncoding, DegenerateRingsGiveNoResidualAndNoNaN) {
    TriMesh mesh = tube(4, 6, 1.0);
    // Collapse one vertex onto its neighbour: two faces get zero area.
    mesh.V.row(7) = mesh.V.row(8);
    // A fan whose ring has no area at all: all its neighbours on one line.
    MeshTopology topo(mesh);
    ShapeEncoding code(mesh, topo);
    for (int v = 0; v < mesh.vertexCount(); ++v) {
        EXPECT_TRUE(std::isfinite(code.height(v)));
        for (int k = 0; k < topo.valence(v); ++k) EXPECT_TRUE(std::isfinite(code.weights(v)[k]));
        if (code.encoded(v))
            EXPECT_LT((code.decode(v, mesh.V) - mesh.V.row(v).transpose()).norm(), 1e-9);
    }
}

TEST(MeshTopology, RingsFollowTheFaceOrientation) {
    const TriMesh mesh = icosphere(1);
    MeshTopology topo(mesh);
    for (int v = 0; v < mesh.vertexCount(); ++v) {
        ASSERT_GE(topo.valence(v), 5);
        EXPECT_FALSE(topo.isBoundary(v));
        Vec3 N = Vec3::Zero();
        for (int k = 0; k < topo.valence(v); ++k)
            N += mesh.V.row(topo.ring(v)[k])
                     .transpose()
                     .cross(mesh.V.row(topo.ring(v)[(k + 1) % topo.valence(v)]).transpose());
        EXPECT_GT(N.dot(mesh.V.row(v).transpose()), 0) << "ring of " << v << " is not outward";
    }
    const TriMesh open = tube(3, 6, 1.0);
    MeshTopology openTopo(open);
    EXPECT_EQ(openTopo.boundaryVertexCount(), 12);
    EXPECT_EQ(openTopo.valence(0), 4);  // a boundary vertex: 3 faces, 4 neighbours
}
