#pragma once

#include <QMetaType>
#include <QObject>
#include <QString>
#include <memory>
#include <vector>

#include "boneless/Alignment.h"
#include "boneless/TakeSolver.h"

namespace boneless::ui {

class Document;

// One solved frame, ready to draw.
struct FrameResult {
    int frame = -1;
    quint64 generation = 0;  // which problem it belongs to (see FrameSolver::setProblem)
    quint64 request = 0;     // which requestFrame() it answers, numbered from 1; 0 if unasked
    Positions V;             // the posed mesh, #V by 3
    // Every marker row of the Document (markerCount() by 3) in mesh coordinates, with the
    // solver's alignment; NaN rows where missing.
    Positions markers;
    // Per marker row: distance in mm between the marker and where the posed mesh predicts it
    // (vertex + offset along the normal); NaN for unmapped or missing markers.
    std::vector<double> residualMm;
    // Per vertex |v_i − F_i(V)| in mesh units, when FrameSolver::setShapeErrorEnabled(true);
    // else empty. Unencoded vertices have 0.
    std::vector<double> shapeError;
    FrameReport report;  // residual RMS/max in mm, iterations, folded faces, solve milliseconds
    Calibration calibration;  // the alignment used
    // What the frame was solved against (#V by 3): the calibrated rest when calibrating, else
    // the mesh's rest; one copy shared by every frame of a generation.
    std::shared_ptr<const Positions> rest;
    double solveMs = 0;  // wall time of the solve (0 for a cache hit)
    bool fromCache = false;

    std::size_t bytes() const;
};

// Solves frames on a worker thread, never on the caller's: requestFrame() returns at once and
// frameReady() follows on the thread FrameSolver lives in. Requests that are still queued when a
// newer one arrives are dropped, and the frame being solved is stopped at its next iteration if
// it is less than half done. Answers are delivered in request order: one to an older request
// that comes after a newer request's answer is not delivered (it is cached), so the last frame
// delivered is always the answer to the newest request answered so far. Solved frames are cached,
// least recently used out first, up to a memory cap.
//
// Each frame is solved from its own markers alone (TakeSolver keeps nothing from the frames it
// solved before), so a cached frame, the same frame solved again after any others, and that
// frame in an exported file agree exactly (the file to the digits it writes). A frame takes a few
// milliseconds on small meshes and up to a couple of hundred on large ones, so what the user
// sees is always the frame's answer, with no preview: while scrubbing, the worker takes the
// newest frame whenever it is free, and once the playhead stops its frame follows the solve in
// flight. While playing, the worker also reads ahead (setReadAhead()): when no request waits it
// solves the frames after the last one asked for into the cache, so that the playhead finds them
// there; but not while requests come faster than it solves them (a large mesh playing): those
// frames would be passed by the time they were solved, so it waits for the newest request: the
// frame shown is where the playhead was when its solve began (docs/view.md, "Large inputs").
class FrameSolver : public QObject {
    Q_OBJECT
  public:
    explicit FrameSolver(QObject* parent = nullptr);
    ~FrameSolver() override;  // waits for the frame being solved

    // Takes a copy of what the document's solve needs (mesh, take, map, solveOptions()), empties
    // the cache and starts a new generation. Returns false (with *why) when the document cannot
    // be solved; frames are then not solved until the next successful call.
    bool setProblem(const Document& document, QString* why = nullptr);
    void clearProblem();
    // Follows a document: after any change of its mesh, take, map, alignment or settings (several
    // changes in one event-loop turn count as one) calls setProblem() and emits problemChanged().
    void watch(const Document* document);
    bool hasProblem() const;
    quint64 generation() const;

    // Cache cap in bytes (default: the QSettings value "solver/cacheMegabytes", 256 MB if unset).
    void setCacheLimit(std::size_t bytes);
    std::size_t cacheLimit() const;
    std::size_t cacheBytes() const;
    int cachedFrames() const;
    bool isCached(int frame) const;
    void setShapeErrorEnabled(bool enabled);  // clears the cache when it changes

    // Asks for a frame; a cached frame is delivered without solving (still asynchronously).
    void requestFrame(int frame);
    // Drops queued requests (the frame being solved still finishes and is cached).
    void cancelPending();
    bool isBusy() const;  // a request queued or being solved
    // Up to `frames` frames after the last request (past the last frame to the first when
    // `wrap`) are solved into the cache, one at a time, while no request waits; a request waits
    // at most for the one read-ahead frame in flight. They are never delivered unasked and count
    // against the cache cap. 0, the default, turns it off (scrubbing wants the worker free).
    void setReadAhead(int frames, bool wrap = false);

    // Times `frames` solved as an export solves each of its frames: on the worker alone, its
    // loops on one core (RunSerially), while the export runs a solver per core. A preview frame's
    // time is no measure of that: its loops share the cores, with each other and with the
    // drawing. Requests come first; each timed frame is cached, not delivered, and
    // frameTimed() follows. Replaces the frames still to time; a new problem drops them.
    void timeFrames(const std::vector<int>& frames);

    // How long building the solver for the current problem took (aligning, calibrating,
    // factorising) in milliseconds; 0 until its first frame is solved. An export of the same
    // problem prepares as much before its first frame (ExportDialog's estimate adds it).
    double preparationMs() const;
    // The calibrated rest the current problem's solver fitted, when it is built, calibrates, and
    // `document`'s mesh, take, map and solve options are still the ones it was built from; else
    // null. An export passes it on (TakeSolveOptions::calibratedRest) rather than fitting again.
    std::shared_ptr<const Positions> calibratedRestFor(const Document& document) const;

    static std::size_t defaultCacheLimit();  // from QSettings

  signals:
    void frameReady(const boneless::ui::FrameResult& result);
    // A frame timeFrames() asked for: its solve's milliseconds on one core, and its problem.
    void frameTimed(int frame, double milliseconds, quint64 generation);
    // Building the solver for a generation failed (bad map for this take, ...): the message.
    void failed(const QString& message);
    void busyChanged(bool busy);
    // After each setProblem() or clearProblem(), watch()'s included: solvable or why not. Cached
    // frames are gone, so the window asks for its current frame again and the timeline strip
    // drops its solved marks.
    void problemChanged(bool solvable, const QString& why);

  private:
    struct Shared;
    std::shared_ptr<Shared> shared_;
    static void run(Shared* shared, FrameSolver* self);
    void deliver(std::shared_ptr<const FrameResult> result);
    void deliverHit(const FrameResult& hit, quint64 request);  // queued, from any thread
    void deliverFailure(quint64 generation, const QString& message);
    void updateBusy();
    const Document* watched_ = nullptr;
    bool refreshQueued_ = false;
    bool busy_ = false;
    quint64 delivered_ = 0;  // the newest request answered
};

}  // namespace boneless::ui

Q_DECLARE_METATYPE(boneless::ui::FrameResult)
