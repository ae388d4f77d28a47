#pragma once

#include <Eigen/CholmodSupport>
#include <Eigen/Sparse>
#include <cmath>
#include <memory>
#include <vector>

#include "StencilPattern.h"
#include "boneless/ShapeEncoding.h"

namespace boneless {

// A Gauss–Newton matrix with each 3×3 block (a, b) replaced by its trace / 3: the average of its
// x, y and z couplings, positive definite when the block matrix is. Of the rest pose, factorised,
// it is the iterative method's preconditioner (see IterativeSolver). It takes the same add() calls
// as BlockSystem, so the one assembly fills either; a ninth of the entries makes it cheaper to
// build than the block matrix it stands for.
//
// Lumped (see StencilPattern::Lumping), it keeps the pairs that share an edge and moves the others
// onto the diagonal, each contribution as its absolute value, so that it is at least the full
// matrix (see accumulate()): positive definite when that is. Its factor is a quarter of the size
// (koala, 100K faces: 1.43M entries against 5.66M, factorised in 93 against 332 ms), and conjugate
// gradients on the full matrix take 13 steps to 1e-2 with it instead of 1; a bend frame's
// preconditioned solves came out cheaper overall. The dropped pairs are almost all positive (Σ_m
// w_ma w_mb between two neighbours a, b of a vertex m: 654,164 of 657,712 pairs' sums on koala), so
// what lumping adds is close to a graph Laplacian, nearly zero on the translations the energy
// cannot see; where a pair's contributions differ in sign (the fold guard's rotation coupling), it
// adds more. Dropped without it, the matrix was not positive definite; lumped with signs (row sums
// kept exactly), it was not either on the bench's 50K- and 200K-face meshes.
class ScalarSystem {
  public:
    // stencils[r] = the vertices residual r depends on, each at most once.
    ScalarSystem(int vertexCount, const std::vector<std::vector<int>>& stencils,
                 const StencilPattern::Lumping* lumping = nullptr);

    // H_ab += trace(M) / 3 for the a-th and b-th vertex of residual r's stencil.
    void add(int residual, int a, int b, const Mat3& M) {
        accumulate(pattern_.entry(residual, a, b), M.trace() / 3.0);
    }
    // H_ab += trace(Pᵀ Q) / 3, without the product's other entries.
    void addGram(int residual, int a, int b, const Mat3& P, const Mat3& Q) {
        accumulate(pattern_.entry(residual, a, b), P.cwiseProduct(Q).sum() / 3.0);
    }
    void addDiagonal(int v, const Mat3& M) {
        matrix_.valuePtr()[pattern_.diagonal(v)] += M.trace() / 3.0;
    }
    // Vertex v's row and column become the identity's.
    void pin(int v);
    double meanDiagonal() const;
    // Factorises H + tikhonov·I; false when it is not positive definite.
    bool factorize(double tikhonov);
    // Solves with the factor, for each column of rhs (#V by 3).
    Eigen::MatrixXd solve(const Eigen::MatrixXd& rhs) const { return factor_->solve(rhs); }
    // Both triangles.
    const Eigen::SparseMatrix<double>& matrix() const { return matrix_; }

  private:
    // A dropped pair's contribution x lands on the diagonal as |x|: with its mirror (b, a) that
    // adds [|x|, −x; −x, |x|], positive semidefinite whatever x's sign.
    void accumulate(int entry, double x) {
        if (entry >= 0)
            matrix_.valuePtr()[entry] += x;
        else
            matrix_.valuePtr()[-1 - entry] += std::abs(x);
    }

    StencilPattern pattern_;
    bool lumped_;
    Eigen::SparseMatrix<double> matrix_;
    std::unique_ptr<Eigen::CholmodDecomposition<Eigen::SparseMatrix<double>, Eigen::Lower>> factor_;
};

}  // namespace boneless
