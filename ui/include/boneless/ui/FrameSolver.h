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
    FrameReport report;       // residual RMS/max in mm, iterations, solve milliseconds
    Calibration calibration;  // the alignment used
    double solveMs = 0;       // wall time of the solve (0 for a cache hit)
    bool fromCache = false;
    // A fast preview of the frame (see FrameSolver::setPreviewEnabled), never cached: the
    // frame's own solve follows and replaces it.
    bool preview = false;

    std::size_t bytes() const;
};

// Solves frames on a worker thread, never on the caller's: requestFrame() returns at once and
// frameReady() follows on the thread FrameSolver lives in. Requests that are still queued when a
// newer one arrives are dropped (the frame being solved finishes and is cached, since a frame
// cannot be interrupted halfway). Solved frames are cached, least recently used out first, up to
// a memory cap.
//
// A frame is solved warm-started from the frame the worker solved last, as in a sequential solve;
// so a frame's shape can differ slightly with the order frames were visited in.
//
// With previews on, a second worker answers each uncached request first with a preview: the
// multiresolution solver's coarsest level, prolonged to the mesh, without the orientation guard
// (tens of milliseconds where the solve takes seconds on a large mesh). The solve of a frame then
// starts only once it has been the newest request for settleMs, so that scrubbing shows previews
// at once and does not queue solves of frames the user has already left, and only once the
// preview being solved is done, so that the preview is posted before the answer that follows
// it. (Measured on the koala, 100K faces: the first frame, whose preview is slow, is shown as
// soon as when the two were solved side by side; on two cores they only slowed each other.)
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
    // Off by default; the window turns it on from the QSettings value "solver/preview". Meshes
    // with fewer than minVertices get none: their frames solve in a few hundred milliseconds,
    // which a preview would only delay by settleMs.
    void setPreviewEnabled(bool enabled, int minVertices = 5000);
    bool previewEnabled() const;
    static constexpr int settleMs = 150;

    // Asks for a frame; a cached frame is delivered without solving (still asynchronously).
    void requestFrame(int frame);
    // Drops queued requests (the frame being solved still finishes and is cached).
    void cancelPending();
    bool isBusy() const;  // a request (or its preview) queued or being solved

    static std::size_t defaultCacheLimit();  // from QSettings

  signals:
    void frameReady(const boneless::ui::FrameResult& result);
    // Building the solver for a generation failed (bad map for this take, ...): the message.
    void failed(const QString& message);
    void busyChanged(bool busy);
    // After watch()'s automatic setProblem(): solvable or why not. Cached frames are gone, so the
    // window asks for its current frame again.
    void problemChanged(bool solvable, const QString& why);

  private:
    struct Shared;
    std::shared_ptr<Shared> shared_;
    static void runPreviews(Shared* shared, FrameSolver* self);
    void deliver(std::shared_ptr<const FrameResult> result);
    void deliverFailure(quint64 generation, const QString& message);
    void updateBusy();
    const Document* watched_ = nullptr;
    bool refreshQueued_ = false;
    bool busy_ = false;
};

}  // namespace boneless::ui

Q_DECLARE_METATYPE(boneless::ui::FrameResult)
