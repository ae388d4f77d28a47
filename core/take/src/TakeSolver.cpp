#include "boneless/TakeSolver.h"

#include <optional>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <exception>
#include <limits>

#include "TrajectoryFilter.h"
#include "boneless/C3dFrameReader.h"
#include "boneless/DentGauge.h"
#include "boneless/Error.h"

namespace boneless {

SurfacePoint surfacePoint(const MarkerMapping& m) {
    return {m.vertex, m.face, Vec3(m.barycentric[0], m.barycentric[1], m.barycentric[2])};
}

std::vector<SurfacePoint> surfacePoints(const Correspondence& map) {
    std::vector<SurfacePoint> points;
    for (const auto& m : map.markers) points.push_back(surfacePoint(m));
    return points;
}

namespace {
// Frames read past the one asked for: frames are mostly asked for in order.
constexpr std::size_t kWindowAhead = 256;

void checkCalibrationFrame(int frame, std::size_t frames, const std::string& file) {
    if (frame >= 0 && static_cast<std::size_t>(frame) >= frames)
        throw Error(file + ": calibration frame " + std::to_string(frame) + " is past the take's " +
                    std::to_string(frames) + " frames");
}
}  // namespace

TakeSolver::TakeSolver(const TriMesh& rest, const C3dTake& take, const Correspondence& map,
                       TakeSolveOptions options)
    : rest_(rest), options_(std::move(options)) {
    map.checkMesh(rest.vertexCount(), "the mesh", &rest);
    const std::vector<std::size_t> points = map.resolve(take);
    checkCalibrationFrame(options_.calibrationFrame, take.frameCount(), take.file);
    track_ = std::make_shared<MarkerTrack>(take, points, options_.lowPassHz);
    prepare(map);
}

TakeSolver::TakeSolver(const TriMesh& rest, const C3dFrameReader& take, const Correspondence& map,
                       TakeSolveOptions options)
    : rest_(rest), options_(std::move(options)) {
    map.checkMesh(rest.vertexCount(), "the mesh", &rest);
    const std::vector<std::size_t> points = map.resolve(take.take());
    checkCalibrationFrame(options_.calibrationFrame, take.frameCount(), take.take().file);
    track_ = std::make_shared<MarkerTrack>(take, points, options_.lowPassHz);
    prepare(map);
}

TakeSolver::TakeSolver(const TriMesh& rest, const TakeSolver& same, const Correspondence& map,
                       TakeSolveOptions options)
    : rest_(rest), track_(same.track_), options_(std::move(options)) {
    map.checkMesh(rest.vertexCount(), "the mesh", &rest);
    options_.lowPassHz = same.options_.lowPassHz;
    checkCalibrationFrame(options_.calibrationFrame, track_->frames(), track_->file());
    prepare(map);
}

void TakeSolver::prepare(const Correspondence& map) {
    followWelds(rest_, rest_.V);  // copies within the weld's tolerance: exactly together
    // One search for every alignment below: the take is read whole once, and the later searches
    // read only the frames the earlier ones leave in the running.
    CalibrationSearch search(
        frameCount(), [&](int f) { return trackFrame(f, false); }, track_->file());
    auto calibrateTrack = [&](const Positions& R) { return search.find(R); };
    SolverOptions solverOptions = options_.solver;
    solverOptions.method = SolverOptions::Method::LocalGlobal;
    solverOptions.constraints = SolverOptions::Constraints::Soft;
    solverOptions.markerWeight = options_.markerWeight;
    solverOptions.markerOffsets.clear();
    // A map may name any copy of a welded vertex; F and the solver know only the first.
    std::vector<SurfacePoint> points = surfacePoints(map);
    for (SurfacePoint& p : points) p.vertex = weldedVertex(rest_, p.vertex);
    topology_ = std::make_unique<MeshTopology>(rest_);
    encoding_ = std::make_unique<ShapeEncoding>(rest_, *topology_);

    // The markers sit off the skin, so the rest pose's marker positions depend on the mesh's
    // unit, which the alignment finds: align, place the markers with that scale, align again.
    // Without this, a 1 cm offset on a small mesh inflates the scale by a few percent.
    auto restMarkers = [&](double meshUnitsPerMm) {
        Positions R(track_->markers(), 3);
        for (size_t k = 0; k < track_->markers(); ++k)
            R.row(k) = (surfacePosition(rest_, rest_.V, points[k]) +
                        map.markers[k].offsetMm * meshUnitsPerMm *
                            surfaceNormal(rest_, *encoding_, points[k]))
                           .transpose();
        return R;
    };
    // A given alignment (the app's Align) is measured at its frame as a found one is, so the
    // sidecar's residual says how well it fits rather than 0.
    auto measureGivenAlignment = [&] {
        const Positions P = trackFrame(calibration_.frame, false);
        calibration_.residual =
            alignmentResidual(calibration_.takeToMesh, P,
                              restMarkers(calibration_.takeToMesh.scale / track_->unitToMm()));
        calibration_.visibleMarkers = visibleRows(P);
    };
    std::optional<Similarity> level;
    double levelResidual = 0;
    if (options_.alignment) {
        calibration_.takeToMesh = *options_.alignment;
        calibration_.frame = options_.calibrationFrame;
        if (calibration_.frame >= 0) measureGivenAlignment();
    } else {
        double meshUnitsPerMm = 0;  // first pass: markers on the skin
        for (int pass = 0; pass < 3; ++pass) {
            const Positions R = restMarkers(meshUnitsPerMm);
            if (options_.calibrationFrame >= 0) {
                const Positions P = trackFrame(options_.calibrationFrame, false);
                if (const int seen = visibleRows(P); seen < kMinAlignmentMarkers)
                    throw Error(track_->file() + ": calibration frame " +
                                std::to_string(options_.calibrationFrame) + " shows " +
                                std::to_string(seen) + " of the " + std::to_string(P.rows()) +
                                " mapped markers; aligning needs at least " +
                                std::to_string(kMinAlignmentMarkers) + " seen at once");
                calibration_.frame = options_.calibrationFrame;
                calibration_.takeToMesh = fitSimilarity(P, R);
                calibration_.residual = alignmentResidual(calibration_.takeToMesh, P, R);
            } else {
                calibration_ = calibrateTrack(R);
            }
            meshUnitsPerMm = calibration_.takeToMesh.scale / track_->unitToMm();
        }
        // Frames are solved and written level (the floor stays the floor), but the actor's shape
        // is fitted under the free alignment: fitted level, the rest would have to lean to meet
        // a leaning calibration frame (CMU 85_02, six picks: 77 suggestions within 30 mm of 175
        // fell to 62).
        const Positions P = trackFrame(calibration_.frame, false), R = restMarkers(meshUnitsPerMm);
        level = levelled(calibration_.takeToMesh, P, R, track_->vertical(), options_.meshUp);
        levelResidual = alignmentResidual(*level, P, R);
    }
    // Offsets are given in millimetres of the take; the solver works in mesh units.
    meshUnitsPerMm_ = calibration_.takeToMesh.scale / track_->unitToMm();
    for (const auto& m : map.markers)
        solverOptions.markerOffsets.push_back(m.offsetMm * meshUnitsPerMm_);
    solver_.prepare(rest_, points, solverOptions);
    const bool exact = options_.solver.method == SolverOptions::Method::Exact;
    // The calibration stage (docs/calibration.md): the engine's answer at the calibration frame
    // becomes the rest every frame is encoded, solved and measured against.
    if (options_.calibrate == CalibrateMode::Shape) {
        if (calibration_.frame < 0) {
            calibration_.frame = calibrateTrack(restMarkers(meshUnitsPerMm_)).frame;
            if (options_.alignment) measureGivenAlignment();
        }
        if (options_.calibratedRest) {
            if (options_.calibratedRest->rows() != rest_.vertexCount() ||
                options_.calibratedRest->cols() != 3)
                throw Error("the calibrated rest has " +
                            std::to_string(options_.calibratedRest->rows()) +
                            " vertices, the mesh " + std::to_string(rest_.vertexCount()));
            rest_.V = *options_.calibratedRest;
        } else {
            std::vector<std::string> labels;
            for (const auto& m : map.markers) labels.push_back(m.label);
            const Positions T = targets(calibration_.frame, true);
            calibration_.unseen.clear();
            for (int k = 0; k < T.rows(); ++k)
                if (!T.row(k).allFinite()) calibration_.unseen.push_back(k);
            rest_.V = fitActorShape(solver_, T, labels, 1.0 / meshUnitsPerMm_);
        }
        followWelds(rest_, rest_.V);
        encoding_ = std::make_unique<ShapeEncoding>(rest_, *topology_);
        solver_.prepare(rest_, points, solverOptions);
    }
    if (level) {  // a rigid motion of the mesh's space: the rest fitted above fits as well
        calibration_.takeToMesh = *level;
        calibration_.residual = levelResidual;
    }
    dents_ = std::make_unique<DentGauge>(rest_, *topology_, *encoding_, points,
                                         kDentRadiusMm * meshUnitsPerMm_);
    if (exact) {
        solverOptions.method = SolverOptions::Method::Exact;
        exact_ = std::make_unique<Reconstruction>();
        exact_->prepare(rest_, points, solverOptions);
    }
}

TakeSolver::~TakeSolver() = default;

Positions TakeSolver::predictedMarkers(const Positions& V) const {
    return solver_.markerPositions(V);
}

Positions TakeSolver::trackFrame(int frame, bool filled) const {
    const std::size_t frames = track_->frames(), f = static_cast<std::size_t>(frame);
    const int maxFrames = static_cast<int>(std::floor(options_.fillGapSeconds * track_->rate()));
    // gapFilled looks at most maxFrames + 2 frames either side of the frame; the window always
    // holds that much, so a frame reads the same whichever window it was read through.
    const std::size_t margin =
        std::min(frames, static_cast<std::size_t>(std::max(0, maxFrames)) + 2);
    const std::size_t from = f >= margin ? f - margin : 0, to = std::min(frames, f + margin + 1);
    std::lock_guard<std::mutex> lock(windowMutex_);
    if (from < windowFirst_ || to > windowFirst_ + window_.frames()) {
        windowFirst_ = from;
        window_ = track_->read(from, std::min(frames - from, to - from + kWindowAhead));
    }
    const std::size_t w = f - windowFirst_;
    Positions T(window_.points(), 3);
    for (int k = 0; k < T.rows(); ++k) {
        auto x = window_.position(w, k);
        if (!x && filled) x = gapFilled(window_, w, k, maxFrames);
        if (x)
            T.row(k) = x->transpose();
        else
            T.row(k).setConstant(std::numeric_limits<double>::quiet_NaN());
    }
    return T;
}

Positions TakeSolver::recorded(int frame) const {
    const C3dSamples samples = track_->recorded(static_cast<std::size_t>(frame));
    Positions T(samples.points(), 3);
    for (int k = 0; k < T.rows(); ++k)
        if (const auto x = samples.position(0, k))
            T.row(k) = calibration_.takeToMesh.apply(*x).transpose();
        else
            T.row(k).setConstant(std::numeric_limits<double>::quiet_NaN());
    return T;
}

Positions TakeSolver::targets(int frame, bool filled) const {
    Positions T = trackFrame(frame, filled);
    for (int k = 0; k < T.rows(); ++k)
        if (T.row(k).allFinite())
            T.row(k) = calibration_.takeToMesh.apply(T.row(k).transpose()).transpose();
    return T;
}

Positions TakeSolver::solve(int frame, FrameReport& report, const std::atomic<bool>* stop) {
    if (frame < 0 || frame >= frameCount())
        throw Error(track_->file() + ": frame " + std::to_string(frame) + " is outside the take");
    const auto start = std::chrono::steady_clock::now();
    // What was seen: the residual is measured on it. Unfiltered, the read window already holds it.
    const Positions T = track_->filtered() ? recorded(frame) : targets(frame);
    Positions pull = targets(frame, true);
    report = {};
    report.frame = frame;
    // A frame without a marker has no pose of its own: it holds the nearest frame's that has
    // one, as an animator holds a pose, and so whichever frames were solved before it. Solved
    // from nothing, it was the rest mesh where the mesh file stands.
    if (!pull.array().isFinite().any()) {
        const int held = track_->nearestSeen(frame);
        if (held >= 0 && held != frame) {
            pull = targets(held, true);
            report.heldFrom = held;
        }
    }
    SolveResult result = solver_.solve(pull, nullptr, stop);
    if (result.report.stopped) {
        report.stopped = true;
        followWelds(rest_, result.V);
        return result.V;
    }
    if (exact_ && result.V.allFinite()) {
        // Refined from the local/global answer, so that the exact answer has no history either.
        SolveResult refined = exact_->solve(pull, &result.V, stop);
        if (refined.report.stopped) {
            report.stopped = true;
            followWelds(rest_, refined.V);
            return refined.V;
        }
        refined.report.iterations += result.report.iterations;
        result = std::move(refined);
    }
    if (!result.V.allFinite()) {
        // Never NaN: the rest pose moved rigidly onto what markers the frame has.
        Positions restMarkers(T.rows(), 3);
        for (int k = 0; k < T.rows(); ++k)
            restMarkers.row(k) = rest_.V.row(solver_.markerVertices()[k]);
        const RigidMotion motion = fitRigidMotion(restMarkers, T);
        for (int v = 0; v < rest_.vertexCount(); ++v)
            result.V.row(v) = motion.apply(rest_.V.row(v).transpose()).transpose();
    }
    // The solver moves a welded vertex's copies rigidly, as vertices no face uses: they take its
    // place, so that a seam the file splits stays closed in every output.
    followWelds(rest_, result.V);
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
    report.foldedFaces = result.report.foldedFaces;
    report.dentRatio = dents_->worstRatio(result.V);
    report.milliseconds =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    return result.V;
}

}  // namespace boneless
