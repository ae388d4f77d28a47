// The fold guard's exact Hessian, as the exact method assembles it, against finite differences of
// its gradient.
#include <gtest/gtest.h>

#include <random>

#include "ArapEnergy.h"
#include "TestMeshes.h"

namespace boneless::testing {
namespace {

// min over R of E(V, R), differentiated with the rotations refitted: 2 (3 L V − b(R(V))).
Eigen::VectorXd gradient(const ArapEnergy& arap, const Positions& V) {
    std::vector<Mat3> R;
    arap.fitRotations(V, R);
    const Eigen::MatrixXd g = 2.0 * (3.0 * (arap.laplacian() * V) - arap.rotatedRestEdges(R));
    Eigen::VectorXd flat(3 * V.rows());
    for (int v = 0; v < V.rows(); ++v) flat.segment<3>(3 * v) = g.row(v).transpose();
    return flat;
}

Positions displaced(const Positions& V, const Eigen::VectorXd& x, double h) {
    Positions out = V;
    for (int v = 0; v < V.rows(); ++v) out.row(v) += h * x.segment<3>(3 * v).transpose();
    return out;
}

struct PosedTube {
    TriMesh rest = tube(8, 12, 4.0);
    Positions V;
    Eigen::VectorXd x;
    PosedTube() {
        // Bent, then jittered, so that every vertex's rotation is its own and not a rest one.
        std::mt19937 rng(7);
        std::normal_distribution<double> noise(0.0, 0.05);
        V = bent(rest.V, 0.6);
        for (int i = 0; i < V.size(); ++i) V.data()[i] += noise(rng);
        x.resize(3 * V.rows());
        for (int i = 0; i < x.size(); ++i) x[i] = noise(rng) * 20;
    }
};

}  // namespace

TEST(ArapEnergy, ExactHessianMatchesFiniteDifferencesOfTheGradient) {
    PosedTube t;
    ArapEnergy arap(t.rest);
    std::vector<Mat3> R, C;
    arap.fitRotations(t.V, R, false, &C);

    const double h = 1e-6;
    const Eigen::VectorXd numeric =
        (gradient(arap, displaced(t.V, t.x, h)) - gradient(arap, displaced(t.V, t.x, -h))) /
        (2 * h);
    Eigen::VectorXd fixedRotations(t.x.size());
    for (int v = 0; v < t.V.rows(); ++v) {
        Vec3 sum = Vec3::Zero();
        for (Eigen::SparseMatrix<double>::InnerIterator it(arap.laplacian(), v); it; ++it)
            sum += it.value() * t.x.segment<3>(3 * it.row());
        fixedRotations.segment<3>(3 * v) = 6.0 * sum;
    }
    // The rotations' coupling, −2 Σ_v G_vᵀ C_v G_v, from the blocks the exact method assembles.
    Eigen::VectorXd exact = fixedRotations;
    std::vector<std::pair<int, Mat3>> blocks;
    for (int v = 0; v < t.V.rows(); ++v) {
        arap.couplingBlocks(v, R[v], blocks);
        Vec3 Gx = Vec3::Zero();
        for (const auto& [u, G] : blocks) Gx += G * t.x.segment<3>(3 * u);
        const Vec3 CGx = C[v] * Gx;
        for (const auto& [u, G] : blocks) exact.segment<3>(3 * u) -= 2.0 * G.transpose() * CGx;
    }

    const double scale = numeric.norm();
    EXPECT_LE((exact - numeric).norm(), 1e-5 * scale);
    // The coupling is what makes it exact: without it the bend is visibly off.
    EXPECT_GE((fixedRotations - numeric).norm(), 1e-2 * scale);
}

}  // namespace boneless::testing

namespace boneless::testing {

// The Laplacian is laid out from the corners (no triplet list): each entry must be the sum of the
// same terms in the same order as the triplets' (a bit's difference moves every frame's answer),
// with no column for a vertex in no face and an entry for a zero-area face's pairs.
TEST(ArapEnergy, TheLaplacianIsTheCotangentTripletsSummedInFaceOrder) {
    TriMesh mesh = tube(7, 9, 3.0);
    std::mt19937 rng(3);
    std::normal_distribution<double> noise(0.0, 0.03);
    for (int i = 0; i < mesh.V.size(); ++i) mesh.V.data()[i] += noise(rng);
    const int isolated = mesh.vertexCount();
    mesh.V.conservativeResize(isolated + 1, 3);
    mesh.V.row(isolated) = Vec3(9, 9, 9).transpose();
    // A flat face on three existing vertices: its cotangents are zero, its pairs still entries.
    mesh.F.conservativeResize(mesh.faceCount() + 1, 3);
    mesh.F.row(mesh.faceCount() - 1) << 0, 0, 1;
    const ArapEnergy arap(mesh);

    std::vector<Eigen::Triplet<double>> t;
    for (int f = 0; f < mesh.faceCount(); ++f)
        for (int c = 0; c < 3; ++c) {
            const int j = mesh.F(f, (c + 1) % 3), k = mesh.F(f, (c + 2) % 3);
            const double w = arap.cotangent(f, c);
            t.emplace_back(j, j, w);
            t.emplace_back(k, k, w);
            t.emplace_back(j, k, -w);
            t.emplace_back(k, j, -w);
        }
    Eigen::SparseMatrix<double> expected(mesh.vertexCount(), mesh.vertexCount());
    expected.setFromTriplets(t.begin(), t.end());

    const Eigen::SparseMatrix<double>& L = arap.laplacian();
    ASSERT_EQ(L.nonZeros(), expected.nonZeros());
    EXPECT_EQ(L.col(isolated).nonZeros(), 0);
    for (int col = 0; col < L.outerSize(); ++col) {
        Eigen::SparseMatrix<double>::InnerIterator a(L, col), b(expected, col);
        for (; a && b; ++a, ++b) {
            EXPECT_EQ(a.row(), b.row()) << "column " << col;
            EXPECT_EQ(a.value(), b.value()) << "(" << a.row() << ", " << col << ")";
        }
        EXPECT_FALSE(a || b) << "column " << col;
    }
}

}  // namespace boneless::testing
