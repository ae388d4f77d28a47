#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <random>

#include "BlockSystem.h"
#include "ScalarSystem.h"
#include "TestMeshes.h"
#include "boneless/MeshTopology.h"

using namespace boneless;

namespace {

Mat3 randomMatrix(std::mt19937& rng) {
    std::normal_distribution<double> g;
    Mat3 M;
    for (int i = 0; i < 9; ++i) M(i / 3, i % 3) = g(rng);
    return M;
}

// A chain of overlapping 3-vertex stencils, each adding MᵀM (M random, so positive
// semidefinite) scaled by `scale`, plus a diagonal that makes the sum definite.
struct Chain {
    static constexpr int kVertices = 400;
    std::vector<std::vector<int>> stencils;
    std::vector<Eigen::MatrixXd> blocks;

    explicit Chain(unsigned seed) {
        std::mt19937 rng(seed);
        std::normal_distribution<double> g;
        for (int v = 0; v + 2 < kVertices; ++v) {
            stencils.push_back({v, v + 1, v + 2});
            Eigen::MatrixXd M(9, 9);
            for (int i = 0; i < 81; ++i) M(i / 9, i % 9) = g(rng);
            blocks.push_back(M.transpose() * M);
        }
    }
    // Adds Σ scale·MᵀM; every Chain has the same stencils, so the terms of two can be added.
    void add(BlockSystem& system, double scale) const {
        for (size_t r = 0; r < stencils.size(); ++r)
            for (int a = 0; a < 3; ++a)
                for (int b = 0; b < 3; ++b)
                    system.add(static_cast<int>(r), a, b,
                               scale * blocks[r].block<3, 3>(3 * a, 3 * b));
    }
    void fill(BlockSystem& system, double scale, double diagonal) const {
        system.clear();
        add(system, scale);
        system.addToDiagonal(diagonal);
    }
};

Eigen::VectorXd randomVector(int n, unsigned seed) {
    std::mt19937 rng(seed);
    std::normal_distribution<double> g;
    Eigen::VectorXd b(n);
    for (int i = 0; i < n; ++i) b[i] = g(rng);
    return b;
}

}  // namespace

TEST(BlockSystem, AnEarlierFactorSolvesANearbyMatrixToTheAskedResidual) {
    const Chain chain(1), change(2);
    BlockSystem system(Chain::kVertices, chain.stencils);
    EXPECT_FALSE(system.hasFactor());
    EXPECT_EQ(system.iterationsPerFactorization(), 0);
    chain.fill(system, 1.0, 0.5);
    ASSERT_TRUE(system.factorize(0));
    EXPECT_TRUE(system.hasFactor());

    // The next matrix: the same terms, 10 % stronger, and a different 10 % added.
    BlockSystem fresh(Chain::kVertices, chain.stencils);
    auto fillNext = [&](BlockSystem& s) {
        chain.fill(s, 1.1, 0.5);
        change.add(s, 0.1);
    };
    fillNext(system);
    fillNext(fresh);
    ASSERT_TRUE(fresh.factorize(0));
    const Eigen::VectorXd b = randomVector(3 * Chain::kVertices, 3);
    Eigen::VectorXd x;
    int iterations = -1;
    ASSERT_TRUE(system.solveByLastFactor(b, x, 100, 1e-10, &iterations));
    EXPECT_GT(iterations, 1);
    EXPECT_LE((system.matrix() * x - b).norm(), 1e-10 * b.norm());
    const Eigen::VectorXd expected = fresh.solve(b);
    EXPECT_LE((x - expected).norm(), 1e-6 * expected.norm());
    // Too few iterations for that tolerance: refused, not a half-solved answer.
    EXPECT_FALSE(system.solveByLastFactor(b, x, 1, 1e-10));
}

TEST(BlockSystem, AnIndefiniteMatrixIsRefusedAndAFailedFactorisationLeavesNoFactor) {
    const Chain chain(4);
    BlockSystem system(Chain::kVertices, chain.stencils);
    chain.fill(system, 1.0, 0.5);
    ASSERT_TRUE(system.factorize(0));
    // Far negative: every direction has negative curvature.
    chain.fill(system, -1.0, -0.5);
    Eigen::VectorXd x;
    EXPECT_FALSE(system.solveByLastFactor(randomVector(3 * Chain::kVertices, 5), x, 50, 1e-8));
    EXPECT_FALSE(system.factorize(0));
    EXPECT_FALSE(system.hasFactor());
    EXPECT_FALSE(system.solveByLastFactor(randomVector(3 * Chain::kVertices, 6), x, 50, 1e-8));
}

TEST(BlockSystem, AFarMatrixIsGivenUpEarlyAndAZeroRightHandSideNeedsNoIteration) {
    const Chain chain(7), other(8);
    BlockSystem system(Chain::kVertices, chain.stencils);
    chain.fill(system, 1.0, 0.5);
    ASSERT_TRUE(system.factorize(0));
    // Nothing like the factor's matrix: far more than the allowance would be needed, and the
    // rate after the first iterations says so.
    other.fill(system, 1.0, 1e-3);
    chain.add(system, 1e-3);
    Eigen::VectorXd x;
    int iterations = -1;
    EXPECT_FALSE(
        system.solveByLastFactor(randomVector(3 * Chain::kVertices, 9), x, 40, 1e-12, &iterations));
    EXPECT_GE(iterations, 5);
    EXPECT_LT(iterations, 40);
    EXPECT_TRUE(system.solveByLastFactor(Eigen::VectorXd::Zero(3 * Chain::kVertices), x, 40, 1e-12,
                                         &iterations));
    EXPECT_EQ(iterations, 0);
    EXPECT_EQ(x.norm(), 0.0);
}

// The scalar preconditioner's matrix is each block's trace / 3, taken from the same add() calls
// (and addGram()'s PᵀQ without the product); a pinned vertex's row and column are the identity's.
TEST(ScalarSystem, HoldsTheTraceOverThreeOfEachBlock) {
    // Stencils of different sizes that overlap irregularly, as a mesh's rings do.
    const int n = 40;
    std::vector<std::vector<int>> stencils;
    for (int v = 0; v + 5 < n; ++v) stencils.push_back({v, v + 1, v + 3, v + 5});
    for (int v = 0; v + 2 < n; v += 3) stencils.push_back({v + 2, v});
    BlockSystem blocks(n, stencils);
    ScalarSystem scalar(n, stencils);
    blocks.clear();
    std::mt19937 rng(7);
    auto random = [&] { return randomMatrix(rng); };
    for (size_t r = 0; r < stencils.size(); ++r) {
        const int m = static_cast<int>(stencils[r].size());
        for (int a = 0; a < m; ++a)
            for (int b = 0; b < m; ++b) {
                const Mat3 M = random(), P = random(), Q = random();
                const int rr = static_cast<int>(r);
                blocks.add(rr, a, b, M);
                scalar.add(rr, a, b, M);
                blocks.addGram(rr, a, b, P, Q);
                scalar.addGram(rr, a, b, P, Q);
            }
    }
    const Mat3 D = random();
    blocks.addDiagonal(4, D);
    scalar.addDiagonal(4, D);
    blocks.pin(9);
    scalar.pin(9);
    const Eigen::MatrixXd H(blocks.matrix());
    const Eigen::MatrixXd S(scalar.matrix());
    ASSERT_EQ(S.rows(), n);
    for (int a = 0; a < n; ++a)
        for (int b = 0; b < n; ++b)
            EXPECT_NEAR(S(a, b), (H.block<3, 3>(3 * a, 3 * b).trace() / 3.0), 1e-12)
                << "(" << a << ", " << b << ")";
    EXPECT_EQ(S(9, 9), 1.0);
    EXPECT_EQ(S.row(9).cwiseAbs().sum(), 1.0);
    EXPECT_NEAR(scalar.meanDiagonal(), blocks.meanDiagonal(), 1e-12);
    // The same pattern: a pair no stencil holds stays zero in both.
    EXPECT_EQ(S(0, 39), 0.0);
    EXPECT_EQ(scalar.matrix().nonZeros() * 9, blocks.matrix().nonZeros());
}

// Lumped, the scalar matrix keeps the pairs that share an edge; every other pair's value moves to
// its column's diagonal, each contribution as its absolute value, so that the lumped matrix is at
// least the full one; a fixed vertex takes its own pairs' values with it when it is pinned.
TEST(ScalarSystem, LumpedKeepsTheEdgesAndIsAtLeastTheFullMatrix) {
    const TriMesh mesh = boneless::testing::icosphere(1);
    const MeshTopology topology(mesh);
    const int n = mesh.vertexCount();
    std::vector<std::vector<int>> stencils;
    for (int v = 0; v < n; ++v) {
        std::vector<int> s{v};
        s.insert(s.end(), topology.ring(v), topology.ring(v) + topology.valence(v));
        stencils.push_back(s);
    }
    for (int f = 0; f < mesh.faceCount(); ++f)
        stencils.push_back({mesh.F(f, 0), mesh.F(f, 1), mesh.F(f, 2)});
    const int fixedVertex = 5;
    std::vector<char> fixed(n, 0);
    fixed[fixedVertex] = 1;
    const StencilPattern::Lumping lumping{topology, fixed};
    BlockSystem blocks(n, stencils);
    ScalarSystem lumped(n, stencils, &lumping);
    blocks.clear();
    std::mt19937 rng(11);
    auto random = [&] { return randomMatrix(rng); };
    auto adjacent = [&](int a, int b) {
        const int* ring = topology.ring(a);
        return std::find(ring, ring + topology.valence(a), b) != ring + topology.valence(a);
    };
    Eigen::VectorXd lumpedOnto = Eigen::VectorXd::Zero(n);  // Σ |x| per column's diagonal
    auto lump = [&](int r, int a, int b, double x) {
        const int u = stencils[r][a], v = stencils[r][b];
        if (u != v && !adjacent(u, v) && !fixed[u]) lumpedOnto[v] += std::abs(x);
    };
    for (size_t r = 0; r < stencils.size(); ++r) {
        const int m = static_cast<int>(stencils[r].size());
        const int rr = static_cast<int>(r);
        for (int a = 0; a < m; ++a)
            for (int b = a; b < m; ++b) {  // symmetric, as a Gauss–Newton matrix is
                const Mat3 M = random(), P = random(), Q = random();
                auto fill = [&](auto& s) {
                    s.add(rr, a, b, M);
                    s.addGram(rr, a, b, P, Q);
                    if (a == b) return;
                    s.add(rr, b, a, Mat3(M.transpose()));
                    s.addGram(rr, b, a, Q, P);
                };
                fill(blocks);
                fill(lumped);
                const double m3 = M.trace() / 3.0, pq = P.cwiseProduct(Q).sum() / 3.0;
                for (auto [i, j] : {std::pair{a, b}, std::pair{b, a}}) {
                    lump(rr, i, j, m3);
                    lump(rr, i, j, pq);
                    if (a == b) break;
                }
            }
    }
    blocks.pin(fixedVertex);
    lumped.pin(fixedVertex);
    const Eigen::MatrixXd H(blocks.matrix());
    Eigen::MatrixXd full(n, n);
    for (int a = 0; a < n; ++a)
        for (int b = 0; b < n; ++b) full(a, b) = H.block<3, 3>(3 * a, 3 * b).trace() / 3.0;
    const Eigen::MatrixXd S(lumped.matrix());
    int dropped = 0;
    for (int a = 0; a < n; ++a)
        for (int b = 0; b < n; ++b) {
            if (a == b) continue;
            if (adjacent(a, b))
                EXPECT_NEAR(S(a, b), full(a, b), 1e-12) << "(" << a << ", " << b << ")";
            else
                EXPECT_EQ(S(a, b), 0.0) << "(" << a << ", " << b << ")";
            if (!adjacent(a, b) && full(a, b) != 0) ++dropped;
        }
    EXPECT_GT(dropped, n);  // the 2-ring pairs: there is something to lump
    for (int v = 0; v < n; ++v) {
        if (v == fixedVertex) continue;
        EXPECT_GT(lumpedOnto[v], 0.0) << v;
        EXPECT_NEAR(S(v, v), full(v, v) + lumpedOnto[v], 1e-10) << v;
    }
    // What lumping added is positive semidefinite, whatever the dropped values' signs.
    const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> added(S - full);
    EXPECT_GE(added.eigenvalues().minCoeff(), -1e-10);
    EXPECT_GT(added.eigenvalues().maxCoeff(), 0.0);
    EXPECT_EQ(S(fixedVertex, fixedVertex), 1.0);
    EXPECT_EQ(S.row(fixedVertex).cwiseAbs().sum(), 1.0);
    EXPECT_EQ(S.col(fixedVertex).cwiseAbs().sum(), 1.0);
    EXPECT_EQ(lumped.matrix().nonZeros(), n + static_cast<long>(topology.neighbours().size()));
}

// Cut into diagonal blocks (ranges of vertices), the lumped matrix also lumps the pairs between
// blocks, so that it stays at least the unblocked one; each block is factorised and solved apart
// (on the cores at once), and together they solve the whole matrix. Terms added through a Part
// (another thread's share of an assembly) count as if added directly.
TEST(ScalarSystem, LumpedBlocksAreSolvedApartAndStayAtLeastTheUnblockedMatrix) {
    const TriMesh mesh = boneless::testing::icosphere(2);
    const MeshTopology topology(mesh);
    const int n = mesh.vertexCount(), half = n / 2;
    std::vector<std::vector<int>> stencils;
    for (int v = 0; v < n; ++v) {
        std::vector<int> s{v};
        s.insert(s.end(), topology.ring(v), topology.ring(v) + topology.valence(v));
        stencils.push_back(s);
    }
    const std::vector<char> fixed(n, 0);
    const StencilPattern::Lumping whole{topology, fixed};
    const StencilPattern::Lumping cut{topology, fixed, {0, half, n}};
    ScalarSystem unblocked(n, stencils, &whole), blocked(n, stencils, &cut),
        inParts(n, stencils, &cut);
    ScalarSystem::Part part(inParts);
    std::mt19937 rng(5);
    // A Gauss–Newton matrix: per stencil, JᵀJ of random Jacobian blocks, plus the identity.
    for (size_t r = 0; r < stencils.size(); ++r) {
        const int m = static_cast<int>(stencils[r].size()), rr = static_cast<int>(r);
        std::vector<Mat3> J(m);
        for (auto& block : J) block = randomMatrix(rng);
        for (int a = 0; a < m; ++a)
            for (int b = 0; b < m; ++b) {
                unblocked.addGram(rr, a, b, J[a], J[b]);
                blocked.addGram(rr, a, b, J[a], J[b]);
                if (r % 2)
                    part.addGram(rr, a, b, J[a], J[b]);
                else
                    inParts.addGram(rr, a, b, J[a], J[b]);
            }
    }
    inParts.add(part);
    for (int v = 0; v < n; ++v)
        for (ScalarSystem* s : {&unblocked, &blocked, &inParts})
            s->addDiagonal(v, Mat3::Identity());

    const Eigen::MatrixXd U(unblocked.matrix()), B(blocked.matrix()), P(inParts.matrix());
    int crossing = 0;
    for (int a = 0; a < n; ++a)
        for (int b = 0; b < n; ++b) {
            EXPECT_NEAR(P(a, b), B(a, b), 1e-12 * B.cwiseAbs().maxCoeff());
            if ((a < half) == (b < half)) continue;
            EXPECT_EQ(B(a, b), 0.0) << "(" << a << ", " << b << ")";
            if (U(a, b) != 0) ++crossing;
        }
    EXPECT_GT(crossing, 0);  // the cut goes through edges: there is something to lump
    const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> added(B - U);
    EXPECT_GE(added.eigenvalues().minCoeff(), -1e-10 * B.cwiseAbs().maxCoeff());

    const Eigen::MatrixXd rhs = Eigen::MatrixXd::Random(n, 3);
    const Eigen::MatrixXd expected = B.llt().solve(rhs);
    inParts.analyse();  // the analysis ahead, as the rest system makes it
    ASSERT_TRUE(blocked.factorize(0.0));
    ASSERT_TRUE(inParts.factorize(0.0));
    EXPECT_LT((blocked.solve(rhs) - expected).norm(), 1e-10 * expected.norm());
    EXPECT_LT((inParts.solve(rhs) - expected).norm(), 1e-10 * expected.norm());
}
