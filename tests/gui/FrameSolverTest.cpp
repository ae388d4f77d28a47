// FrameSolver: frames solved off the caller's thread, stale requests dropped, LRU cache,
// following the document's edits, and a frame's answer independent of the frames before it.
#include <QSignalSpy>
#include <QtTest>
#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <vector>

#include "ModelTestFixtures.h"
#include "boneless/Metrics.h"
#include "boneless/ui/FrameSolver.h"

using namespace boneless;
using namespace boneless::ui;

namespace {

FrameResult resultOf(const QSignalSpy& spy, int i) {
    return spy.at(i).at(0).value<FrameResult>();
}

}  // namespace

class FrameSolverTest : public QObject {
    Q_OBJECT
    QString demo_;

  private slots:
    void initTestCase() {
        test::isolate("FrameSolverTest");
        demo_ = test::freshFolder("FrameSolverTest/demo");
        test::writeDemoProject(demo_);
    }

    void solvesAFrameThenServesItFromTheCache() {
        Document d;
        QVERIFY(test::loadDemo(d, demo_));
        FrameSolver solver;
        QString why;
        QVERIFY2(solver.setProblem(d, &why), qPrintable(why));
        QSignalSpy ready(&solver, &FrameSolver::frameReady);
        solver.requestFrame(5);
        QVERIFY(solver.isBusy());
        QCOMPARE(ready.count(), 0);  // never solved inside the call
        QVERIFY(ready.wait(30000));
        const FrameResult r = resultOf(ready, 0);
        QCOMPARE(r.frame, 5);
        QVERIFY(!r.fromCache);
        QVERIFY(r.solveMs > 0);
        QCOMPARE(r.V.rows(), Eigen::Index(d.mesh().vertexCount()));
        QVERIFY(r.V.allFinite());
        QCOMPARE(r.markers.rows(), Eigen::Index(d.markerCount()));
        QCOMPARE(int(r.residualMm.size()), d.markerCount());
        int measured = 0;
        for (int m = 0; m < d.markerCount(); ++m) {
            // A residual exactly where the marker is mapped and seen.
            QCOMPARE(std::isfinite(r.residualMm[m]), d.markerVisible(m, 5));
            measured += std::isfinite(r.residualMm[m]);
        }
        QVERIFY(measured >= 20);
        QVERIFY(r.report.residualRmsMm < 20.0);
        QVERIFY(!solver.isBusy());

        solver.requestFrame(5);
        QCOMPARE(ready.count(), 1);  // a hit is delivered asynchronously too
        QVERIFY(ready.wait(5000));
        const FrameResult hit = resultOf(ready, 1);
        QVERIFY(hit.fromCache);
        QCOMPARE(hit.solveMs, 0.0);
        QVERIFY(hit.V == r.V);
        QCOMPARE(solver.cachedFrames(), 1);
    }

    void aNewerRequestDropsTheQueuedOnes() {
        Document d;
        QVERIFY(test::loadDemo(d, demo_));
        FrameSolver solver;
        QVERIFY(solver.setProblem(d));
        QSignalSpy ready(&solver, &FrameSolver::frameReady);
        for (int f = 0; f < 40; ++f) solver.requestFrame(f);
        while (ready.isEmpty() || resultOf(ready, ready.count() - 1).frame != 39)
            QVERIFY(ready.wait(30000));
        QTest::qWait(200);  // nothing else is still coming
        // The worker took at most the first request or two before the last one arrived.
        QVERIFY2(ready.count() <= 3, qPrintable(QString::number(ready.count())));
        QCOMPARE(resultOf(ready, ready.count() - 1).frame, 39);
        QVERIFY(!solver.isCached(20));
    }

    // Playback on a machine slower than the take: a request comes before each solve is half
    // done. The solver still finishes frames while the requests keep coming (it used to stop
    // every one, and the view stayed on one frame for as long as the requests came).
    void requestsFasterThanASolveStillGetFramesSolved() {
        Document d;
        QVERIFY(test::loadDemo(d, demo_));
        FrameSolver solver;
        QVERIFY(solver.setProblem(d));
        QSignalSpy ready(&solver, &FrameSolver::frameReady);
        solver.requestFrame(0);
        QVERIFY(ready.wait(30000));  // the solver now knows how long a frame takes
        const int frames = d.frameCount();
        QElapsedTimer clock;
        clock.start();
        for (int f = 1; solver.cachedFrames() < 4 && clock.elapsed() < 20000;
             f = f % (frames - 1) + 1) {
            solver.requestFrame(f);
            QTest::qWait(1);
        }
        QVERIFY2(solver.cachedFrames() >= 4,
                 qPrintable(QString("%1 frames solved in %2 ms of requests")
                                .arg(solver.cachedFrames())
                                .arg(clock.elapsed())));
    }

    void theCacheKeepsTheMostRecentlyUsedWithinItsCap() {
        Document d;
        QVERIFY(test::loadDemo(d, demo_));
        FrameSolver solver;
        QVERIFY(solver.setProblem(d));
        QSignalSpy ready(&solver, &FrameSolver::frameReady);
        solver.requestFrame(0);
        QVERIFY(ready.wait(30000));
        const std::size_t perFrame = resultOf(ready, 0).bytes();
        solver.setCacheLimit(3 * perFrame + perFrame / 2);
        for (int f : {1, 2, 0, 3}) {  // 0 is used again, so 1 is the least recently used
            solver.requestFrame(f);
            QVERIFY(ready.wait(30000));
        }
        QCOMPARE(solver.cachedFrames(), 3);
        QVERIFY(!solver.isCached(1));
        QVERIFY(solver.isCached(0));
        QVERIFY(solver.isCached(2));
        QVERIFY(solver.isCached(3));
        QVERIFY(solver.cacheBytes() <= solver.cacheLimit());
        solver.setCacheLimit(perFrame);
        QCOMPARE(solver.cachedFrames(), 1);
    }

    void shapeErrorOnDemand() {
        Document d;
        QVERIFY(test::loadDemo(d, demo_));
        FrameSolver solver;
        solver.setShapeErrorEnabled(true);
        QVERIFY(solver.setProblem(d));
        QSignalSpy ready(&solver, &FrameSolver::frameReady);
        solver.requestFrame(30);
        QVERIFY(ready.wait(30000));
        const FrameResult r = resultOf(ready, 0);
        QCOMPARE(int(r.shapeError.size()), d.mesh().vertexCount());
        double largest = 0;
        for (double e : r.shapeError) {
            QVERIFY(std::isfinite(e) && e >= 0);
            largest = std::max(largest, e);
        }
        QVERIFY(largest > 0);  // a deformed frame strains somewhere
        QVERIFY(largest < boundingBoxDiagonal(d.mesh().V));
    }

    void followsTheDocument() {
        Document d;
        QVERIFY(test::loadDemo(d, demo_));
        FrameSolver solver;
        QSignalSpy problem(&solver, &FrameSolver::problemChanged);
        QSignalSpy ready(&solver, &FrameSolver::frameReady);
        solver.watch(&d);
        QVERIFY(problem.wait(5000));
        QVERIFY(problem.last().at(0).toBool());
        solver.requestFrame(2);
        QVERIFY(ready.wait(30000));
        QVERIFY(solver.isCached(2));
        const quint64 generation = solver.generation();

        // Several edits in one turn of the event loop: one new problem.
        QVERIFY(d.clearMapping(0));
        QVERIFY(d.clearMapping(1));
        QVERIFY(problem.wait(5000));
        QCOMPARE(problem.count(), 2);
        QCOMPARE(solver.generation(), generation + 1);
        QVERIFY(!solver.isCached(2));  // solved with the old map

        QVERIFY(d.clearAllMappings());
        QVERIFY(problem.wait(5000));
        QVERIFY(!problem.last().at(0).toBool());
        QVERIFY(!problem.last().at(1).toString().isEmpty());
        solver.requestFrame(3);  // nothing to solve: ignored, no crash
        QVERIFY(!solver.isBusy());
    }

    // Users rely on a frame looking the same however they got to it: scrubbed to from either
    // side, solved first, or exported. Each frame is solved from its own markers alone.
    void aFramesAnswerDoesNotDependOnTheFramesVisitedBeforeIt() {
        Document d;
        QVERIFY(test::loadDemo(d, demo_));
        const int frame = 30;
        auto solveInOrder = [&](const std::vector<int>& frames) -> std::optional<FrameResult> {
            FrameSolver solver;
            if (!solver.setProblem(d)) return std::nullopt;
            QSignalSpy ready(&solver, &FrameSolver::frameReady);
            for (int f : frames) {
                // One at a time, so that every frame in the order is really solved.
                ready.clear();
                solver.requestFrame(f);
                if (!ready.wait(30000)) return std::nullopt;
                const FrameResult r = resultOf(ready, 0);
                if (r.frame != f || r.fromCache) return std::nullopt;
                if (f == frame) return r;
            }
            return std::nullopt;
        };
        const auto first = solveInOrder({frame});
        const auto afterOthers = solveInOrder({55, 2, 41, 17, 31, 29, frame});
        const auto afterOthersReversed = solveInOrder({29, 31, 17, 41, 2, 55, frame});
        QVERIFY(first && afterOthers && afterOthersReversed);

        // And what the core solver gives for that frame on its own, as export and the CLI do.
        TakeSolver direct(d.mesh(), d.take(), d.correspondence(), d.solveOptions());
        FrameReport report;
        const Positions expected = direct.solve(frame, report);

        const double tolerance = 1e-12 * boundingBoxDiagonal(d.mesh().V);
        auto largestGap = [](const Positions& a, const Positions& b) {
            return a.rows() == b.rows() ? (a - b).cwiseAbs().maxCoeff()
                                        : std::numeric_limits<double>::infinity();
        };
        for (const FrameResult* r : {&*first, &*afterOthers, &*afterOthersReversed}) {
            const double gap = largestGap(r->V, expected);
            QVERIFY2(gap <= tolerance, qPrintable(QString("%1 apart").arg(gap)));
            QCOMPARE(r->report.residualRmsMm, report.residualRmsMm);
        }
        qInfo(
            "frame %d: bit for bit the same in every order and directly: %s", frame,
            first->V == expected && afterOthers->V == expected && afterOthersReversed->V == expected
                ? "yes"
                : "no (within 1e-12 of the diagonal)");
    }

    // While playing, frames after the last request are solved into the cache, never delivered,
    // and move on with the requests.
    void readAheadFillsTheCacheWithoutDelivering() {
        Document d;
        QVERIFY(test::loadDemo(d, demo_));
        FrameSolver solver;
        QVERIFY(solver.setProblem(d));
        QSignalSpy ready(&solver, &FrameSolver::frameReady);
        solver.requestFrame(10);
        QVERIFY(ready.wait(30000));
        QTest::qWait(100);
        QCOMPARE(solver.cachedFrames(), 1);  // off by default

        solver.setReadAhead(4);
        QVERIFY(QTest::qWaitFor([&] { return solver.cachedFrames() == 5; }, 30000));
        for (int f = 11; f <= 14; ++f) QVERIFY(solver.isCached(f));
        QTest::qWait(100);
        QCOMPARE(solver.cachedFrames(), 5);
        QCOMPARE(ready.count(), 1);  // read-ahead frames are not delivered

        // A request for a read-ahead frame is a cache hit, with the answer a request gives.
        solver.requestFrame(12);
        QVERIFY(ready.wait(5000));
        const FrameResult ahead = resultOf(ready, 1);
        QCOMPARE(ahead.frame, 12);
        QVERIFY(ahead.fromCache);
        FrameSolver other;
        QVERIFY(other.setProblem(d));
        QSignalSpy otherReady(&other, &FrameSolver::frameReady);
        other.requestFrame(12);
        QVERIFY(otherReady.wait(30000));
        QVERIFY(resultOf(otherReady, 0).V == ahead.V);

        // It moves with the requests: 15 and 16 now; a request elsewhere comes first.
        QVERIFY(QTest::qWaitFor([&] { return solver.isCached(16); }, 30000));
        solver.requestFrame(40);
        QVERIFY(ready.wait(30000));
        QCOMPARE(resultOf(ready, 2).frame, 40);
        QVERIFY(QTest::qWaitFor([&] { return solver.isCached(44); }, 30000));
        QVERIFY(!solver.isCached(45));

        // Off: nothing more after the next request.
        solver.setReadAhead(0);
        solver.requestFrame(50);
        QVERIFY(ready.wait(30000));
        QTest::qWait(100);
        QVERIFY(!solver.isCached(51));
        QCOMPARE(ready.count(), 4);
    }

    void readAheadWrapsOnlyWhenAsked() {
        Document d;
        QVERIFY(test::loadDemo(d, demo_));
        const int last = d.frameCount() - 1;
        FrameSolver solver;
        QVERIFY(solver.setProblem(d));
        QSignalSpy ready(&solver, &FrameSolver::frameReady);
        solver.setReadAhead(3);
        solver.requestFrame(last - 1);
        QVERIFY(QTest::qWaitFor([&] { return solver.isCached(last); }, 30000));
        QTest::qWait(100);
        QCOMPARE(solver.cachedFrames(), 2);
        solver.setReadAhead(3, true);  // looping: on past the last frame to the first
        QVERIFY(QTest::qWaitFor([&] { return solver.isCached(0) && solver.isCached(1); }, 30000));
        QVERIFY(!solver.isCached(2));
        QCOMPARE(ready.count(), 1);
    }

    // Read-ahead counts against the cache cap and never evicts its own frames (which would
    // solve them over and over), nor outlives the problem it was solving for.
    void readAheadKeepsWithinTheCacheAndTheProblem() {
        Document d;
        QVERIFY(test::loadDemo(d, demo_));
        FrameSolver solver;
        QVERIFY(solver.setProblem(d));
        QSignalSpy ready(&solver, &FrameSolver::frameReady);
        solver.requestFrame(0);
        QVERIFY(ready.wait(30000));
        const std::size_t perFrame = resultOf(ready, 0).bytes();
        solver.setCacheLimit(3 * perFrame + perFrame / 2);  // three frames
        solver.setReadAhead(8);
        solver.requestFrame(20);
        QVERIFY(ready.wait(30000));
        QVERIFY(QTest::qWaitFor([&] { return solver.isCached(22); }, 30000));
        QTest::qWait(200);
        QCOMPARE(solver.cachedFrames(), 3);  // 20 and the two after it that fit
        QVERIFY(solver.isCached(20) && solver.isCached(21) && solver.isCached(22));
        QVERIFY(solver.cacheBytes() <= solver.cacheLimit());

        solver.setCacheLimit(256 << 20);
        solver.requestFrame(30);
        QVERIFY(ready.wait(30000));
        QVERIFY(solver.setProblem(d));  // a new generation: its cache starts empty...
        QTest::qWait(300);
        QCOMPARE(solver.cachedFrames(), 0);  // ...and nothing is read ahead until asked
        QCOMPARE(ready.count(), 3);
    }

    // Playing a 100K-face koala at 120 Hz showed frames 125 to 262 behind the playhead: when a
    // request was answered and the next had not come yet, the worker read ahead from the frame
    // answered, frames the playhead had long passed, and the next request waited for them. When
    // requests come faster than the solver answers them, it reads nothing ahead: free, it takes
    // the newest request.
    void whenRequestsOutrunTheSolverItSolvesNoFrameThePlayheadHasPassed() {
        Document d;
        QVERIFY(test::loadDemo(d, demo_));
        FrameSolver solver;
        QVERIFY(solver.setProblem(d));
        QSignalSpy ready(&solver, &FrameSolver::frameReady);
        solver.requestFrame(0);
        QVERIFY(ready.wait(30000));
        solver.setReadAhead(8);
        QVERIFY(QTest::qWaitFor([&] { return solver.isCached(8); }, 30000));
        // The playhead moves on before frame 20 is answered: the solver is behind.
        solver.requestFrame(20);
        solver.requestFrame(30);
        QVERIFY(QTest::qWaitFor(
            [&] { return !ready.isEmpty() && resultOf(ready, ready.count() - 1).frame == 30; },
            30000));
        QTest::qWait(300);
        for (int f = 31; f <= 38; ++f)
            QVERIFY2(!solver.isCached(f), qPrintable(QString::number(f)));
        // A request it answers before the next one comes: it keeps up, and reads ahead again.
        solver.requestFrame(40);
        QVERIFY(QTest::qWaitFor([&] { return solver.isCached(44); }, 30000));
    }

    void aMapTheTakeCannotResolveIsRefused() {
        Document d;
        QVERIFY(test::loadDemo(d, demo_));
        Correspondence map = d.correspondence();
        map.markers[0].label = "NOT_IN_TAKE";
        const QString path = test::freshFolder("FrameSolverTest/bad") + "/bad.map.json";
        map.write(path.toStdString());
        QVERIFY(d.loadCorrespondence(path));
        FrameSolver solver;
        QString why;
        QVERIFY(!solver.setProblem(d, &why));
        QVERIFY2(why.contains("NOT_IN_TAKE"), qPrintable(why));
        QVERIFY(!solver.hasProblem());
    }
};

QTEST_MAIN(FrameSolverTest)
#include "FrameSolverTest.moc"
