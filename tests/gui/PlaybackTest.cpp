// Realtime playback of the demo, one pass with loop off from a cold cache: how many frames the
// playhead stood on were shown with their own answer (rendered while the playhead was there), how
// many were skipped, and how long each shown frame took from the playhead reaching it to its
// render. Those figures depend on the machine and are printed only. Asserted is what holds on any
// machine: the pass ends with the last frame on screen. (That an answer drawn after the playhead
// left is marked as a preview is SliderDragTest's.)
#include <QtTest>
#include <algorithm>
#include <map>
#include <numeric>
#include <set>
#include <vector>

#include "ViewTestSupport.h"
#include "boneless/ui/FrameSolver.h"
#include "boneless/ui/MainWindow.h"
#include "boneless/ui/MeshView.h"
#include "boneless/ui/Timeline.h"

using namespace boneless;
using namespace boneless::ui;

namespace {

struct Pass {
    int frames = 0;               // the frames the playhead should reach: 1 .. last
    std::set<int> reached;        // the frames the playhead stood on
    std::set<int> shown;          // ... and whose own answer was rendered meanwhile
    int staleDisplays = 0;        // answers drawn for a frame the playhead had left
    int solvedOnRequest = 0;      // frames the playhead had to wait for (not found cached)
    std::vector<double> latency;  // playhead reached a shown frame -> its answer rendered (ms)
    std::vector<double> gaps;     // between the renders of successive shown frames (ms)
    double wallMs = 0;
    int skipped() const { return frames - int(shown.size()); }
};

double mean(const std::vector<double>& v) {
    return v.empty() ? -1 : std::accumulate(v.begin(), v.end(), 0.0) / double(v.size());
}
double worst(const std::vector<double>& v) {
    return v.empty() ? -1 : *std::max_element(v.begin(), v.end());
}

// The median solve time of a few frames nobody asked for yet, scrubbed to one at a time: how
// fast this machine solves at the moment (a fold repair now and then does not count).
double medianSolveMs(MainWindow& window) {
    std::vector<double> ms;
    QObject context;
    QObject::connect(window.frameSolver(), &FrameSolver::frameReady, &context,
                     [&](const FrameResult& r) {
                         if (!r.fromCache) ms.push_back(r.solveMs);
                     });
    for (int frame : {10, 20, 30, 40, 50}) {
        window.timeline()->scrubTo(frame);
        if (!test::waitForFrame(window)) return -1;
    }
    if (ms.empty()) return -1;
    std::nth_element(ms.begin(), ms.begin() + ms.size() / 2, ms.end());
    return ms[ms.size() / 2];
}

// Plays the take once at Realtime speed from frame 0 with the solver's cache emptied, and
// follows every frame change, answer and render until the playhead stops on the last frame.
Pass playOnce(MainWindow& window) {
    Pass pass;
    Timeline* timeline = window.timeline();
    FrameSolver* solver = window.frameSolver();
    pass.frames = timeline->frameCount() - 1;  // frame 0 is on screen before play starts

    QElapsedTimer clock;
    std::map<int, qint64> reachedAt;  // ns on `clock`
    int awaiting = -1;                // an own answer handed to the view, not yet rendered
    qint64 lastShownNs = -1;
    QObject context;
    QObject::connect(timeline, &Timeline::frameChanged, &context, [&](int frame) {
        if (!timeline->isPlaying()) return;
        pass.reached.insert(frame);
        reachedAt[frame] = clock.nsecsElapsed();
    });
    QObject::connect(solver, &FrameSolver::frameReady, &context, [&](const FrameResult& r) {
        if (timeline->isPlaying() && !r.fromCache) ++pass.solvedOnRequest;
    });
    QObject::connect(&window, &MainWindow::frameDisplayed, &context, [&](int frame) {
        if (!timeline->isPlaying() || frame == 0) return;
        if (frame == timeline->frame())
            awaiting = frame;
        else
            ++pass.staleDisplays;
    });
    // A render shows the last answer handed over, even if the playhead moved on meanwhile.
    QObject::connect(window.meshView(), &MeshView::rendered, &context, [&](double) {
        if (awaiting < 0 || pass.shown.count(awaiting)) return;
        const qint64 now = clock.nsecsElapsed();
        pass.shown.insert(awaiting);
        pass.latency.push_back((now - reachedAt[awaiting]) / 1e6);
        if (lastShownNs >= 0) pass.gaps.push_back((now - lastShownNs) / 1e6);
        lastShownNs = now;
        awaiting = -1;
    });

    timeline->setLoop(false);
    timeline->setSpeed(Timeline::Speed::Realtime);
    timeline->scrubTo(0);
    if (!test::waitForFrame(window)) return pass;
    const std::size_t limit = solver->cacheLimit();
    solver->setCacheLimit(0);  // empties it: a first pass, every frame still to solve
    solver->setCacheLimit(limit);
    clock.start();
    timeline->play();
    if (!QTest::qWaitFor([&] { return !timeline->isPlaying(); }, 60000)) timeline->pause();
    pass.wallMs = clock.nsecsElapsed() / 1e6;
    return pass;
}

void report(const MainWindow& window, const Pass& p, double solveMs) {
    const Timeline* timeline = window.timeline();
    qInfo(
        "demo playback, Realtime %.0f fps, one pass from a cold cache (a solve takes %.1f ms "
        "here, median): %d of %d frames shown with their own answer, %d skipped (%d never "
        "reached by the playhead, %d answers drawn after the playhead left, %d frames solved "
        "while the playhead waited); playhead reached -> answer rendered: mean %.1f ms, worst "
        "%.1f ms; between shown frames: mean %.1f ms, worst %.1f ms (a frame lasts %.1f ms); the "
        "pass took %.0f ms (nominal %.0f ms)",
        timeline->rate(), solveMs, int(p.shown.size()), p.frames, p.skipped(),
        p.frames - int(p.reached.size()), p.staleDisplays, p.solvedOnRequest, mean(p.latency),
        worst(p.latency), mean(p.gaps), worst(p.gaps), 1000 / timeline->rate(), p.wallMs,
        1000 * p.frames / timeline->rate());
}

}  // namespace

class PlaybackTest : public QObject {
    Q_OBJECT
  public:
    static void initMain() { setDefaultSurfaceFormat(); }

  private slots:
    void initTestCase() {
        test::isolate("PlaybackTest");
        folder_ = test::freshFolder("PlaybackTest");
    }

    void realtimePlaybackEndsWithTheLastFrameOnScreen() {
        MainWindow window;
        window.setMessageBoxesEnabled(false);
        QVERIFY(window.openProject(test::writeDemoProject(folder_ + "/demo")));
        QVERIFY(test::showAndWait(window));
        QVERIFY(window.isSolving());
        const double solveMs = medianSolveMs(window);
        QVERIFY(solveMs > 0);
        const Pass pass = playOnce(window);
        report(window, pass, solveMs);
        QVERIFY(!window.timeline()->isPlaying());
        QCOMPARE(window.timeline()->frame(), window.timeline()->frameCount() - 1);
        QVERIFY(test::waitForFrame(window));
        QCOMPARE(window.displayedFrame(), window.timeline()->frame());
    }

  private:
    QString folder_;
};

QTEST_MAIN(PlaybackTest)
#include "PlaybackTest.moc"
