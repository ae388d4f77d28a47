#include "MultiresSolver.h"

#include <algorithm>
#include <chrono>

#include "Parallel.h"
#include "boneless/Error.h"

namespace boneless {

namespace {

HierarchyOptions hierarchyOptions(const SolverOptions& o, size_t markers) {
    HierarchyOptions h;
    // §1.6: a few hundred to two thousand vertices, or about ten per marker.
    h.coarsestVertices = std::max(o.coarsestVertices, static_cast<int>(10 * markers));
    return h;
}

}  // namespace

MultiresSolver::MultiresSolver(const TriMesh& rest, const std::vector<int>& markers,
                               const SolverOptions& options)
    : hierarchy_(rest, markers, hierarchyOptions(options, markers.size())) {
    const int L = hierarchy_.levelCount();
    auto levelMarkers = [&](int l) {
        const HierarchyLevel& level = hierarchy_.level(l);
        std::vector<int> levelIndex(rest.vertexCount(), -1);
        for (size_t i = 0; i < level.original.size(); ++i)
            levelIndex[level.original[i]] = static_cast<int>(i);
        std::vector<int> ids(markers.size());
        for (size_t k = 0; k < markers.size(); ++k) ids[k] = levelIndex[markers[k]];
        return ids;
    };
    // Both solved levels use conjugate gradients preconditioned by their rest matrix (rotated
    // per vertex): it is the smooth part of the error that matters, and a rest factorisation is
    // what removes it. The coarsest converges (§1.6: relative decrease below 1e-4, at most ~10
    // steps), with a factorisation when CG stall; the input takes fineIterations steps.
    SolverOptions coarse = options;
    coarse.method = SolverOptions::Method::Iterative;
    coarse.preconditioner = SolverOptions::Preconditioner::Scalar;
    coarse.directFallback = true;
    coarse.maxCgIterations = std::max(options.maxCgIterations, 50);  // cheap at this size
    coarse.maxIterations = std::max(options.maxIterations, 10);
    coarse.relativeTolerance = std::min(options.relativeTolerance, 1e-4);
    coarsest_.prepare(hierarchy_.coarsest().mesh, levelMarkers(L - 1), coarse);
    if (L == 1) return;
    SolverOptions fine = options;
    fine.method = SolverOptions::Method::Iterative;
    fine.preconditioner = SolverOptions::Preconditioner::Scalar;
    fine.maxIterations = options.fineIterations;
    fine_.prepare(rest, markers, fine);
    // The levels between are only prolonged through: their encodings are all they need.
    for (int l = 1; l < L - 1; ++l) {
        const TriMesh& mesh = hierarchy_.level(l).mesh;
        topologies_.push_back(std::make_unique<MeshTopology>(mesh));
        encodings_.push_back(std::make_unique<ShapeEncoding>(mesh, *topologies_.back()));
    }
}

const ShapeEncoding& MultiresSolver::encoding(int l) const {
    return l == 0 ? fine_.encoding() : *encodings_[l - 1];
}

void MultiresSolver::prolong(int l, const Positions& coarse, Positions& fine) const {
    const HierarchyLevel& level = hierarchy_.level(l);
    const int n = level.mesh.vertexCount();
    fine.resize(n, 3);
    for (int i = 0; i < n; ++i)
        if (level.coarser[i] >= 0) fine.row(i) = coarse.row(level.coarser[i]);
    // Removed vertices are independent: each ring is made of survivors only.
    const ShapeEncoding& enc = encoding(l);
    parallelFor(
        static_cast<int>(level.removed.size()),
        [&](int begin, int end, int) {
            for (int i = begin; i < end; ++i) {
                const int r = level.removed[i];
                fine.row(r) = enc.decode(r, fine).transpose();
            }
        },
        4096);
}

Positions MultiresSolver::restrictTo(int l, const Positions& input) const {
    const HierarchyLevel& level = hierarchy_.level(l);
    Positions out(level.mesh.vertexCount(), 3);
    for (int i = 0; i < out.rows(); ++i) out.row(i) = input.row(level.original[i]);
    return out;
}

void MultiresSolver::restartFrom(const Positions& guess) {
    last_.resize(levelCount());
    for (int l = 0; l < levelCount(); ++l) last_[l] = restrictTo(l, guess);
}

SolveResult MultiresSolver::solve(const Positions& targets, const Positions* guess) {
    const auto start = std::chrono::steady_clock::now();
    const int L = levelCount();
    // Warm: the guess is the last answer, so every level's last answer belongs to it.
    const bool warm = guess && !last_.empty() && last_[0].rows() == guess->rows() &&
                      (last_[0] - *guess).cwiseAbs().maxCoeff() == 0;
    if (guess && !warm) restartFrom(*guess);

    SolveResult coarse = coarsest_.solve(targets, guess ? &last_[L - 1] : nullptr);
    if (L == 1) {
        last_ = {coarse.V};
        return coarse;
    }
    std::vector<Positions> answer(L);
    answer[L - 1] = std::move(coarse.V);
    Positions prolongedLast;
    for (int l = L - 2; l >= 0; --l) {
        prolong(l, answer[l + 1], answer[l]);
        if (guess) {
            // Last answer + the prolonged change of the level below.
            prolong(l, last_[l + 1], prolongedLast);
            answer[l] += last_[l] - prolongedLast;
        }
    }
    SolveReport report;
    if (fine_.options().maxIterations > 0) {
        SolveResult r = fine_.solve(targets, &answer[0]);
        answer[0] = std::move(r.V);
        report = std::move(r.report);
    } else {
        report.energyBefore = report.energyAfter = fine_.energy(answer[0], targets);
        report.energies = {report.energyBefore};
    }
    report.iterations += coarse.report.iterations;
    report.linearIterations += coarse.report.linearIterations;
    report.directSteps += coarse.report.directSteps;
    last_ = answer;
    SolveResult result;
    result.V = std::move(answer[0]);
    result.report = std::move(report);
    result.report.milliseconds =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    return result;
}

}  // namespace boneless
