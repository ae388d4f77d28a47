#pragma once

#include <QElapsedTimer>
#include <QObject>
#include <QString>
#include <optional>

#include "boneless/TriMesh.h"
#include "boneless/ui/FrameSolver.h"

class QTimer;

namespace boneless::ui {

class Document;
class MarkerListModel;
class MeshView;
class Timeline;

// Keeps the view showing the timeline's frame: asks the FrameSolver for it, draws what comes
// back (mesh, markers, trails, heat map) and tells the window what to put in the status bar.
// Without a solvable problem (no take, fewer than 3 markers mapped) it shows the rest mesh and
// the take's markers placed by the document's alignment, which is what authoring needs.
class FrameDisplay : public QObject {
    Q_OBJECT
  public:
    // What the view shows of a solved frame: the frame itself, the rest it was solved against
    // (the calibrated rest when calibrating: the mesh in the actor's proportions and pose at the
    // calibration frame), or the mesh's own rest. On a rest the mapped markers are drawn at their
    // vertices, and no trails: the take's, around this frame, would float off the body.
    enum class Shown { Frame, CalibratedRest, Rest };
    FrameDisplay(Document* document, FrameSolver* solver, Timeline* timeline, MeshView* view,
                 MarkerListModel* markers, QObject* parent = nullptr);

    void setTrailsVisible(bool visible);
    void setHeatMapVisible(bool visible);
    void setShown(Shown shown);
    Shown shown() const { return shown_; }
    bool trailsVisible() const { return trails_; }
    bool heatMapVisible() const { return heatMap_; }

    // While mapping markers the picture holds still (mesh, markers, camera) whatever is solved or
    // wherever the playhead goes, so the surface does not move under the cursor as each mapping
    // re-solves; mapping states still update. Unfreezing shows the playhead's frame.
    void setFrozen(bool frozen);
    bool frozen() const { return frozen_; }

    bool solving() const { return solving_; }
    QString notSolvingReason() const { return notSolvingReason_; }
    int displayedFrame() const { return displayedFrame_; }
    // The timeline's frame has been drawn (solved, or unsolved when nothing can be solved).
    bool upToDate() const;
    const std::optional<FrameResult>& lastResult() const { return result_; }
    // Moves the camera to the marker where it is shown (or, missing this frame, to its point).
    // False when it has neither.
    bool frameMarker(int marker);

  public slots:
    // Rebuilds the solver's problem from the document on the next turn of the event loop, so
    // that a project load's many change signals cost one rebuild.
    void scheduleProblem();

  signals:
    void frameDisplayed(int frame);
    // solveDetail: what `solve` leaves out (the whole list of markers it names a few of).
    void statusChanged(const QString& frame, const QString& solve, const QString& residual,
                       const QString& solveDetail);
    // From the frame request to the end of the render that shows it.
    void latencyMeasured(int frame, double milliseconds, bool fromCache);
    void solverFailed(const QString& message);
    // The mesh is too large to solve in the memory the process may use (Document::memoryRefusal):
    // once per mesh and method, not at each edit. The mesh is still shown, unsolved.
    void solveRefused(const QString& message);

  private:
    // Where the marker's point of the surface is as the view draws the mesh; none if unmapped.
    std::optional<Vec3> mappedPosition(int marker) const;
    void onMeshChanged();
    void onTakeChanged();
    void onFrameChanged(int frame);
    void onFrameReady(const FrameResult& result);
    void onSolverFailed(const QString& message);
    void onRendered();
    void rebuildProblem();
    void showUnsolved(int frame);
    void showResult();  // result_ as shown_ says
    void updateMarkers();
    void updateTrails(int frame);
    void updateUpAxis(bool force);
    void updateFloor();
    void emitStatus();

    Document* document_;
    FrameSolver* solver_;
    Timeline* timeline_;
    MeshView* view_;
    MarkerListModel* markers_;
    QTimer* problemTimer_;

    bool solving_ = false;
    bool upPending_ = false;  // the up axis changed while mapping held the camera
    QString notSolvingReason_;
    QString notSolvingDetail_;  // the reason's whole list
    QString refusalShown_;      // the last solveRefused() message, while it still holds
    int carriedParts_ = 0;  // the mesh's parts with no marker, carried rigidly (as the CLI says)
    bool trails_ = false, heatMap_ = false;
    Shown shown_ = Shown::Frame;
    bool frozen_ = false;
    int displayedFrame_ = -1;
    std::optional<FrameResult> result_;
    Positions markerPositions_;
    bool markersOnRest_ = false;  // markerPositions_ follow the map onto the rest shown
    Eigen::Vector3d up_ = Eigen::Vector3d::UnitY();

    int requestedFrame_ = -1;
    QElapsedTimer requestClock_;
    bool awaitingRender_ = false;
    bool renderFromCache_ = false;
};

}  // namespace boneless::ui
