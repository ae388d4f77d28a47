#pragma once

#include <Eigen/Core>
#include <Eigen/SparseCore>

namespace boneless {

// A symmetric positive definite sparse matrix factorised once, then solved many times. CHOLMOD
// factorises it simplicially (LL'): only its LGPL modules, and the simplicial triangular solves
// are the faster ones for a few right-hand sides (docs/benchmarks.md).
class SparseCholesky {
  public:
    SparseCholesky();
    ~SparseCholesky();
    SparseCholesky(const SparseCholesky&) = delete;
    SparseCholesky& operator=(const SparseCholesky&) = delete;

    // A: symmetric, both triangles or the lower one. False when it is not positive definite.
    bool factorize(const Eigen::SparseMatrix<double>& A);
    // X = A⁻¹ B (B: n by any number of columns). Not for two threads at once.
    Eigen::MatrixXd solve(const Eigen::MatrixXd& B) const;
    int size() const { return size_; }

  private:
    static constexpr int kSplitSize = 4000;
    struct State;
    State* state_;
    int size_ = 0;
};

}  // namespace boneless
