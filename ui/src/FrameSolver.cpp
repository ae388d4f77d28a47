#include "boneless/ui/FrameSolver.h"

#include <QMetaObject>
#include <QSettings>
#include <QTimer>
#include <chrono>
#include <cmath>
#include <condition_variable>
#include <limits>
#include <list>
#include <mutex>
#include <optional>
#include <thread>
#include <unordered_map>

#include "boneless/MeshTopology.h"
#include "boneless/ShapeEncoding.h"
#include "boneless/ui/Document.h"

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
    bool solving = false;  // or settling (see FrameSolver::settleMs)
    bool shapeError = false;
    bool previewWanted = false;
    bool previewSolving = false;
    int previewMinVertices = 0;
    std::optional<int> previewPending;
    std::condition_variable previewWake;

    // Least recently used at the back.
    std::list<int> order;
    std::unordered_map<int, std::pair<std::shared_ptr<const FrameResult>, std::list<int>::iterator>>
        cache;
    std::size_t bytes = 0, limit = 0;

    std::thread worker, previewWorker;

    // A request taken from a queue slot, with the problem it was made for.
    struct Request {
        int frame;
        quint64 generation;
        std::shared_ptr<const Problem> problem;
        bool shapeError;
    };
    // Waits on `wakeUp` for a request in `slot`; empty when stopping.
    std::optional<Request> take(std::unique_lock<std::mutex>& lock, std::condition_variable& wakeUp,
                                std::optional<int>& slot) {
        wakeUp.wait(lock, [&] { return stop || (slot && problem); });
        if (stop) return std::nullopt;
        Request r{*slot, generation, problem, shapeError};
        slot.reset();
        return r;
    }

    // Previews wanted, and worth it for the problem's mesh.
    bool previewOn() const {
        return previewWanted && problem && problem->mesh.vertexCount() >= previewMinVertices;
    }
    void clearCache() {
        order.clear();
        cache.clear();
        bytes = 0;
    }
    void insert(std::shared_ptr<const FrameResult> r) {
        if (auto it = cache.find(r->frame); it != cache.end()) {
            bytes -= it->second.first->bytes();
            order.erase(it->second.second);
            cache.erase(it);
        }
        const int frame = r->frame;
        order.push_front(frame);
        bytes += r->bytes();
        cache[frame] = {std::move(r), order.begin()};
        // Always keep the newest frame, even when it alone is over the cap.
        while (bytes > limit && order.size() > 1) {
            auto victim = cache.find(order.back());
            bytes -= victim->second.first->bytes();
            cache.erase(victim);
            order.pop_back();
        }
    }
    std::shared_ptr<const FrameResult> lookup(int frame) {
        auto it = cache.find(frame);
        if (it == cache.end()) return nullptr;
        order.splice(order.begin(), order, it->second.second);
        return it->second.first;
    }
};

namespace {

std::shared_ptr<FrameResult> solveOne(TakeSolver& solver, const Problem& p, int frame,
                                      const ShapeEncoding* encoding) {
    auto r = std::make_shared<FrameResult>();
    r->frame = frame;
    const auto t0 = std::chrono::steady_clock::now();
    r->V = solver.solve(frame, r->report);
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

// What the preview solves: the same take, map and alignment, by the multiresolution solver's
// coarsest level alone (prolonged, no step on the mesh), with at most 6 Gauss–Newton steps there.
// On the demo at twice its resolution (5,700 vertices, markers 10 mm off the skin), frames 1–29:
//   6 steps:   median 175 ms, marker residual ≤ 3.8 mm, edge distortion ≤ 0.118, ≤ 30 folds;
//   10 steps:  median 312 ms, ≤ 4.0 mm, ≤ 0.111, ≤ 21 folds;
//   4 steps left a frame after a jump at 0.35 distortion;
//   the answer (direct, orientation guard): median 1.9 s, ≤ 0.40 mm, ≤ 0.080, ≤ 2 folds.
// Without the orientation guard: with it the coarsest level takes direct steps, which on the
// koala cost 160 ms a preview against 25–35 ms, all 6 of them, and land no nearer the markers.
// (On the demo above, in one run: 167 against 119 ms, for ≤ 10 faces folded against ≤ 35.)
TakeSolveOptions previewOptions(TakeSolveOptions o) {
    o.solver.method = SolverOptions::Method::Multiresolution;
    o.solver.coarsestIterations = 6;
    o.solver.fineIterations = 0;
    o.solver.correctionSteps = 0;
    o.solver.orientationWeight = 0;
    return o;
}

// The solver and shape encoding a worker keeps for one generation.
struct WorkerState {
    std::unique_ptr<TakeSolver> solver;
    std::unique_ptr<MeshTopology> topology;
    std::unique_ptr<ShapeEncoding> encoding;
    quint64 generation = 0, failedGeneration = 0;

    std::shared_ptr<FrameResult> solve(const Problem& p, const TakeSolveOptions& options,
                                       quint64 gen, int frame, bool wantShapeError) {
        if (generation != gen) {
            solver.reset();
            encoding.reset();
            topology.reset();
            solver = std::make_unique<TakeSolver>(p.mesh, p.take, p.map, options);
            generation = gen;
        }
        if (wantShapeError && !encoding) {
            topology = std::make_unique<MeshTopology>(p.mesh);
            encoding = std::make_unique<ShapeEncoding>(p.mesh, *topology);
        }
        auto result = solveOne(*solver, p, frame, wantShapeError ? encoding.get() : nullptr);
        result->generation = gen;
        return result;
    }
    void fail(quint64 gen) {
        solver.reset();
        generation = 0;
        failedGeneration = gen;
    }
};

}  // namespace

// The preview worker: the newest preview request, unless its frame is cached by now. A failure
// is left to the solve's worker to report (it fails on the same problem).
void FrameSolver::runPreviews(Shared* sh, FrameSolver* self) {
    WorkerState state;
    for (;;) {
        std::unique_lock lock(sh->mutex);
        const auto request = sh->take(lock, sh->previewWake, sh->previewPending);
        if (!request) return;
        const int frame = request->frame;
        const quint64 generation = request->generation;
        const auto& problem = request->problem;
        const bool wantShapeError = request->shapeError;
        if (generation == state.failedGeneration || sh->cache.count(frame)) {
            sh->wake.notify_all();  // an answer may be waiting for this preview
            continue;
        }
        sh->previewSolving = true;
        lock.unlock();
        std::shared_ptr<FrameResult> result;
        try {
            result = state.solve(*problem, previewOptions(problem->options), generation, frame,
                                 wantShapeError);
            result->preview = true;
        } catch (const std::exception&) {
            state.fail(generation);
        }
        lock.lock();
        sh->previewSolving = false;
        sh->wake.notify_all();
        // Posted before the answer can start, so it arrives first.
        if (result)
            QMetaObject::invokeMethod(self, [self, result] { self->deliver(result); });
        else
            QMetaObject::invokeMethod(self, [self] { self->updateBusy(); });
    }
}

FrameSolver::FrameSolver(QObject* parent) : QObject(parent), shared_(std::make_shared<Shared>()) {
    qRegisterMetaType<boneless::ui::FrameResult>();
    shared_->limit = defaultCacheLimit();
    // The worker owns the solver; it only ever touches `shared` and posts results back here.
    shared_->worker = std::thread([sh = shared_.get(), self = this] {
        WorkerState state;
        for (;;) {
            std::unique_lock lock(sh->mutex);
            const auto request = sh->take(lock, sh->wake, sh->pending);
            if (!request) return;
            const int frame = request->frame;
            const quint64 generation = request->generation;
            const auto& problem = request->problem;
            const bool wantShapeError = request->shapeError;
            if (generation == state.failedGeneration) continue;
            if (auto hit = sh->lookup(frame)) {
                auto copy = std::make_shared<FrameResult>(*hit);
                copy->fromCache = true;
                copy->solveMs = 0;
                QMetaObject::invokeMethod(self, [self, copy] { self->deliver(copy); });
                continue;
            }
            sh->solving = true;
            if (sh->previewOn()) {
                // Settle: a newer request within settleMs replaces this one before any work.
                auto superseded = [&] {
                    return sh->stop || sh->pending.has_value() || sh->generation != generation;
                };
                sh->wake.wait_for(lock, std::chrono::milliseconds(settleMs), superseded);
                // Then let the preview finish: with two cores busy, the answer could otherwise
                // overtake it and the preview would never be shown.
                sh->wake.wait(lock, [&] {
                    return superseded() || (!sh->previewSolving && !sh->previewPending);
                });
                if (superseded()) {
                    sh->solving = false;
                    continue;
                }
            }
            lock.unlock();

            std::shared_ptr<FrameResult> result;
            QString error;
            try {
                result = state.solve(*problem, problem->options, generation, frame, wantShapeError);
            } catch (const std::exception& e) {
                error = QString::fromStdString(e.what());
                state.fail(generation);
            }

            lock.lock();
            sh->solving = false;
            if (!result) {
                QMetaObject::invokeMethod(
                    self, [self, generation, error] { self->deliverFailure(generation, error); });
                continue;
            }
            if (generation == sh->generation) sh->insert(result);
            QMetaObject::invokeMethod(self, [self, result] { self->deliver(result); });
        }
    });
    shared_->previewWorker = std::thread(&FrameSolver::runPreviews, shared_.get(), this);
}

FrameSolver::~FrameSolver() {
    {
        std::lock_guard lock(shared_->mutex);
        shared_->stop = true;
    }
    shared_->wake.notify_all();
    shared_->previewWake.notify_all();
    shared_->worker.join();
    shared_->previewWorker.join();
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
        shared_->previewPending.reset();
        shared_->clearCache();
    }
    shared_->wake.notify_all();  // a worker settling on the old problem gives up
    updateBusy();
    if (why) *why = reason;
    return p != nullptr;
}

void FrameSolver::clearProblem() {
    std::lock_guard lock(shared_->mutex);
    ++shared_->generation;
    shared_->problem.reset();
    shared_->pending.reset();
    shared_->previewPending.reset();
    shared_->clearCache();
    shared_->wake.notify_all();
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
            QString why;
            const bool ok = setProblem(*watched_, &why);
            emit problemChanged(ok, why);
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
    shared_->limit = bytes;
    while (shared_->bytes > bytes && !shared_->order.empty()) {
        auto victim = shared_->cache.find(shared_->order.back());
        shared_->bytes -= victim->second.first->bytes();
        shared_->cache.erase(victim);
        shared_->order.pop_back();
    }
}

std::size_t FrameSolver::cacheLimit() const {
    std::lock_guard lock(shared_->mutex);
    return shared_->limit;
}

std::size_t FrameSolver::cacheBytes() const {
    std::lock_guard lock(shared_->mutex);
    return shared_->bytes;
}

int FrameSolver::cachedFrames() const {
    std::lock_guard lock(shared_->mutex);
    return int(shared_->cache.size());
}

bool FrameSolver::isCached(int frame) const {
    std::lock_guard lock(shared_->mutex);
    return shared_->cache.count(frame) > 0;
}

void FrameSolver::setShapeErrorEnabled(bool enabled) {
    std::lock_guard lock(shared_->mutex);
    if (shared_->shapeError == enabled) return;
    shared_->shapeError = enabled;
    shared_->clearCache();
}

void FrameSolver::requestFrame(int frame) {
    {
        std::lock_guard lock(shared_->mutex);
        if (!shared_->problem || frame < 0 || frame >= int(shared_->problem->take.frameCount()))
            return;
        if (auto hit = shared_->lookup(frame)) {
            auto copy = std::make_shared<FrameResult>(*hit);
            copy->fromCache = true;
            copy->solveMs = 0;
            QMetaObject::invokeMethod(
                this, [this, copy] { deliver(copy); }, Qt::QueuedConnection);
            return;
        }
        shared_->pending = frame;  // replaces any older request still waiting
        if (shared_->previewOn()) shared_->previewPending = frame;
    }
    shared_->wake.notify_one();
    shared_->previewWake.notify_one();
    updateBusy();
}

void FrameSolver::setPreviewEnabled(bool enabled, int minVertices) {
    std::lock_guard lock(shared_->mutex);
    shared_->previewWanted = enabled;
    shared_->previewMinVertices = minVertices;
    if (!shared_->previewOn()) shared_->previewPending.reset();
    shared_->wake.notify_all();
}

bool FrameSolver::previewEnabled() const {
    std::lock_guard lock(shared_->mutex);
    return shared_->previewOn();
}

void FrameSolver::cancelPending() {
    {
        std::lock_guard lock(shared_->mutex);
        shared_->pending.reset();
        shared_->previewPending.reset();
    }
    shared_->wake.notify_all();
    updateBusy();
}

bool FrameSolver::isBusy() const {
    std::lock_guard lock(shared_->mutex);
    return shared_->pending.has_value() || shared_->solving ||
           shared_->previewPending.has_value() || shared_->previewSolving;
}

void FrameSolver::updateBusy() {
    const bool busy = isBusy();
    if (busy == busy_) return;
    busy_ = busy;
    emit busyChanged(busy);
}

void FrameSolver::deliver(std::shared_ptr<const FrameResult> result) {
    updateBusy();
    if (result->generation != generation()) return;  // solved for a problem since replaced
    emit frameReady(*result);
}

void FrameSolver::deliverFailure(quint64 generation, const QString& message) {
    updateBusy();
    if (generation != this->generation()) return;
    emit failed(message);
}

}  // namespace boneless::ui
