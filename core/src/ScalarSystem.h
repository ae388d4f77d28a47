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
    ScalarSystem(int vertexCount, const Stencils& stencils,
                 const StencilPattern::Lumping* lumping = nullptr);

    // Terms added apart from the system's own values, on its pattern, for one thread of an
    // assembly split between threads; add(const Part&) adds them.
    class Part {
      public:
        explicit Part(const ScalarSystem& system)
            : pattern_(system.pattern_), values_(system.matrix_.nonZeros(), 0.0) {}
        void add(int residual, int a, int b, const Mat3& M) {
            accumulate(values_.data(), pattern_.entry(residual, a, b), traceTerm(M));
        }
        void addGram(int residual, int a, int b, const Mat3& P, const Mat3& Q) {
            accumulate(values_.data(), pattern_.entry(residual, a, b), gramTerm(P, Q));
        }

      private:
        friend class ScalarSystem;
        const StencilPattern& pattern_;
        std::vector<double> values_;
    };

    // H_ab += trace(M) / 3 for the a-th and b-th vertex of residual r's stencil.
    void add(int residual, int a, int b, const Mat3& M) {
        accumulate(matrix_.valuePtr(), pattern_.entry(residual, a, b), traceTerm(M));
    }
    // H_ab += trace(Pᵀ Q) / 3, without the product's other entries.
    void addGram(int residual, int a, int b, const Mat3& P, const Mat3& Q) {
        accumulate(matrix_.valuePtr(), pattern_.entry(residual, a, b), gramTerm(P, Q));
    }
    void addDiagonal(int v, const Mat3& M) {
        matrix_.valuePtr()[pattern_.diagonal(v)] += traceTerm(M);
    }
    void add(const Part& part);
    // Vertex v's row and column become the identity's.
    void pin(int v);
    double meanDiagonal() const;
    // The factorisation's symbolic part (its ordering and the factor's structure), which needs
    // only the pattern: it may run on another thread while add() calls fill the values
    // (koala's input in two blocks, each apart: 13–23 ms of analysis, 24–34 ms of numeric
    // factorisation). factorize() does it itself when it has not been done.
    void analyse();
    // Factorises H + tikhonov·I; false when it is not positive definite.
    bool factorize(double tikhonov);
    // Solves with the factor, for each column of rhs (#V by 3).
    Eigen::MatrixXd solve(const Eigen::MatrixXd& rhs) const;
    // Both triangles.
    const Eigen::SparseMatrix<double>& matrix() const { return matrix_; }

  private:
    // What a 3×3 block contributes to its one scalar entry.
    static double traceTerm(const Mat3& M) { return M.trace() / 3.0; }
    static double gramTerm(const Mat3& P, const Mat3& Q) { return P.cwiseProduct(Q).sum() / 3.0; }
    // A dropped pair's contribution x lands on the diagonal as |x|: with its mirror (b, a) that
    // adds [|x|, −x; −x, |x|], positive semidefinite whatever x's sign.
    static void accumulate(double* values, int entry, double x) {
        if (entry >= 0)
            values[entry] += x;
        else
            values[-1 - entry] += std::abs(x);
    }

    using Factor = Eigen::CholmodDecomposition<Eigen::SparseMatrix<double>, Eigen::Lower>;
    // Diagonal block k of the matrix, or of its pattern with zero values.
    Eigen::SparseMatrix<double> block(int k, bool values) const;
    std::unique_ptr<Factor> analysed(int k) const;

    StencilPattern pattern_;
    bool lumped_;
    Eigen::SparseMatrix<double> matrix_;
    // Per diagonal block (StencilPattern::blockStarts()), factorised and solved apart, on the
    // cores at once.
    struct Block {
        std::unique_ptr<Factor> factor;
        std::unique_ptr<Factor> symbolic;  // analyse()'s, until factorize() takes it
    };
    std::vector<Block> blocks_;
};

}  // namespace boneless
