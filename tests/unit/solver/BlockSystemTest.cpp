#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <random>

#include "BlockSystem.h"
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
