#include "SparseCholesky.h"

#include <cholmod.h>

#include <cstring>

#include "boneless/Error.h"
#include "boneless/Parallel.h"

namespace boneless {

namespace {

// cholmod_solve2's workspace and answer, kept between solves so that none allocates; one per
// thread that solves.
struct Workspace {
    cholmod_common common;
    cholmod_dense *x = nullptr, *y = nullptr, *e = nullptr;
    Workspace() { cholmod_start(&common); }
    ~Workspace() {
        cholmod_free_dense(&x, &common);
        cholmod_free_dense(&y, &common);
        cholmod_free_dense(&e, &common);
        cholmod_finish(&common);
    }
    // X.col(first..first+count) = A⁻¹ B.col(...).
    void solve(cholmod_factor* factor, const Eigen::MatrixXd& B, int first, int count,
               Eigen::MatrixXd& X) {
        cholmod_dense b{};
        b.nrow = static_cast<size_t>(B.rows());
        b.ncol = static_cast<size_t>(count);
        b.nzmax = b.nrow * b.ncol;
        b.d = b.nrow;
        b.x = const_cast<double*>(B.col(first).data());
        b.xtype = CHOLMOD_REAL;
        b.dtype = CHOLMOD_DOUBLE;
        if (!cholmod_solve2(CHOLMOD_A, factor, &b, nullptr, &x, nullptr, &y, &e, &common))
            throw SolverError("a solve with the factorised system failed (out of memory?)");
        std::memcpy(X.col(first).data(), x->x, sizeof(double) * b.nzmax);
    }
};

}  // namespace

struct SparseCholesky::State {
    Workspace main, second;
    cholmod_factor* factor = nullptr;
    ~State() { cholmod_free_factor(&factor, &main.common); }
};

SparseCholesky::SparseCholesky() : state_(new State) {}
SparseCholesky::~SparseCholesky() {
    delete state_;
}

bool SparseCholesky::factorize(const Eigen::SparseMatrix<double>& A) {
    cholmod_common& c = state_->main.common;
    cholmod_free_factor(&state_->factor, &c);
    Eigen::SparseMatrix<double> lower = A.triangularView<Eigen::Lower>();
    lower.makeCompressed();
    cholmod_sparse view{};
    view.nrow = view.ncol = static_cast<size_t>(lower.rows());
    view.nzmax = static_cast<size_t>(lower.nonZeros());
    view.p = lower.outerIndexPtr();
    view.i = lower.innerIndexPtr();
    view.x = lower.valuePtr();
    view.stype = -1;  // the lower triangle holds the matrix
    view.itype = CHOLMOD_INT;
    view.xtype = CHOLMOD_REAL;
    view.dtype = CHOLMOD_DOUBLE;
    view.sorted = 1;
    view.packed = 1;
    // Simplicial LL' only: CHOLMOD's Supernodal module is GPL, its Cholesky module LGPL
    // (docs/licence.md). LL', not LDL', so that an indefinite matrix fails here.
    c.supernodal = CHOLMOD_SIMPLICIAL;
    c.final_asis = 0;
    c.final_ll = 1;
    state_->factor = cholmod_analyze(&view, &c);
    if (!state_->factor) return false;
    cholmod_factorize(&view, state_->factor, &c);
    if (c.status != CHOLMOD_OK || state_->factor->minor < state_->factor->n) return false;
    size_ = static_cast<int>(lower.rows());
    return c.status == CHOLMOD_OK;
}

Eigen::MatrixXd SparseCholesky::solve(const Eigen::MatrixXd& B) const {
    Eigen::MatrixXd X(B.rows(), B.cols());
    const int columns = static_cast<int>(B.cols());
    // The solve streams the factor from memory; a second core streaming it for the last column
    // at the same time shares the cache lines the first one fetches.
    if (columns >= 2 && size_ >= kSplitSize) {
        runOnWorkers(2, [&](int t) {
            if (t == 0)
                state_->main.solve(state_->factor, B, 0, columns - 1, X);
            else
                state_->second.solve(state_->factor, B, columns - 1, 1, X);
        });
    } else {
        state_->main.solve(state_->factor, B, 0, columns, X);
    }
    return X;
}

}  // namespace boneless
