#include "boneless/ui/FrameSolver.h"

#include <QMetaObject>
#include <QSettings>
#include <QTimer>
#include <atomic>
#include <chrono>
#include <cmath>
#include <condition_variable>
#include <cstring>
#include <deque>
#include <limits>
#include <mutex>
#include <optional>
#include <thread>

#include <nlohmann/json.hpp>
#include "boneless/MeshTopology.h"
#include "boneless/Parallel.h"
#include "boneless/ShapeEncoding.h"
#include "boneless/TakeOptionsJson.h"
#include "boneless/ui/Document.h"
#include "boneless/ui/FrameCache.h"

namespace boneless::ui {

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// What a generation solves: copies, so that the document may change while the worker runs.
struct Problem {
    TriMesh mesh;
    C3dTake take;
    Correspondence map;
    TakeSolveOptions options;
    std::vector<int> rowPoint;    // Document marker row -> take point
    std::vector<int> rowMapping;  // Document marker row -> map entry, -1
};

}  // namespace

std::size_t FrameResult::bytes() const {
    return sizeof(FrameResult) +
           sizeof(double) * (V.size() + markers.size() + residualMm.size() + shapeError.size());
}

struct FrameSolver::Shared {
    std::mutex mutex;
    std::condition_variable wake;
    bool stop = false;
    quint64 generation = 0;
    std::shared_ptr<const Problem> problem;
    std::optional<int> pending;
    quint64 requests = 0;                // requests numbered in order, the newest last
    quint64 pendingRequest = 0;          // the number of `pending`
    bool solving = false;                // a requested frame (not a read-ahead one) is being solved
    std::optional<int> inFlight;         // the frame being solved, requested or read ahead
    std::atomic<bool> stopSolve{false};  // raised when a request elsewhere supersedes it
    std::chrono::steady_clock::time_point inFlightSince;
    double lastSolveMs = 0;       // how long the last frame took, for how far along this one is
    bool lastSuperseded = false;  // the last solve was stopped by a request: this one finishes
    bool shapeError = false;
    // The current generation's solver, once built: how long that took, and its calibrated rest.
    quint64 preparedGeneration = 0;
    double preparationMs = 0;
    std::shared_ptr<const Positions> preparedRest;
    std::deque<int> toTime;          // timeFrames()'s frames not yet timed
    std::optional<int> lastRequest;  // where read-ahead starts
    int readAhead = 0;
    bool wrap = false;
    // The last request missed the cache while an older one was still unanswered: requests come
    // faster than frames are solved (playback of a large mesh), so the frames after the one
    // answered are passed by the time they would be solved, and the worker reads none ahead.
    bool behind = false;
    FrameCache cache;
    std::thread worker;

    // The first uncached frame of the read-ahead window, if any. The window shrinks to what the
    // cache holds, and its cached frames and the request are marked used, so that read-ahead
    // evicts other frames, never its own.
    std::optional<int> nextAhead() {
        if (!problem || !lastRequest || readAhead <= 0 || behind) return std::nullopt;
        const int frames = int(problem->take.frameCount());
        const std::size_t frameBytes = cache.lastFrameBytes();
        const std::size_t fits =
            frameBytes ? cache.limit() / frameBytes : std::size_t(readAhead) + 1;
        const int window = int(std::min(std::size_t(readAhead) + 1, fits)) - 1;
        std::optional<int> next;
        for (int i = window; i >= 0; --i) {
            if (*lastRequest + i >= frames && !wrap) continue;
            const int frame = (*lastRequest + i) % frames;
            if (i > 0 && frame == *lastRequest) continue;  // a take shorter than the window
            if (!cache.use(frame) && i > 0) next = frame;  // the nearest one wins
        }
        return next;
    }
    // A request for `frame` arrived: the frame being solved is no longer wanted first. It is
    // stopped if less than half done (by the last frame's time), so that a scrub that stops
    // waits for one iteration of it at most, while one over a fast mesh still shows the frames
    // it passes (as previews: see FrameSolver::deliver). Never two in a row: requests that come
    // faster than half a solve (playback on a slow machine) would otherwise stop every solve,
    // and the view would stay on one frame for as long as they come.
    void supersede(int frame) {
        const double elapsedMs = std::chrono::duration<double, std::milli>(
                                     std::chrono::steady_clock::now() - inFlightSince)
                                     .count();
        if (inFlight && *inFlight != frame && !lastSuperseded && elapsedMs < 0.5 * lastSolveMs) {
            stopSolve = true;
            lastSuperseded = true;
        }
    }
};

namespace {

// Empty when `stop` was raised before the frame was done.
std::shared_ptr<FrameResult> solveOne(TakeSolver& solver, const Problem& p, int frame,
                                      const ShapeEncoding* encoding,
                                      const std::atomic<bool>* stop) {
    auto r = std::make_shared<FrameResult>();
    r->frame = frame;
    const auto t0 = std::chrono::steady_clock::now();
    r->V = solver.solve(frame, r->report, stop);
    if (r->report.stopped) return nullptr;
    r->solveMs =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
    r->calibration = solver.calibration();
    const Similarity& s = r->calibration.takeToMesh;
    const double meshUnitsPerMm = s.scale / p.take.unitToMm;

    const int rows = int(p.rowPoint.size());
    r->markers = Positions::Constant(rows, 3, kNaN);
    r->residualMm.assign(rows, kNaN);
    const Positions targets = solver.targets(frame);
    const Positions predicted = solver.predictedMarkers(r->V);
    for (int row = 0; row < rows; ++row) {
        if (const auto x = p.take.samples.position(frame, p.rowPoint[row]))
            r->markers.row(row) = s.apply(*x).transpose();
        const int k = p.rowMapping[row];
        if (k >= 0 && k < targets.rows() && targets.row(k).allFinite())
            r->residualMm[row] = (predicted.row(k) - targets.row(k)).norm() / meshUnitsPerMm;
    }
    if (encoding) {
        r->shapeError.assign(r->V.rows(), 0.0);
        for (int v = 0; v < encoding->vertexCount(); ++v)
            if (encoding->encoded(v))
                r->shapeError[v] = (r->V.row(v).transpose() - encoding->decode(v, r->V)).norm();
    }
    return r;
}

// The solver and shape encoding the worker keeps for one generation.
struct WorkerState {
    std::unique_ptr<TakeSolver> solver;
    std::shared_ptr<const Positions> rest;  // the solver's rest, handed to every result
    std::unique_ptr<MeshTopology> topology;
    std::unique_ptr<ShapeEncoding> encoding;
    quint64 generation = 0, failedGeneration = 0;
    double preparationMs = 0;  // building `solver`

    std::shared_ptr<FrameResult> solve(const Problem& p, quint64 gen, int frame,
                                       bool wantShapeError, const std::atomic<bool>* stop,
                                       bool serially = false) {
        if (generation != gen) {
            solver.reset();
            encoding.reset();
            topology.reset();
            const auto t0 = std::chrono::steady_clock::now();
            solver = std::make_unique<TakeSolver>(p.mesh, p.take, p.map, p.options);
            preparationMs =
                std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0)
                    .count();
            rest = std::make_shared<const Positions>(solver->rest().V);
            generation = gen;
        }
        if (wantShapeError && !encoding) {
            topology = std::make_unique<MeshTopology>(p.mesh);
            encoding = std::make_unique<ShapeEncoding>(p.mesh, *topology);
        }
        std::optional<RunSerially> oneCore;
        if (serially) oneCore.emplace();
        auto result = solveOne(*solver, p, frame, wantShapeError ? encoding.get() : nullptr, stop);
        oneCore.reset();
        if (!result) return nullptr;
        result->generation = gen;
        result->rest = rest;
        return result;
    }
    void fail(quint64 gen) {
        solver.reset();
        generation = 0;
        failedGeneration = gen;
    }
};

}  // namespace

// The worker: owns the solver, only ever touches `sh` and posts results back to `self`. No delay
// before a solve: the newest request is taken as soon as the worker is free, so a scrub shows
// answers as it goes and a stop waits for at most the solve in flight. With no request waiting
// it solves the read-ahead frames one at a time, looking for a request between them.
void FrameSolver::run(Shared* sh, FrameSolver* self) {
    WorkerState state;
    for (;;) {
        std::unique_lock lock(sh->mutex);
        sh->wake.wait(lock, [&] {
            return sh->stop ||
                   (sh->problem && (sh->pending || !sh->toTime.empty() || sh->nextAhead()));
        });
        if (sh->stop) return;
        const bool requested = sh->pending.has_value();
        // Timed after the requests, before reading ahead, which would find them cached.
        const bool timed = !requested && !sh->toTime.empty();
        const int frame = requested ? *sh->pending : timed ? sh->toTime.front() : *sh->nextAhead();
        if (timed) sh->toTime.pop_front();
        const quint64 request = requested ? sh->pendingRequest : 0;
        sh->pending.reset();
        const quint64 generation = sh->generation;
        const std::shared_ptr<const Problem> problem = sh->problem;
        const bool wantShapeError = sh->shapeError;
        if (generation == state.failedGeneration) {  // reported once already
            sh->lastRequest.reset();  // nothing to read ahead in a problem that cannot be solved
            QMetaObject::invokeMethod(self, [self] { self->updateBusy(); });
            continue;
        }
        if (auto hit = timed ? nullptr : sh->cache.use(frame)) {  // solved since it was asked for
            if (requested) self->deliverHit(*hit, request);
            continue;
        }
        sh->solving = requested;
        sh->inFlight = frame;
        sh->inFlightSince = std::chrono::steady_clock::now();
        sh->stopSolve = false;
        lock.unlock();

        std::shared_ptr<FrameResult> result;
        QString error;
        try {
            result =
                state.solve(*problem, generation, frame, wantShapeError, &sh->stopSolve, timed);
        } catch (const std::exception& e) {
            error = QString::fromStdString(e.what());
            state.fail(generation);
        }

        lock.lock();
        sh->solving = false;
        sh->inFlight.reset();
        if (!result && error.isEmpty()) {  // stopped for a newer request: nothing to keep
            if (timed && generation == sh->generation) sh->toTime.push_front(frame);  // later
            QMetaObject::invokeMethod(self, [self] { self->updateBusy(); });
            continue;
        }
        if (!result) {
            QMetaObject::invokeMethod(
                self, [self, generation, error] { self->deliverFailure(generation, error); });
            continue;
        }
        if (generation == sh->generation && sh->preparedGeneration != generation) {
            sh->preparedGeneration = generation;
            sh->preparationMs = state.preparationMs;
            sh->preparedRest =
                problem->options.calibrate == CalibrateMode::None ? nullptr : state.rest;
        }
        sh->lastSolveMs = result->solveMs;
        sh->lastSuperseded = false;
        result->request = request;
        if (generation == sh->generation) sh->cache.insert(result);
        if (requested)  // read-ahead frames only go to the cache
            QMetaObject::invokeMethod(self, [self, result] { self->deliver(result); });
        if (timed)
            QMetaObject::invokeMethod(self,
                                      [self, frame, ms = result->report.milliseconds, generation] {
                                          emit self->frameTimed(frame, ms, generation);
                                      });
    }
}

FrameSolver::FrameSolver(QObject* parent) : QObject(parent), shared_(std::make_shared<Shared>()) {
    qRegisterMetaType<boneless::ui::FrameResult>();
    shared_->cache.setLimit(defaultCacheLimit());
    shared_->worker = std::thread(&FrameSolver::run, shared_.get(), this);
}

FrameSolver::~FrameSolver() {
    {
        std::lock_guard lock(shared_->mutex);
        shared_->stop = true;
        shared_->stopSolve = true;  // closing need not wait for the frame in flight
    }
    shared_->wake.notify_all();
    shared_->worker.join();
}

std::size_t FrameSolver::defaultCacheLimit() {
    const int mb = QSettings().value("solver/cacheMegabytes", 256).toInt();
    return std::size_t(std::max(1, mb)) << 20;
}

bool FrameSolver::setProblem(const Document& document, QString* why) {
    QString reason;
    std::shared_ptr<Problem> p;
    if (document.canSolve(&reason)) {
        p = std::make_shared<Problem>();
        p->mesh = document.mesh();
        p->take = document.take();
        p->map = document.correspondence();
        p->options = document.solveOptions();
        for (int row = 0; row < document.markerCount(); ++row) {
            p->rowPoint.push_back(document.markerPoint(row));
            int mapping = -1;
            for (int k = 0; k < int(p->map.markers.size()) && document.mappedVertex(row) >= 0; ++k)
                if (p->take.findPoint(p->map.markers[k].label) ==
                    std::size_t(document.markerPoint(row)))
                    mapping = k;
            p->rowMapping.push_back(mapping);
        }
    }
    {
        std::lock_guard lock(shared_->mutex);
        ++shared_->generation;
        shared_->problem = p;
        shared_->pending.reset();
        shared_->toTime.clear();
        shared_->lastRequest.reset();
        shared_->behind = false;
        shared_->stopSolve = true;  // a frame of the old problem is of no use
        shared_->cache.clear();
    }
    updateBusy();
    if (why) *why = reason;
    emit problemChanged(p != nullptr, reason);
    return p != nullptr;
}

void FrameSolver::clearProblem() {
    {
        std::lock_guard lock(shared_->mutex);
        ++shared_->generation;
        shared_->problem.reset();
        shared_->pending.reset();
        shared_->toTime.clear();
        shared_->lastRequest.reset();
        shared_->behind = false;
        shared_->stopSolve = true;
        shared_->cache.clear();
    }
    emit problemChanged(false, {});
}

void FrameSolver::timeFrames(const std::vector<int>& frames) {
    {
        std::lock_guard lock(shared_->mutex);
        shared_->toTime.clear();
        if (!shared_->problem) return;
        for (int frame : frames)
            if (frame >= 0 && frame < int(shared_->problem->take.frameCount()))
                shared_->toTime.push_back(frame);
    }
    shared_->wake.notify_one();
}

double FrameSolver::preparationMs() const {
    std::lock_guard lock(shared_->mutex);
    return shared_->preparedGeneration == shared_->generation ? shared_->preparationMs : 0;
}

namespace {

bool sameTake(const C3dTake& a, const C3dTake& b) {
    const C3dSamples &x = a.samples, &y = b.samples;
    if (a.file != b.file || a.unitToMm != b.unitToMm || a.points.size() != b.points.size() ||
        x.frames() != y.frames() || x.points() != y.points() || a.vertical != b.vertical)
        return false;
    for (std::size_t i = 0; i < a.points.size(); ++i)
        if (a.points[i].label != b.points[i].label) return false;
    // The problem's take is the document's copy, sharing its samples until the document reads
    // another (samePositions compares sample by sample only a take read again).
    return x.samePositions(y);
}

}  // namespace

std::shared_ptr<const Positions> FrameSolver::calibratedRestFor(const Document& document) const {
    std::shared_ptr<const Problem> problem;
    std::shared_ptr<const Positions> rest;
    {
        std::lock_guard lock(shared_->mutex);
        if (shared_->preparedGeneration != shared_->generation) return nullptr;
        problem = shared_->problem;
        rest = shared_->preparedRest;
    }
    // The watched document may have changed since (a refresh is queued a turn later), and an
    // unwatched one may never have been this problem's.
    if (!problem || !rest || !document.hasMesh() || !document.hasTake()) return nullptr;
    const TriMesh& mesh = document.mesh();
    if (toJson(problem->options) != toJson(document.solveOptions()) ||
        problem->map.toJson() != document.correspondence().toJson() ||
        problem->mesh.V.rows() != mesh.V.rows() || problem->mesh.F.rows() != mesh.F.rows() ||
        problem->mesh.V != mesh.V || problem->mesh.F != mesh.F ||
        !sameTake(problem->take, document.take()))
        return nullptr;
    return rest;
}

bool FrameSolver::hasProblem() const {
    std::lock_guard lock(shared_->mutex);
    return shared_->problem != nullptr;
}

quint64 FrameSolver::generation() const {
    std::lock_guard lock(shared_->mutex);
    return shared_->generation;
}

void FrameSolver::watch(const Document* document) {
    if (watched_) disconnect(watched_, nullptr, this, nullptr);
    watched_ = document;
    if (!document) return;
    auto refresh = [this] {
        if (refreshQueued_) return;
        refreshQueued_ = true;
        QTimer::singleShot(0, this, [this] {
            refreshQueued_ = false;
            if (!watched_) return;
            setProblem(*watched_);  // which says so (problemChanged)
        });
    };
    for (auto signal :
         {&Document::meshChanged, &Document::takeChanged, &Document::correspondenceChanged,
          &Document::alignmentChanged, &Document::settingsChanged})
        connect(document, signal, this, refresh);
    connect(document, &QObject::destroyed, this, [this] { watched_ = nullptr; });
    refresh();
}

void FrameSolver::setCacheLimit(std::size_t bytes) {
    std::lock_guard lock(shared_->mutex);
    shared_->cache.setLimit(bytes);
}

std::size_t FrameSolver::cacheLimit() const {
    std::lock_guard lock(shared_->mutex);
    return shared_->cache.limit();
}

std::size_t FrameSolver::cacheBytes() const {
    std::lock_guard lock(shared_->mutex);
    return shared_->cache.bytes();
}

int FrameSolver::cachedFrames() const {
    std::lock_guard lock(shared_->mutex);
    return shared_->cache.size();
}

bool FrameSolver::isCached(int frame) const {
    std::lock_guard lock(shared_->mutex);
    return shared_->cache.contains(frame);
}

void FrameSolver::setShapeErrorEnabled(bool enabled) {
    std::lock_guard lock(shared_->mutex);
    if (shared_->shapeError == enabled) return;
    shared_->shapeError = enabled;
    shared_->cache.clear();
}

void FrameSolver::requestFrame(int frame) {
    {
        std::lock_guard lock(shared_->mutex);
        if (!shared_->problem || frame < 0 || frame >= int(shared_->problem->take.frameCount()))
            return;
        shared_->lastRequest = frame;
        const quint64 request = ++shared_->requests;
        const bool unanswered = shared_->pending.has_value() || shared_->solving;
        // Any older request still waiting is no longer wanted, whether or not this one is
        // cached: solved after it, it would replace this frame on screen.
        shared_->pending.reset();
        shared_->supersede(frame);
        if (auto hit = shared_->cache.use(frame)) {
            shared_->behind = false;
            deliverHit(*hit, request);
        } else {
            shared_->behind = unanswered;
            shared_->pending = frame;
            shared_->pendingRequest = request;
        }
    }
    shared_->wake.notify_one();  // for the request, or for the read-ahead that moved with it
    updateBusy();
}

void FrameSolver::setReadAhead(int frames, bool wrap) {
    {
        std::lock_guard lock(shared_->mutex);
        shared_->readAhead = std::max(0, frames);
        shared_->wrap = wrap;
    }
    shared_->wake.notify_one();
}

void FrameSolver::cancelPending() {
    {
        std::lock_guard lock(shared_->mutex);
        shared_->pending.reset();
    }
    updateBusy();
}

bool FrameSolver::isBusy() const {
    std::lock_guard lock(shared_->mutex);
    return shared_->pending.has_value() || shared_->solving;
}

void FrameSolver::updateBusy() {
    const bool busy = isBusy();
    if (busy == busy_) return;
    busy_ = busy;
    emit busyChanged(busy);
}

void FrameSolver::deliverHit(const FrameResult& hit, quint64 request) {
    auto copy = std::make_shared<FrameResult>(hit);
    copy->fromCache = true;
    copy->solveMs = 0;
    copy->request = request;
    QMetaObject::invokeMethod(
        this, [this, copy] { deliver(copy); }, Qt::QueuedConnection);
}

void FrameSolver::deliver(std::shared_ptr<const FrameResult> result) {
    updateBusy();
    if (result->generation != generation()) return;  // solved for a problem since replaced
    // Answers can arrive out of request order (a cache hit overtakes the solve in flight): an
    // older request's answer after a newer one's would put a frame the user left on screen.
    if (result->request < delivered_) return;
    delivered_ = result->request;
    emit frameReady(*result);
}

void FrameSolver::deliverFailure(quint64 generation, const QString& message) {
    updateBusy();
    if (generation != this->generation()) return;
    emit failed(message);
}

}  // namespace boneless::ui
