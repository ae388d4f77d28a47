#include "ScalarSystem.h"

#include <algorithm>

#include "Parallel.h"

namespace boneless {

namespace {

// The pattern's matrix, all values zero.
Eigen::SparseMatrix<double> zeroMatrix(Eigen::Index vertexCount, const StencilPattern& pattern) {
    Eigen::SparseMatrix<double> m(vertexCount, vertexCount);
    m.resizeNonZeros(static_cast<Eigen::Index>(pattern.inner().size()));
    std::copy(pattern.outer().begin(), pattern.outer().end(), m.outerIndexPtr());
    std::copy(pattern.inner().begin(), pattern.inner().end(), m.innerIndexPtr());
    std::fill_n(m.valuePtr(), pattern.inner().size(), 0.0);
    return m;
}

}  // namespace

ScalarSystem::ScalarSystem(int vertexCount, const Stencils& stencils,
                           const StencilPattern::Lumping* lumping)
    : pattern_(vertexCount, stencils, lumping),
      lumped_(lumping != nullptr),
      matrix_(zeroMatrix(vertexCount, pattern_)),
      blocks_(pattern_.blockStarts().size() - 1) {}

void ScalarSystem::add(const Part& part) {
    double* values = matrix_.valuePtr();
    for (size_t e = 0; e < part.values_.size(); ++e) values[e] += part.values_[e];
}

void ScalarSystem::pin(int v) {
    double* values = matrix_.valuePtr();
    const int* outer = matrix_.outerIndexPtr();
    const int* inner = matrix_.innerIndexPtr();
    for (int at = outer[v]; at < outer[v + 1]; ++at) {
        const int row = inner[at];
        values[at] = row == v ? 1.0 : 0.0;
        if (row == v) continue;
        // The row is cleared through the symmetric column that holds it.
        const int* hit = std::lower_bound(inner + outer[row], inner + outer[row + 1], v);
        values[hit - inner] = 0.0;
    }
}

double ScalarSystem::meanDiagonal() const {
    const int n = static_cast<int>(matrix_.rows());
    double sum = 0;
    for (int v = 0; v < n; ++v) sum += matrix_.valuePtr()[pattern_.diagonal(v)];
    return n ? sum / n : 0.0;
}

Eigen::SparseMatrix<double> ScalarSystem::block(int k, bool values) const {
    const std::vector<int>& starts = pattern_.blockStarts();
    // No entry crosses a block: its columns hold its rows only.
    const int first = starts[k], size = starts[k + 1] - first;
    const int* outer = matrix_.outerIndexPtr();
    const int* inner = matrix_.innerIndexPtr();
    const int begin = outer[first], count = outer[first + size] - begin;
    Eigen::SparseMatrix<double> m(size, size);
    m.resizeNonZeros(count);
    for (int c = 0; c <= size; ++c) m.outerIndexPtr()[c] = outer[first + c] - begin;
    for (int e = 0; e < count; ++e) m.innerIndexPtr()[e] = inner[begin + e] - first;
    if (values)
        std::copy_n(matrix_.valuePtr() + begin, count, m.valuePtr());
    else
        std::fill_n(m.valuePtr(), count, 0.0);
    return m;
}

std::unique_ptr<ScalarSystem::Factor> ScalarSystem::analysed(int k) const {
    auto factor = std::make_unique<Factor>();
    factor->cholmod().print = 0;  // a matrix that is not positive definite is reported by info()
    // Each conjugate-gradient step solves with this factor. On a multiresolution solver's coarsest
    // level (2,000 vertices) that solve was half the time of conjugate gradients, and the
    // supernodal factor's dense-block calls cost more than the arithmetic: simplicial, the bench's
    // frame went from 18.4 to 15.5 ms. On the input (50,000 vertices) supernodal stays ahead (one
    // fine step: 613 against 650 ms); at 10,000 they are even. Lumped, the factor is sparse enough
    // for simplicial to win there too (koala's input, lnz 1.4M: analysed and factorised in 93
    // against 140 ms, a solve for three columns 4.9 against 8.5 ms).
    constexpr int simplicialBelow = 10000;
    factor->setMode(lumped_ || matrix_.rows() < simplicialBelow ? Eigen::CholmodSimplicialLLt
                                                                : Eigen::CholmodSupernodalLLt);
    // On a copy of the pattern: the values may be filled meanwhile, and the analysis must not
    // read them.
    factor->analyzePattern(block(k, false));
    return factor;
}

void ScalarSystem::analyse() {
    parallelFor(
        static_cast<int>(blocks_.size()),
        [&](int begin, int end, int) {
            for (int k = begin; k < end; ++k) blocks_[k].symbolic = analysed(k);
        },
        1);
}

bool ScalarSystem::factorize(double tikhonov) {
    const int n = static_cast<int>(matrix_.rows());
    for (int v = 0; v < n; ++v) matrix_.valuePtr()[pattern_.diagonal(v)] += tikhonov;
    std::vector<char> ok(blocks_.size(), 0);
    parallelFor(
        static_cast<int>(blocks_.size()),
        [&](int begin, int end, int) {
            for (int k = begin; k < end; ++k) {
                Block& b = blocks_[k];
                // A retry (a stronger Tikhonov term) analyses again: the failed factor is gone.
                b.factor = b.symbolic ? std::move(b.symbolic) : analysed(k);
                // One block is the matrix itself: no copy of it.
                if (blocks_.size() == 1)
                    b.factor->factorize(matrix_);
                else
                    b.factor->factorize(block(k, true));
                ok[k] = b.factor->info() == Eigen::Success;
            }
        },
        1);
    if (std::all_of(ok.begin(), ok.end(), [](char x) { return x; })) return true;
    for (Block& b : blocks_) b.factor.reset();
    return false;
}

Eigen::MatrixXd ScalarSystem::solve(const Eigen::MatrixXd& rhs) const {
    if (blocks_.size() == 1) return blocks_[0].factor->solve(rhs);
    const std::vector<int>& starts = pattern_.blockStarts();
    Eigen::MatrixXd x(rhs.rows(), rhs.cols());
    parallelFor(
        static_cast<int>(blocks_.size()),
        [&](int begin, int end, int) {
            for (int k = begin; k < end; ++k) {
                const int first = starts[k], size = starts[k + 1] - first;
                const Eigen::MatrixXd part = rhs.middleRows(first, size);
                x.middleRows(first, size) = blocks_[k].factor->solve(part);
            }
        },
        1);
    return x;
}

}  // namespace boneless
