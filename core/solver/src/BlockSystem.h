#pragma once

#include <Eigen/CholmodSupport>
#include <Eigen/Sparse>
#include <memory>
#include <vector>

#include "StencilPattern.h"
#include "boneless/ShapeEncoding.h"

namespace boneless {

// The Gauss–Newton normal matrix AᵀA over all vertices, with 3×3 blocks (plus, near a minimum,
// the fold guard's rotation coupling, which can make it indefinite). Its pattern (the 2-ring)
// is fixed by the stencils given once, so the symbolic analysis is done once; each iteration only
// fills values through precomputed slots and refactorises numerically.
class BlockSystem {
  public:
    // stencils[r] = the vertices residual r depends on, each at most once.
    BlockSystem(int vertexCount, const Stencils& stencils);

    void clear();
    // H_ab += M for the a-th and b-th vertex of residual r's stencil.
    void add(int residual, int a, int b, const Mat3& M) {
        const int* slot =
            slots_.data() + slotOffset_[residual] + 3 * (a * stencilSize(residual) + b);
        double* values = matrix_.valuePtr();
        for (int c = 0; c < 3; ++c)
            for (int row = 0; row < 3; ++row) values[slot[c] + row] += M(row, c);
    }
    // H_ab += Pᵀ Q (a Gauss–Newton product of two Jacobian blocks).
    void addGram(int residual, int a, int b, const Mat3& P, const Mat3& Q) {
        add(residual, a, b, P.transpose() * Q);
    }
    // H_vv += M (diagonal block, independent of any residual).
    void addDiagonal(int v, const Mat3& M);
    // Turns vertex v into a fixed one: its rows and columns become those of the identity.
    void pin(int v);
    // Factorises H + tikhonov·I; false when the matrix is not positive definite.
    bool factorize(double tikhonov);
    Eigen::VectorXd solve(const Eigen::VectorXd& rhs) const { return solver_->solve(rhs); }
    // Whether the last factorize() succeeded: its factor then stays usable after the values
    // change, as a preconditioner of the matrix they hold now.
    bool hasFactor() const { return factorValid_; }
    // Solves H x = rhs for the values held now (add the Tikhonov term first) by conjugate
    // gradients preconditioned with the last factor, which was made from an earlier H: the
    // next Gauss–Newton step's matrix, or the next frame's, is close to the last one, and a
    // factorisation costs as much as dozens of solves with it. False (x unspecified) when
    // |H x − rhs| has not reached tolerance·|rhs| within maxIterations, or H has shown a
    // direction of non-positive curvature.
    bool solveByLastFactor(const Eigen::VectorXd& rhs, Eigen::VectorXd& x, int maxIterations,
                           double tolerance, int* iterations = nullptr) const;
    // How many of those iterations cost about one numeric factorisation, from the symbolic
    // analysis' counts (so the same for every run on this matrix): the factorisation's flops
    // over an iteration's (a solve with the factor and a product with H), divided by the
    // measured advantage of the factorisation's dense kernels. 0 before the first factorize().
    int iterationsPerFactorization() const;
    // The iterations a solve with the last factor may take before a factorisation is made
    // instead: three quarters of one's cost, so that a failed try costs less than the
    // factorisation after it.
    int reuseAllowance() const { return iterationsPerFactorization() * 3 / 4; }
    // Below this allowance (small meshes, where factorising is cheap) the exact method does not
    // try the reuse.
    static constexpr int kMinimumReuseIterations = 4;
    // Adds tikhonov·I to the values (what factorize() does before factorising).
    void addToDiagonal(double tikhonov);
    double meanDiagonal() const;
    const Eigen::SparseMatrix<double>& matrix() const { return matrix_; }

  private:
    int stencilSize(int r) const { return stencilSizes_[r]; }

    Eigen::SparseMatrix<double> matrix_;
    // Simplicial: CHOLMOD's Supernodal module is GPL (docs/licence.md).
    using Factor = Eigen::CholmodSimplicialLLT<Eigen::SparseMatrix<double>, Eigen::Lower>;
    std::unique_ptr<Factor> solver_;  // made on the first factorize()
    bool factorValid_ = false;
    std::vector<int> stencilSizes_;
    std::vector<long> slotOffset_;
    std::vector<int> slots_;  // value index of the first row of each block column
    std::vector<int> diagonalSlots_;
};

}  // namespace boneless
