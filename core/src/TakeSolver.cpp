#include "boneless/TakeSolver.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <exception>
#include <limits>

#include "boneless/Error.h"
#include "boneless/TrajectoryFilter.h"

namespace boneless {

TakeSolver::TakeSolver(const TriMesh& rest, const C3dTake& take, const Correspondence& map,
                       TakeSolveOptions options)
    : rest_(rest), take_(take), options_(std::move(options)) {
    map.checkMesh(rest.vertexCount(), "the mesh");
    points_ = map.resolve(take_);
    if (options_.lowPassHz > 0) lowPassFilter(take_.samples, take_.rate, options_.lowPassHz);

    SolverOptions solverOptions = options_.solver;
    solverOptions.constraints = SolverOptions::Constraints::Soft;
    solverOptions.softWeight = options_.markerWeight;
    solverOptions.markerOffsets.clear();
    std::vector<int> vertices;
    for (const auto& m : map.markers) vertices.push_back(m.vertex);
    solver_.prepare(rest_, vertices, solverOptions);

    // The markers sit off the skin, so the rest pose's marker positions depend on the mesh's
    // unit, which the alignment finds: align, place the markers with that scale, align again.
    // Without this, a 1 cm offset on a small mesh inflates the scale by a few percent.
    auto restMarkers = [&](double meshUnitsPerMm) {
        Positions R(points_.size(), 3);
        for (size_t k = 0; k < points_.size(); ++k) {
            const int v = vertices[k];
            Vec3 x = rest_.V.row(v).transpose();
            if (solver_.encoding().encoded(v))
                x += map.markers[k].offsetMm * meshUnitsPerMm *
                     solver_.encoding().ringNormal(v, rest_.V);
            R.row(k) = x.transpose();
        }
        return R;
    };
    if (options_.calibrationFrame >= frameCount())
        throw Error(take.file + ": calibration frame " + std::to_string(options_.calibrationFrame) +
                    " is past the take's " + std::to_string(frameCount()) + " frames");
    if (options_.alignment) {
        calibration_.takeToMesh = *options_.alignment;
        calibration_.frame = options_.calibrationFrame;
    } else {
        double meshUnitsPerMm = 0;  // first pass: markers on the skin
        for (int pass = 0; pass < 3; ++pass) {
            const Positions R = restMarkers(meshUnitsPerMm);
            if (options_.calibrationFrame >= 0) {
                const Positions P = takeFrame(take_, points_, options_.calibrationFrame);
                calibration_.frame = options_.calibrationFrame;
                calibration_.takeToMesh = fitSimilarity(P, R);
                calibration_.residual = alignmentResidual(calibration_.takeToMesh, P, R);
            } else {
                calibration_ = calibrate(take_, points_, R);
            }
            meshUnitsPerMm = calibration_.takeToMesh.scale / take_.unitToMm;
        }
    }
    // Offsets are given in millimetres of the take; the solver works in mesh units.
    meshUnitsPerMm_ = calibration_.takeToMesh.scale / take_.unitToMm;
    for (const auto& m : map.markers)
        solverOptions.markerOffsets.push_back(m.offsetMm * meshUnitsPerMm_);
    solver_.setOptions(solverOptions);
}

Positions TakeSolver::predictedMarkers(const Positions& V) const {
    const auto& markers = solver_.markerVertices();
    const auto& offsets = solver_.options().markerOffsets;
    Positions P(markers.size(), 3);
    for (size_t k = 0; k < markers.size(); ++k) {
        Vec3 x = V.row(markers[k]).transpose();
        if (k < offsets.size() && offsets[k] != 0 && solver_.encoding().encoded(markers[k]))
            x += offsets[k] * solver_.encoding().ringNormal(markers[k], V);
        P.row(k) = x.transpose();
    }
    return P;
}

Positions TakeSolver::targets(int frame) const {
    Positions T = takeFrame(take_, points_, frame);
    for (int k = 0; k < T.rows(); ++k)
        if (T.row(k).allFinite())
            T.row(k) = calibration_.takeToMesh.apply(T.row(k).transpose()).transpose();
    return T;
}

bool TakeSolver::coarsestLeadsFor(const Positions& T) {
    std::vector<int> visible;
    for (int k = 0; k < T.rows(); ++k)
        if (T.row(k).allFinite()) visible.push_back(k);
    SolverOptions o = solver_.options();
    const int coarsest = std::max(o.coarsestVertices, 10 * static_cast<int>(visible.size()));
    if (!options_.coarsestLeads || coarsestFailed_ ||
        o.method == SolverOptions::Method::Multiresolution || rest_.vertexCount() < 2 * coarsest ||
        visible.size() < 3) {
        coarsestLast_.reset();  // the next frame that leads must not measure from an older one
        return false;
    }
    if (coarsest_ && visible == coarsestMarkers_) return true;
    // The coarsest level alone (with the orientation guard, if on), prolonged.
    o.method = SolverOptions::Method::Multiresolution;
    o.fineIterations = 0;
    o.correctionSteps = 0;
    o.markerOffsets.clear();
    std::vector<int> vertices;
    for (int k : visible) {
        vertices.push_back(solver_.markerVertices()[k]);
        o.markerOffsets.push_back(solver_.options().markerOffsets[k]);  // one per marker
    }
    coarsest_.reset();
    coarsestLast_.reset();
    auto coarse = std::make_unique<Reconstruction>();
    try {
        coarse->prepare(rest_, vertices, o);
    } catch (const std::exception&) {
        // The lead is a better start, never a requirement: without it the take still solves.
        coarsestFailed_ = true;
        return false;
    }
    coarsest_ = std::move(coarse);
    coarsestMarkers_ = std::move(visible);
    return true;
}

int TakeSolver::seenBy(const Positions& T) const {
    int seen = 0;
    for (int k : coarsestMarkers_) seen += T.row(k).allFinite();
    return seen;
}

Positions TakeSolver::solveCoarsest(const Positions& T, const Positions& guess) {
    Positions targets(coarsestMarkers_.size(), 3);
    for (size_t i = 0; i < coarsestMarkers_.size(); ++i)
        targets.row(i) = T.row(coarsestMarkers_[i]);
    return coarsest_->solve(targets, &guess).V;
}

void TakeSolver::leadFromLast(const Positions& T, Positions& V) {
    // Without its answer to the last frame (it was just built, or the last frame could not be
    // led), the coarsest level solves that frame again, from the last answer; not when too few
    // of its markers were seen there (that answer would be its shape left free).
    if (!coarsestLeadsFor(T) || (!coarsestLast_ && seenBy(previousTargets_) < 3)) return;
    const Positions last = coarsestLast_ ? *coarsestLast_ : solveCoarsest(previousTargets_, V);
    const Positions X = last.allFinite() ? solveCoarsest(T, last) : last;
    if (!X.allFinite()) {
        coarsestLast_.reset();
        return;
    }
    // The coarsest level's change, not its answer: its minimum differs from the full mesh's by
    // a smooth offset the last answer has already removed.
    V += X - last;
    coarsestLast_ = X;
}

SolveResult TakeSolver::solveFirst(const Positions& T) {
    // Continuation (algorithm.md §4.2): from the rest pose moved rigidly onto the markers, the
    // targets travel to the frame's in a few steps, so a first frame far from the rest pose is
    // reached through poses near each other.
    Positions restMarkers(T.rows(), 3);
    for (int k = 0; k < T.rows(); ++k)
        restMarkers.row(k) = rest_.V.row(solver_.markerVertices()[k]);
    const RigidMotion motion = fitRigidMotion(restMarkers, T);
    Positions V(rest_.V.rows(), 3);
    for (int v = 0; v < V.rows(); ++v)
        V.row(v) = motion.apply(rest_.V.row(v).transpose()).transpose();
    const Positions from = predictedMarkers(V);
    const int steps = std::max(1, options_.continuationSteps);
    if (coarsestLeadsFor(T)) {
        // The steps are cheap there; the full mesh then solves the frame once.
        Positions X = V;
        for (int s = 1; s <= steps && X.allFinite(); ++s) {
            const double a = static_cast<double>(s) / steps;
            X = solveCoarsest((1 - a) * from + a * T, X);  // NaN rows stay missing
        }
        if (X.allFinite()) {
            coarsestLast_ = X;
            return solver_.solve(T, &X);
        }
        coarsestLast_.reset();
    }
    SolveResult r;
    int iterations = 0;
    for (int s = 1; s <= steps; ++s) {
        const double a = static_cast<double>(s) / steps;
        r = solver_.solve((1 - a) * from + a * T, &V);
        iterations += r.report.iterations;
        V = r.V;
    }
    r.report.iterations = iterations;
    return r;
}

Positions TakeSolver::solve(int frame, FrameReport& report) {
    if (frame < 0 || frame >= frameCount())
        throw Error(take_.file + ": frame " + std::to_string(frame) + " is outside the take");
    const auto start = std::chrono::steady_clock::now();
    const Positions T = targets(frame);
    report = {};
    report.frame = frame;
    SolveResult result;
    if (!previous_) {
        result = solveFirst(T);
    } else {
        Positions V = *previous_;
        leadFromLast(T, V);
        result = solver_.solve(T, &V);
    }
    const bool failed = !result.V.allFinite();
    if (failed) {
        result.V = previous_ ? *previous_ : rest_.V;  // keep the last good shape, never NaN
        coarsestLast_.reset();                        // it belongs to the frame that failed
    }
    const Positions predicted = predictedMarkers(result.V);
    double sum = 0;
    for (int k = 0; k < T.rows(); ++k) {
        if (!T.row(k).allFinite()) continue;
        const double mm = (predicted.row(k) - T.row(k)).norm() / meshUnitsPerMm_;
        sum += mm * mm;
        report.residualMaxMm = std::max(report.residualMaxMm, mm);
        ++report.visibleMarkers;
    }
    report.residualRmsMm = report.visibleMarkers ? std::sqrt(sum / report.visibleMarkers) : 0.0;
    report.iterations = result.report.iterations;
    // A failed frame leaves the last good one (and its targets) to start from; a failed first
    // frame, none, so that the next is approached from the rest pose again.
    if (!failed) {
        previous_ = result.V;
        previousTargets_ = T;
    }
    report.milliseconds =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    return result.V;
}

}  // namespace boneless
