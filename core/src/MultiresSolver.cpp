#include "MultiresSolver.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>

#include "IterativeSolver.h"
#include "LineSearch.h"
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

MultiresSolver::MultiresSolver(const TriMesh& userRest, const std::vector<int>& userMarkers,
                               const SolverOptions& options)
    : diagonal_(boundingBoxDiagonal(userRest.V)) {
    // Below this many vertices a level's arrays stay in the caches whatever their order.
    constexpr int reorderFrom = 10000;
    if (userRest.vertexCount() >= reorderFrom) order_ = VertexOrder::spatial(userRest);
    const TriMesh rest = order_.apply(userRest);
    const std::vector<int> markers = order_.toInternal(userMarkers);
    const HierarchyOptions levels = hierarchyOptions(options, markers.size());
    // The input level's preparation does not need the hierarchy, and it is most of the time
    // (koala, 100K faces, in the spatial order: 240 ms, 90 of them its factorisation, against
    // 115 for the hierarchy and the coarsest level): the two go on both cores, and the input's
    // encoding in the caller's order goes with the hierarchy. A mesh too small for a hierarchy
    // has no input level apart from the coarsest.
    const bool twoLevels = rest.vertexCount() > levels.coarsestVertices;
    runOnWorkers(twoLevels ? 2 : 1, [&](int task) {
        if (task == 1) {
            prepareInput(rest, markers, options);
            return;
        }
        hierarchy_.emplace(rest, markers, levels);
        prepareCoarsest(rest, markers, options);
        if (order_.identity()) return;
        userTopology_ = std::make_unique<MeshTopology>(userRest);
        userEncoding_ = std::make_unique<ShapeEncoding>(userRest, *userTopology_);
    });
    const int L = hierarchy_->levelCount();
    if (L == 1) {
        fine_ = Reconstruction();
        return;
    }
    if (!twoLevels) prepareInput(rest, markers, options);
}

void MultiresSolver::prepareCoarsest(const TriMesh& rest, const std::vector<int>& markers,
                                     const SolverOptions& options) {
    const int L = hierarchy_->levelCount();
    auto levelMarkers = [&](int l) {
        const HierarchyLevel& level = hierarchy_->level(l);
        std::vector<int> levelIndex(rest.vertexCount(), -1);
        for (size_t i = 0; i < level.original.size(); ++i)
            levelIndex[level.original[i]] = static_cast<int>(i);
        std::vector<int> ids(markers.size());
        for (size_t k = 0; k < markers.size(); ++k) ids[k] = levelIndex[markers[k]];
        return ids;
    };
    // Both solved levels use conjugate gradients preconditioned by their rest matrix (rotated
    // per vertex): it is the smooth part of the error that matters, and a rest factorisation is
    // what removes it. The input's may use Preconditioner::LastFactor instead (prepareInput()).
    // The coarsest converges (§1.6: relative decrease below 1e-4, at most ~10 steps), with a
    // factorisation when CG stall; the input takes fineIterations steps.
    SolverOptions coarse = options;
    coarse.method = SolverOptions::Method::Iterative;
    coarse.preconditioner = SolverOptions::Preconditioner::Scalar;
    coarse.directFallback = true;
    coarse.maxCgIterations = std::max(options.maxCgIterations, 50);  // cheap at this size
    coarse.maxIterations = options.coarsestIterations;
    coarse.relativeTolerance = std::min(options.relativeTolerance, 1e-4);
    coarse.recycledMotions = 0;
    coarse.refreshEvery = 1;
    // The orientation guard needs the direct method, which the coarsest level's size affords
    // (a take's frame there fell back to a factorisation in most steps anyway). The input level
    // carries it in its own steps (prepareInput()).
    if (options.orientationWeight > 0) coarse.method = SolverOptions::Method::Direct;
    // The fold guard's weight grows with the coarsest level's edge length relative to the input's
    // (the square root of the vertex ratio): it brings the coarsest level's minimum, which is
    // what prolongation passes on, closer to the input's. Measured on the bend workload (koala
    // at 20K, 50K, 100K faces, prolongation alone, worst RMS against the converged answer):
    // 0.31 → 0.21 %, 0.50 → 0.33 %, 0.57 → 0.34–0.41 % (×5 and ×5.5; ×3 and ×8: 0.42 %, 0.38 %).
    coarse.rigidityWeight *=
        std::sqrt(double(rest.vertexCount()) / hierarchy_->coarsest().mesh.vertexCount());
    coarsest_.prepare(hierarchy_->coarsest().mesh, levelMarkers(L - 1), coarse);
    // The levels between are only prolonged through: their encodings are all they need.
    for (int l = 1; l < L - 1; ++l) {
        const TriMesh& mesh = hierarchy_->level(l).mesh;
        topologies_.push_back(std::make_unique<MeshTopology>(mesh));
        encodings_.push_back(std::make_unique<ShapeEncoding>(mesh, *topologies_.back()));
    }
}

void MultiresSolver::prepareInput(const TriMesh& rest, const std::vector<int>& markers,
                                  const SolverOptions& options) {
    SolverOptions fine = options;
    fine.method = SolverOptions::Method::Iterative;
    // The input's steps may use the last factor of their own matrix instead (see
    // SolverOptions::Preconditioner): more accurate per step, a factorisation now and then.
    // Lumped from lumpFrom vertices, where the full factor's cost shows. Koala (100K faces),
    // three alternating runs of the bench's first 12 frames: preprocessing 428–623 ms against
    // 746–1083, conjugate gradients 47.7 a frame against 37.8. Below it the full factor is cheap
    // and saves those iterations.
    constexpr int lumpFrom = 10000;
    if (fine.preconditioner != SolverOptions::Preconditioner::LastFactor)
        fine.preconditioner = rest.vertexCount() >= lumpFrom
                                  ? SolverOptions::Preconditioner::LumpedScalar
                                  : SolverOptions::Preconditioner::Scalar;
    // In the spatial order each core's range of vertices is a region of the mesh: the factor
    // splits into one block per core with few pairs lumped between them (koala: 921 of 150,000),
    // factorised and solved on both cores at once.
    if (fine.preconditioner == SolverOptions::Preconditioner::LumpedScalar && !order_.identity())
        fine.lumpedBlocks = solverThreadCount();
    fine.maxIterations = options.fineIterations;
    // The input minimises the same energy as the direct method, the orientation guard included.
    // Without it the answer was the unguarded minimum near the guarded coarsest one: samba at 40
    // markers, frame 135, 31 % above the direct solver's energy (the guard's part) against 1.9 %
    // with it, at 4 % more time a frame. The iterative method refuses the guard as a solver of
    // its own (checkOrientationGuard()), so it is set here, after prepare().
    fine.orientationWeight = 0;
    fine_.prepare(rest, markers, fine);
    fine_.impl_->options.orientationWeight = options.orientationWeight;
    fine_.impl_->updateOrientationGuard();
    fine_.impl_->iterative->setStartsNearMinimum(true);
    fine_.impl_->iterative->setCallerTellsJumps(true);  // restartFrom()
}

const ShapeEncoding& MultiresSolver::encoding(int l) const {
    return l == 0 ? fine_.encoding() : *encodings_[l - 1];
}

void MultiresSolver::prolong(int l, const Positions& coarse, Positions& fine) const {
    const HierarchyLevel& level = hierarchy_->level(l);
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
        256);
}

std::vector<Mat3> MultiresSolver::prolongationJacobian(int l, const Positions& fine) const {
    const HierarchyLevel& level = hierarchy_->level(l);
    const ShapeEncoding& enc = encoding(l);
    const MeshTopology& topo = enc.topology();
    // One block per ring entry (CSR, the topology's offsets); only removed vertices' are filled.
    std::vector<Mat3> jacobian(topo.neighbours().size());
    parallelFor(
        static_cast<int>(level.removed.size()),
        [&](int begin, int end, int) {
            std::vector<Mat3> J;
            Vec3 F;
            for (int i = begin; i < end; ++i) {
                const int r = level.removed[i];
                enc.decodeWithJacobian(r, fine, F, J);
                std::copy(J.begin(), J.end(), jacobian.begin() + topo.offsets()[r]);
            }
        },
        256);
    return jacobian;
}

void MultiresSolver::restrictGradient(int l, const std::vector<Mat3>& jacobian, const Positions& g,
                                      Positions& out) const {
    const HierarchyLevel& level = hierarchy_->level(l);
    const MeshTopology& topo = encoding(l).topology();
    // Removed vertex r was placed at F_r(ring), so its gradient reaches its ring through J_rkᵀ.
    Positions sum = g;
    for (int r : level.removed)
        for (int k = 0; k < topo.valence(r); ++k)
            sum.row(topo.ring(r)[k]) +=
                (jacobian[topo.offsets()[r] + k].transpose() * g.row(r).transpose()).transpose();
    out.resize(hierarchy_->level(l + 1).mesh.vertexCount(), 3);
    for (int i = 0; i < sum.rows(); ++i)
        if (level.coarser[i] >= 0) out.row(level.coarser[i]) = sum.row(i);
}

void MultiresSolver::prolongLinear(int l, const std::vector<Mat3>& jacobian, const Positions& d,
                                   Positions& out) const {
    const HierarchyLevel& level = hierarchy_->level(l);
    const MeshTopology& topo = encoding(l).topology();
    const int n = level.mesh.vertexCount();
    out.resize(n, 3);
    for (int i = 0; i < n; ++i)
        if (level.coarser[i] >= 0) out.row(i) = d.row(level.coarser[i]);
    // Removed vertices are independent: their rings hold survivors only.
    for (int r : level.removed) {
        Vec3 s = Vec3::Zero();
        for (int k = 0; k < topo.valence(r); ++k)
            s += jacobian[topo.offsets()[r] + k] * out.row(topo.ring(r)[k]).transpose();
        out.row(r) = s.transpose();
    }
}

double MultiresSolver::correctionSteps(const Positions& targets,
                                       const std::vector<Positions>& prolonged, Positions& V,
                                       SolveReport& report) {
    const int L = levelCount();
    IterativeSolver& fine = *fine_.impl_->iterative;
    IterativeSolver& coarse = *coarsest_.impl_->iterative;
    const Reconstruction::Impl& c = *coarsest_.impl_;
    Eigen::VectorXd g, gc, dc, step;
    double E = fine.gradientAt(V, targets, g, false);
    Positions G, next, trial;
    // The prolongation does not move during the steps: its Jacobians are taken once.
    std::vector<std::vector<Mat3>> jacobians(L - 1);
    for (int l = 0; l + 1 < L; ++l) jacobians[l] = prolongationJacobian(l, prolonged[l]);
    // Line search along `step` from V; on success V, E and g belong to the new pose.
    auto take = [&] {
        const double slope = g.dot(step);
        if (!(slope < 0)) return false;
        double Enew = E;
        if (!armijoBacktrack(
                V, step, E, slope, [&](const Positions& X) { return fine.tryPose(X, targets); },
                trial, Enew))
            return false;
        fine.keepTried();
        V.swap(trial);
        E = fine.gradientAt(V, targets, g, true);
        ++report.iterations;
        return true;
    };
    for (int it = 0; it < fine_.options().correctionSteps; ++it) {
        // Smoothing first: the finest scale's error would otherwise dominate the gradient and,
        // restricted, make the coarse direction noise.
        fine.blockJacobi(g, step);
        take();
        G = Eigen::Map<const Positions>(g.data(), V.rows(), 3);
        for (int l = 0; l + 1 < L; ++l) {
            restrictGradient(l, jacobians[l], G, next);
            G.swap(next);
        }
        if (!c.softMarkers())
            for (int v : c.markers) G.row(v).setZero();
        // The coarse system of the pose the coarsest level has just converged to.
        gc = Eigen::Map<const Eigen::VectorXd>(G.data(), G.size());
        dc.setZero(gc.size());
        report.linearIterations += coarse.solveAtCurrent(gc, dc);
        G = Eigen::Map<const Positions>(dc.data(), G.rows(), 3);
        for (int l = L - 2; l >= 0; --l) {
            prolongLinear(l, jacobians[l], G, next);
            G.swap(next);
        }
        step = Eigen::Map<const Eigen::VectorXd>(G.data(), G.size());
        // Pinned vertices (zero gradient rows) stay where they are.
        for (int v = 0; v < V.rows(); ++v)
            if (g.segment<3>(3 * v).squaredNorm() == 0) step.segment<3>(3 * v).setZero();
        take();
    }
    return E;
}

Positions MultiresSolver::restrictTo(int l, const Positions& input) const {
    const HierarchyLevel& level = hierarchy_->level(l);
    Positions out(level.mesh.vertexCount(), 3);
    for (int i = 0; i < out.rows(); ++i) out.row(i) = input.row(level.original[i]);
    return out;
}

void MultiresSolver::keepKeyframe(const std::vector<Positions>& answer, const Positions& prolonged,
                                  bool warm) {
    if (warm && keyframe_) {
        const Keyframe& last = *keyframe_;
        intervalCorrection_ = (answer.front() - last.fine) - (prolonged - last.prolonged);
        intervalCoarsestChange_ = answer.back() - last.coarsest;
    } else {
        intervalCorrection_.resize(0, 3);  // no interval continues into this frame
    }
    keyframe_ = Keyframe{answer.front(), prolonged, answer.back()};
    appliedAlong_ = 0;
    sinceKeyframe_ = 0;
}

MultiresSolver::Progress MultiresSolver::coarsestProgress(const Positions& coarsest) const {
    const Positions moved = coarsest - keyframe_->coarsest;
    const double norm2 = intervalCoarsestChange_.squaredNorm();
    Progress p;
    p.along = norm2 > 0 ? moved.cwiseProduct(intervalCoarsestChange_).sum() / norm2 : 0;
    const double movedNorm = moved.norm();
    p.off = movedNorm > 0 ? (moved - p.along * intervalCoarsestChange_).norm() / movedNorm : 0;
    return p;
}

void MultiresSolver::extrapolateCorrection(std::vector<Positions>& answer, double along) {
    // The last answer already holds appliedAlong_ times the same correction.
    answer.front() += (along - appliedAlong_) * intervalCorrection_;
    appliedAlong_ = along;
    ++sinceKeyframe_;
}

void MultiresSolver::restartFrom(const Positions& guess) {
    const int L = levelCount();
    if (L > 1) fine_.impl_->iterative->forgetMotions();
    last_.resize(L);
    for (int l = 0; l < L; ++l) last_[l] = restrictTo(l, guess);
    lastProlonged_.resize(L - 1);
    for (int l = 0; l + 1 < L; ++l) prolong(l, last_[l + 1], lastProlonged_[l]);
}

SolveResult MultiresSolver::solve(const Positions& targets, const Positions* guess) {
    if (order_.identity()) return solveInOrder(targets, guess);
    const auto start = std::chrono::steady_clock::now();
    std::optional<Positions> internalGuess;
    if (guess) internalGuess = order_.toInternal(*guess);
    SolveResult result = solveInOrder(targets, guess ? &*internalGuess : nullptr);
    result.V = order_.toUser(result.V);
    result.report.milliseconds =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    return result;
}

double MultiresSolver::energy(const Positions& V, const Positions& targets) const {
    return fine().energy(order_.toInternal(V), targets);
}

const ShapeEncoding& MultiresSolver::encoding() const {
    return userEncoding_ ? *userEncoding_ : fine().encoding();
}

SolveResult MultiresSolver::solveInOrder(const Positions& targets, const Positions* guess) {
    const auto start = std::chrono::steady_clock::now();
    const int L = levelCount();
    // Warm: the guess is the last answer, so every level's last answer belongs to it.
    const bool warm = guess && !last_.empty() && last_[0].rows() == guess->rows() &&
                      (last_[0] - *guess).cwiseAbs().maxCoeff() == 0;
    if (guess && !warm) restartFrom(*guess);
    if (L == 1) {
        SolveResult coarse = coarsest_.solve(targets, guess ? &last_[0] : nullptr);
        last_ = {coarse.V};
        return coarse;
    }
    SolveResult coarse = coarsest_.solve(targets, guess ? &last_[L - 1] : nullptr);
    std::vector<Positions> answer(L), prolonged(L - 1);
    answer[L - 1] = std::move(coarse.V);
    for (int l = L - 2; l >= 0; --l) {
        prolong(l, answer[l + 1], prolonged[l]);
        answer[l] = prolonged[l];
        // Last answer + the prolonged change of the level below.
        if (guess) answer[l] += last_[l] - lastProlonged_[l];
    }
    SolveReport report;
    const SolverOptions& fineOptions = fine_.options();
    const bool keyframes = fineOptions.keyframeEvery > 1 &&
                           fineOptions.maxIterations + fineOptions.correctionSteps > 0;
    // A keyframe starts from the same prediction as a frame between keyframes would, so that
    // what its steps move measures that prediction's error. Started from the warm start alone,
    // that move held the whole frame's correction: at 200K faces it stayed above the tolerance,
    // and every frame became a keyframe (the sweep's median was a keyframe's, 4.2 s).
    const bool predicted = keyframes && warm && intervalCorrection_.rows() > 0;
    Progress progress;
    if (predicted) progress = coarsestProgress(answer.back());
    const bool straight = predicted && progress.off <= fineOptions.keyframeTurn;
    const bool between = straight && sinceKeyframe_ + 1 < fineOptions.keyframeEvery &&
                         keyframeMove_ <= fineOptions.keyframeTolerance * diagonal_;
    const bool corrected = !between && fineOptions.correctionSteps > 0;
    double energy = std::numeric_limits<double>::quiet_NaN();
    if (straight) extrapolateCorrection(answer, progress.along);
    Positions keyframeStart;
    if (keyframes && !between) keyframeStart = answer[0];
    if (corrected) energy = correctionSteps(targets, prolonged, answer[0], report);
    if (!between && fineOptions.maxIterations > 0) {
        SolveResult r = fine_.solve(targets, &answer[0]);
        answer[0] = std::move(r.V);
        r.report.iterations += report.iterations;
        r.report.linearIterations += report.linearIterations;
        report = std::move(r.report);
    } else {
        // Prolongation alone does not evaluate the input's energy: that would cost as much as
        // the rest of the frame (see SolveReport).
        report.energyBefore = report.energyAfter = energy;
        if (corrected) report.energies = {energy};
    }
    if (keyframes && !between) {
        keyframeMove_ = std::sqrt((answer[0] - keyframeStart).rowwise().squaredNorm().mean());
        keepKeyframe(answer, prolonged[0], warm);
    }
    report.iterations += coarse.report.iterations;
    report.linearIterations += coarse.report.linearIterations;
    report.directSteps += coarse.report.directSteps;
    SolveResult result;
    result.V = answer[0];  // the only level the caller gets: the others move into last_
    last_ = std::move(answer);
    lastProlonged_ = std::move(prolonged);
    result.report = std::move(report);
    result.report.milliseconds =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    return result;
}

}  // namespace boneless
