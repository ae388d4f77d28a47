#include "BlockSystem.h"

#include <algorithm>
#include <cmath>

#include "StencilPattern.h"
#include "boneless/Parallel.h"

namespace boneless {

namespace {
// Iterations after which solveByLastFactor() judges from its rate whether it will converge.
constexpr int kRateIterations = 5;
}  // namespace

BlockSystem::BlockSystem(int vertexCount, const Stencils& stencils) {
    // Each pair of the pattern becomes a 3×3 block: column 3b+c holds, for every row vertex a of
    // the pattern's column b, the rows 3a, 3a+1, 3a+2.
    const StencilPattern pattern(vertexCount, stencils);
    const std::vector<int>& columnStart = pattern.outer();
    const int n = 3 * vertexCount;
    std::vector<int> outer(n + 1, 0);
    for (int b = 0; b < vertexCount; ++b) {
        const int count = columnStart[b + 1] - columnStart[b];
        for (int c = 0; c < 3; ++c) outer[3 * b + c] = 9 * columnStart[b] + 3 * c * count;
    }
    outer[n] = 9 * columnStart[vertexCount];
    matrix_.resize(n, n);
    matrix_.resizeNonZeros(outer[n]);
    std::copy(outer.begin(), outer.end(), matrix_.outerIndexPtr());
    int* inner = matrix_.innerIndexPtr();
    for (int b = 0; b < vertexCount; ++b)
        for (int c = 0; c < 3; ++c) {
            int at = outer[3 * b + c];
            for (int e = columnStart[b]; e < columnStart[b + 1]; ++e)
                for (int row = 0; row < 3; ++row) inner[at++] = 3 * pattern.inner()[e] + row;
        }

    const int stencilCount = pattern.stencilCount();
    stencilSizes_.resize(stencilCount);
    slotOffset_.assign(stencilCount + 1, 0);
    for (int r = 0; r < stencilCount; ++r) {
        const long m = pattern.stencilSize(r);
        stencilSizes_[r] = static_cast<int>(m);
        slotOffset_[r + 1] = slotOffset_[r] + 3 * m * m;
    }
    slots_.resize(slotOffset_.back());
    for (int r = 0; r < stencilCount; ++r) {
        const int* s = stencils[r];
        const int m = stencilSizes_[r];
        for (int i = 0; i < m; ++i)
            for (int j = 0; j < m; ++j) {
                const int pos = pattern.entry(r, i, j) - columnStart[s[j]];
                for (int c = 0; c < 3; ++c)
                    slots_[slotOffset_[r] + 3 * (i * m + j) + c] = outer[3 * s[j] + c] + 3 * pos;
            }
    }
    diagonalSlots_.resize(vertexCount);
    for (int v = 0; v < vertexCount; ++v) diagonalSlots_[v] = pattern.diagonal(v) - columnStart[v];
}

void BlockSystem::clear() {
    std::fill_n(matrix_.valuePtr(), matrix_.nonZeros(), 0.0);
}

void BlockSystem::addDiagonal(int v, const Mat3& M) {
    double* values = matrix_.valuePtr();
    for (int c = 0; c < 3; ++c) {
        const int at = matrix_.outerIndexPtr()[3 * v + c] + 3 * diagonalSlots_[v];
        for (int row = 0; row < 3; ++row) values[at + row] += M(row, c);
    }
}

void BlockSystem::pin(int v) {
    double* values = matrix_.valuePtr();
    const int* outer = matrix_.outerIndexPtr();
    const int* inner = matrix_.innerIndexPtr();
    // The column is cleared directly; the row is cleared through the symmetric columns that hold
    // it.
    for (int c = 0; c < 3; ++c) {
        const int col = 3 * v + c;
        for (int at = outer[col]; at < outer[col + 1]; ++at) {
            const int row = inner[at];
            values[at] = (row == col) ? 1.0 : 0.0;
            if (row / 3 != v) {
                const int* first = inner + outer[row];
                const int* last = inner + outer[row + 1];
                const int* hit = std::lower_bound(first, last, col);
                values[hit - inner] = 0.0;
            }
        }
    }
}

void BlockSystem::addToDiagonal(double tikhonov) {
    const int n = static_cast<int>(matrix_.rows()) / 3;
    for (int v = 0; v < n; ++v) addDiagonal(v, tikhonov * Mat3::Identity());
}

bool BlockSystem::factorize(double tikhonov) {
    if (tikhonov != 0) addToDiagonal(tikhonov);
    if (!solver_) {
        solver_ = std::make_unique<Factor>();
        // Silent: a matrix that is not positive definite is a result the callers handle (the
        // exact method's Hessian may be indefinite), and CHOLMOD prints it as an error.
        // The callers see it, like any failed factorisation, through info().
        solver_->cholmod().print = 0;
        solver_->analyzePattern(matrix_);
    }
    solver_->factorize(matrix_);
    factorValid_ = solver_->info() == Eigen::Success;
    return factorValid_;
}

bool BlockSystem::solveByLastFactor(const Eigen::VectorXd& rhs, Eigen::VectorXd& x,
                                    int maxIterations, double tolerance, int* iterations) const {
    if (!factorValid_ || maxIterations <= 0) return false;
    const int n = static_cast<int>(matrix_.rows());
    const double* values = matrix_.valuePtr();
    const int* outer = matrix_.outerIndexPtr();
    const int* inner = matrix_.innerIndexPtr();
    // Both triangles are stored, so row j of H is column j: each entry of H·p is a gather.
    auto multiply = [&](const Eigen::VectorXd& p, Eigen::VectorXd& out) {
        parallelFor(n, [&](int begin, int end, int) {
            for (int j = begin; j < end; ++j) {
                double sum = 0;
                for (int at = outer[j]; at < outer[j + 1]; ++at) sum += values[at] * p[inner[at]];
                out[j] = sum;
            }
        });
    };
    const double rhsNorm = rhs.norm(), stop = tolerance * rhsNorm;
    x.setZero(n);
    if (iterations) *iterations = 0;
    if (rhsNorm == 0) return true;
    Eigen::VectorXd r = rhs, z = solver_->solve(r), p = z, Hp(n);
    double rz = r.dot(z);
    for (int it = 0; it < maxIterations; ++it) {
        multiply(p, Hp);
        const double curvature = p.dot(Hp);
        if (!(curvature > 0)) return false;
        const double alpha = rz / curvature;
        x += alpha * p;
        r -= alpha * Hp;
        if (iterations) *iterations = it + 1;
        const double residual = r.norm();
        if (residual <= stop) return true;
        // A try that will not make it is given up early: after a few iterations, the mean
        // rate so far says how many the tolerance needs (a take's first step of a frame, with
        // the last frame's factor, needed over twice the allowance).
        if (it + 1 >= kRateIterations) {
            const double rate = std::pow(residual / rhsNorm, 1.0 / (it + 1));
            if (rate >= 1 || std::log(tolerance) / std::log(rate) > 1.5 * maxIterations)
                return false;
        }
        z = solver_->solve(r);
        const double rzNext = r.dot(z);
        p = z + (rzNext / rz) * p;
        rz = rzNext;
    }
    return false;
}

int BlockSystem::iterationsPerFactorization() const {
    if (!solver_) return 0;
    const cholmod_common& c = const_cast<Factor&>(*solver_).cholmod();
    // A solve reads L twice (2 flops per entry each way); the product reads H once.
    const double perIteration = 4.0 * c.lnz + 2.0 * matrix_.nonZeros();
    // The factorisation does more flops per second than the memory-bound solve and product:
    // measured with CHOLMOD's supernodal kernels, its time was 1.4–3.9 times less than the flops'
    // ratio says (1,458 to 49,999 vertices); not yet re-measured for the simplicial factor.
    constexpr double kDenseAdvantage = 2.5;
    return static_cast<int>(c.fl / perIteration / kDenseAdvantage);
}

double BlockSystem::meanDiagonal() const {
    double sum = 0;
    const int n = static_cast<int>(matrix_.rows());
    for (int col = 0; col < n; ++col) sum += matrix_.coeff(col, col);
    return n ? sum / n : 0.0;
}

}  // namespace boneless
