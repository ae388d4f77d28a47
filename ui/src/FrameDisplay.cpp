#include "FrameDisplay.h"

#include <utility>

#include <QFileInfo>
#include <QStringList>
#include <QTimer>
#include <cmath>
#include <limits>

#include "Counted.h"
#include "FloorGrid.h"
#include "boneless/Reconstruction.h"
#include "boneless/TakeExport.h"
#include "boneless/ui/Document.h"
#include "boneless/ui/MarkerListModel.h"
#include "boneless/ui/MeshView.h"
#include "boneless/ui/Timeline.h"

namespace boneless::ui {
namespace {
constexpr int kTrailFrames = 20;
// The heat map's scale reaches at least this: below it, about a capture's marker noise, a frame
// reads as no shape error (docs/view.md), where a frame at rest showed its 1e-6 mm as red.
constexpr double kShapeErrorFloorMm = 2.0;
}  // namespace

FrameDisplay::FrameDisplay(Document* document, FrameSolver* solver, Timeline* timeline,
                           MeshView* view, MarkerListModel* markers, QObject* parent)
    : QObject(parent),
      document_(document),
      solver_(solver),
      timeline_(timeline),
      view_(view),
      markers_(markers),
      problemTimer_(new QTimer(this)) {
    problemTimer_->setSingleShot(true);
    problemTimer_->setInterval(0);
    connect(problemTimer_, &QTimer::timeout, this, &FrameDisplay::rebuildProblem);

    connect(document_, &Document::meshChanged, this, &FrameDisplay::onMeshChanged);
    connect(document_, &Document::takeChanged, this, &FrameDisplay::onTakeChanged);
    connect(document_, &Document::correspondenceChanged, this, [this] {
        updateMarkers();
        updateUpAxis(false);  // a map opened after the take is what first says which way is up
        scheduleProblem();
    });
    connect(document_, &Document::alignmentChanged, this, [this] {
        updateUpAxis(false);
        scheduleProblem();
    });
    connect(document_, &Document::settingsChanged, this, &FrameDisplay::scheduleProblem);
    connect(document_, &Document::selectionChanged, this, &FrameDisplay::updateMarkers);
    connect(timeline_, &Timeline::frameChanged, this, &FrameDisplay::onFrameChanged);
    connect(solver_, &FrameSolver::frameReady, this, &FrameDisplay::onFrameReady);
    connect(solver_, &FrameSolver::failed, this, &FrameDisplay::onSolverFailed);
    connect(view_, &MeshView::rendered, this, &FrameDisplay::onRendered);
    connect(timeline_, &Timeline::playingChanged, view_, &MeshView::setPlaying);
}

void FrameDisplay::setTrailsVisible(bool visible) {
    trails_ = visible;
    updateTrails(displayedFrame_);
}

void FrameDisplay::setHeatMapVisible(bool visible) {
    if (heatMap_ == visible) return;
    heatMap_ = visible;
    solver_->setShapeErrorEnabled(visible);
    if (!visible) view_->setHeatMap({}, {});
    // The cache was emptied: the shown frame has no shape error yet.
    if (solving_) onFrameChanged(timeline_->frame());
}

void FrameDisplay::setFrozen(bool frozen) {
    if (frozen_ == frozen) return;
    frozen_ = frozen;
    if (frozen_) {
        emitStatus();
        return;
    }
    if (std::exchange(upPending_, false)) {
        updateUpAxis(false);
        updateFloor();
    }
    onFrameChanged(timeline_->frame());
}

bool FrameDisplay::upToDate() const {
    const int frame = timeline_->frame();
    // While solving, only a solved frame counts: the unsolved picture shown before the problem
    // was built has the right frame number but the rest pose.
    const bool solved = !solving_ || (result_ && result_->frame == frame);
    return !problemTimer_->isActive() && displayedFrame_ == frame && solved && !awaitingRender_;
}

void FrameDisplay::scheduleProblem() {
    problemTimer_->start();
    emitStatus();  // the picture is the old problem's answer until the new one's comes
}

void FrameDisplay::onMeshChanged() {
    result_.reset();
    displayedFrame_ = -1;
    updateUpAxis(true);
    if (document_->hasMesh())
        view_->setMesh(document_->mesh(), up_);
    else
        view_->clearMesh();
    scheduleProblem();
}

void FrameDisplay::onTakeChanged() {
    timeline_->setRate(document_->frameRate());
    timeline_->setFirstFrame(document_->hasTake() ? document_->take().firstFrame : 0);
    timeline_->setFrameCount(document_->frameCount());
    updateUpAxis(false);
    scheduleProblem();
}

void FrameDisplay::updateUpAxis(bool force) {
    Eigen::Vector3d up = Eigen::Vector3d::UnitY();
    // Whichever alignment places the markers (roughAlignment's before three are mapped) says
    // which way the take's vertical points on the mesh.
    if (document_->hasTake() && document_->hasMesh())
        up = upAxisVector(QString::fromStdString(
            guessUpAxis(document_->displayAlignment().takeToMesh, document_->take().vertical)));
    if (!force && up.isApprox(up_)) return;
    if (!force && frozen_) {  // mapping holds the camera still: turn it when mapping ends
        upPending_ = true;
        return;
    }
    up_ = up;
    if (!force) view_->setUpAxis(up_);
}

void FrameDisplay::rebuildProblem() {
    QString why;
    solving_ = document_->hasMesh() && solver_->setProblem(*document_, &why);
    if (!document_->hasMesh()) document_->canSolve(&why);  // "No mesh is loaded."
    notSolvingReason_ = solving_ ? QString() : why;
    notSolvingDetail_.clear();
    if (!solving_) document_->canSolve(nullptr, &notSolvingDetail_);
    const QString refusal = document_->memoryRefusal();
    if (!refusal.isEmpty() && refusal != refusalShown_) emit solveRefused(refusal);
    refusalShown_ = refusal;
    result_.reset();
    if (!solving_) solver_->clearProblem();
    // A part with no marker (a prop, a detached eye) is not solved but carried: the CLI says so,
    // and the view alone showed it moving stiffly with nothing to say why.
    carriedParts_ = 0;
    if (solving_) {
        std::vector<int> markerVertices;
        for (int k = 0; k < document_->markerCount(); ++k)
            if (document_->mappedVertex(k) >= 0)
                markerVertices.push_back(document_->mappedVertex(k));
        carriedParts_ = componentsWithoutMarkers(document_->mesh(), markerVertices);
    }
    updateFloor();
    onFrameChanged(timeline_->frame());
}

void FrameDisplay::onSolverFailed(const QString& message) {
    // Nothing of this problem will be solved: say so, and show the take on the unposed mesh
    // rather than the last problem's answer under a "solving" that never ends.
    solving_ = false;
    notSolvingReason_ = tr("the take could not be solved with this map and settings");
    notSolvingDetail_.clear();
    result_.reset();
    showUnsolved(timeline_->frame());
    emit solverFailed(message);
}

void FrameDisplay::onFrameChanged(int frame) {
    if (frozen_) {
        emitStatus();
        return;
    }
    markers_->setFrame(frame);
    if (!document_->hasMesh()) {
        // Nothing to pose: the frame is shown as it is (the take's markers), and the status
        // says why, where "preparing the solver" stayed up for ever.
        displayedFrame_ = frame;
        timeline_->frameShown(frame);  // Every Frame playback waits for it
        emitStatus();
        return;
    }
    if (!solving_) {
        showUnsolved(frame);
        return;
    }
    requestedFrame_ = frame;
    requestClock_.start();
    solver_->requestFrame(frame);
    emitStatus();
}

void FrameDisplay::showUnsolved(int frame) {
    displayedFrame_ = frame;
    view_->setPositions(document_->mesh().V);
    markersOnRest_ = false;
    markerPositions_ = document_->markerPositions(frame);
    updateMarkers();
    updateTrails(frame);
    view_->setHeatMap({}, {});
    // Shown as it is: Every Frame playback, waiting for each frame to be shown, stood still
    // on a take with too few markers mapped to solve (when a user scrubs it to map them).
    timeline_->frameShown(frame);
    emitStatus();
    emit frameDisplayed(frame);
}

void FrameDisplay::onFrameReady(const FrameResult& result) {
    if (!solving_ || result.generation != solver_->generation() || frozen_) return;
    // A frame solved for an older request is still shown: during playback the newest request
    // is usually still in the solver, and showing nothing would freeze the picture.
    result_ = result;
    displayedFrame_ = result.frame;
    showResult();
    markers_->setFrameResult(result);
    if (result.frame == requestedFrame_) {
        awaitingRender_ = true;
        renderFromCache_ = result.fromCache;
    }
    timeline_->frameShown(result.frame);
    emitStatus();
    emit frameDisplayed(result.frame);
}

void FrameDisplay::setShown(Shown shown) {
    if (shown_ == shown) return;
    shown_ = shown;
    markers_->setRestShown(shown_ != Shown::Frame);
    if (result_ && solving_) showResult();
    emitStatus();
}

void FrameDisplay::showResult() {
    const FrameResult& result = *result_;
    const bool frame = shown_ == Shown::Frame;
    if (frame)
        view_->setPositions(result.V);
    else if (shown_ == Shown::CalibratedRest && result.rest)
        view_->setPositions(*result.rest);
    else
        view_->setPositions(document_->mesh().V);
    markersOnRest_ = !frame;
    if (frame) markerPositions_ = result.markers;
    updateMarkers();
    updateTrails(result.frame);
    // The heat map is the frame's shape error: on a rest it would read as the rest's.
    if (!frame) {
        view_->setHeatMap({}, {});
    } else if (heatMap_ && !result.shapeError.empty()) {
        // Shape error comes in mesh units; a user reads millimetres, as in the residuals.
        const double meshUnitsPerMm =
            result.calibration.takeToMesh.scale / document_->take().unitToMm;
        std::vector<float> mm(result.shapeError.size());
        for (std::size_t i = 0; i < mm.size(); ++i)
            mm[i] = float(result.shapeError[i] / meshUnitsPerMm);
        view_->setHeatMap(mm, tr("Shape error (mm)"), kShapeErrorFloorMm);
    }
}

void FrameDisplay::updateFloor() {
    view_->setFloor(floorOf(*document_, up_));
}

std::optional<Vec3> FrameDisplay::mappedPosition(int marker) const {
    const SurfacePoint p = document_->mappedPoint(marker);
    const Positions& V = view_->positions();
    if (p.vertex < 0 || p.vertex >= V.rows() || p.face >= document_->mesh().faceCount() ||
        V.rows() != document_->mesh().vertexCount())
        return std::nullopt;
    return surfacePosition(document_->mesh(), V, p);
}

bool FrameDisplay::frameMarker(int marker) {
    if (marker < 0 || marker >= document_->markerCount()) return false;
    if (marker < markerPositions_.rows() && markerPositions_.row(marker).allFinite()) {
        view_->frame(markerPositions_.row(marker).transpose());
        return true;
    }
    const std::optional<Vec3> x = mappedPosition(marker);
    if (!x) return false;
    view_->frame(*x);
    return true;
}

void FrameDisplay::onRendered() {
    if (!awaitingRender_) return;
    awaitingRender_ = false;
    emit latencyMeasured(requestedFrame_, requestClock_.nsecsElapsed() / 1e6, renderFromCache_);
}

void FrameDisplay::updateMarkers() {
    const int count = document_->markerCount();
    if (markersOnRest_) {  // placed anew at each map edit, so mapping can go on on the rest
        markerPositions_ = Positions::Constant(count, 3, std::numeric_limits<double>::quiet_NaN());
        for (int k = 0; k < count; ++k)
            if (const std::optional<Vec3> x = mappedPosition(k)) markerPositions_.row(k) = *x;
    }
    if (markerPositions_.rows() != count) {
        view_->setMarkers(Positions(0, 3), {}, {});
        view_->setHighlightedPoint({});
        return;
    }
    std::vector<MarkerState> states(count, MarkerState::Unmapped);
    QStringList labels;
    for (int k = 0; k < count; ++k) {
        if (document_->mappedVertex(k) >= 0) states[k] = MarkerState::Mapped;
        labels << document_->markerLabel(k);
    }
    const int selected = document_->selectedMarker();
    if (selected >= 0 && selected < count) states[selected] = MarkerState::Selected;
    view_->setMarkers(markerPositions_, states, labels);
    view_->setHighlightedPoint(document_->mappedPoint(selected));
}

void FrameDisplay::updateTrails(int frame) {
    // Trails are the take's markers over the frames before this one, where the posed mesh meets
    // them. A rest is not posed and draws its markers at their vertices: trails would float.
    if (!trails_ || !document_->hasTake() || frame < 0 || markersOnRest_) {
        view_->setTrails({});
        return;
    }
    const int first = std::max(0, frame - kTrailFrames);
    std::vector<Positions> trails(document_->markerCount(), Positions(frame - first + 1, 3));
    for (int f = first; f <= frame; ++f) {
        const Positions P = document_->markerPositions(f);
        for (int k = 0; k < P.rows() && k < static_cast<int>(trails.size()); ++k)
            trails[k].row(f - first) = P.row(k);
    }
    view_->setTrails(trails);
}

void FrameDisplay::emitStatus() {
    const int playhead = timeline_->frame();
    // Over the last frame's number, as the timeline: a 60-frame take ends at "Frame 59 / 59";
    // then the capture's own number for it, which Vicon and MotionBuilder show.
    // Before anything is drawn (the solver being prepared) the view shows the rest mesh: the
    // playhead's frame is named, never the -1 of no frame.
    const int named = displayedFrame_ >= 0 ? displayedFrame_ : playhead;
    QString frame = document_->hasTake() ? tr("Frame %1 / %2 (capture frame %3)")
                                               .arg(named)
                                               .arg(document_->frameCount() - 1)
                                               .arg(timeline_->captureFrame(named))
                                         : tr("No take");
    if (frozen_)
        frame += tr(" (held while mapping; playhead at %1)").arg(timeline_->frameName(playhead));
    else if (document_->hasTake() && named != playhead)
        frame += tr(" (preview; playhead at %1)").arg(timeline_->frameName(playhead));
    QString solve, residual, solveDetail;
    const bool current = result_ && result_->frame == playhead && !problemTimer_->isActive();
    if (frozen_) {
        solve = tr("mapping markers");
    } else if (!solving_ && !problemTimer_->isActive()) {
        solve = notSolvingReason_.isEmpty() ? tr("Not solving")
                                            : tr("Not solving: %1").arg(notSolvingReason_);
        solveDetail = notSolvingDetail_;
    } else if (!result_) {
        // No frame of this problem yet: the solver is being built (calibrated, factorised),
        // seconds on a large mesh, which "solving frame 0…" did not say.
        const QString mesh = QFileInfo(document_->meshPath()).fileName();
        solve = document_->settings().calibrate == CalibrateMode::None
                    ? tr("preparing the solver for %1 (factorising)…").arg(mesh)
                    : tr("preparing the solver for %1 (calibrating, factorising)…").arg(mesh);
    } else if (!current) {
        solve = tr("solving frame %1…").arg(timeline_->frameName(playhead));
    } else if (shown_ == Shown::CalibratedRest) {
        // The frame's solve time and residual would read as the rest's.
        solve = document_->settings().calibrate == CalibrateMode::None
                    ? tr("showing the rest (not calibrated)")
                    : tr("showing the calibrated rest, fitted at frame %1")
                          .arg(timeline_->frameName(result_->calibration.frame));
    } else if (shown_ == Shown::Rest) {
        solve = tr("showing the rest");
    } else {
        solve = result_->fromCache ? tr("cached")
                                   : tr("solved in %1 ms").arg(result_->solveMs, 0, 'f', 0);
        if (carriedParts_ > 0) {
            solve += ", " + counted(carriedParts_, tr("%n part carried rigidly"),
                                    tr("%n parts carried rigidly"));
            solveDetail = counted(carriedParts_,
                                  tr("%n component of the mesh carries no marker: it follows the "
                                     "nearest marked part rigidly."),
                                  tr("%n components of the mesh carry no marker: each follows the "
                                     "nearest marked part rigidly."));
        }
        // Frames meet their markers even on a take aligned 200 mm off: the alignment's own
        // residual says that. The solver measures it, found or given: a project's stored
        // residual is only what the file says.
        const Calibration& aligned = result_->calibration;
        const QString alignment =
            tr("alignment %1 mm").arg(aligned.residualMm(document_->take().unitToMm), 0, 'f', 1);
        residual = result_->report.heldFrom >= 0
                       ? tr("no marker seen: holding the pose of frame %1, %2")
                             .arg(timeline_->frameName(result_->report.heldFrom))
                             .arg(alignment)
                       : tr("residual %1 mm (max %2), %3")
                             .arg(result_->report.residualRmsMm, 0, 'f', 2)
                             .arg(result_->report.residualMaxMm, 0, 'f', 2)
                             .arg(alignment);
    }
    emit statusChanged(frame, solve, residual, solveDetail);
}

}  // namespace boneless::ui
