// The strip over the timeline: each marker's gaps are the take's missing frames, solved frames
// are marked as they come, and a click there scrubs.
#include <QSignalSpy>
#include <QtTest>
#include <set>

#include "ModelTestFixtures.h"
#include "boneless/ui/FrameSolver.h"
#include "boneless/ui/Timeline.h"
#include "boneless/ui/TimelineStrip.h"

using namespace boneless;
using namespace boneless::ui;

namespace {

std::set<int> marked(const std::vector<bool>& frames) {
    std::set<int> out;
    for (int f = 0; f < int(frames.size()); ++f)
        if (frames[f]) out.insert(f);
    return out;
}

}  // namespace

class TimelineStripTest : public QObject {
    Q_OBJECT
    QString work_;
    Document document_;

  private slots:
    void initTestCase() {
        test::isolate("TimelineStripTest");
        work_ = test::freshFolder("TimelineStripTest");
        QVERIFY(test::loadDemo(document_, work_ + "/demo"));
    }

    void eachMarkersGapsAreTheTakesMissingFrames() {
        FrameSolver solver;
        Timeline timeline;
        TimelineStrip strip(&document_, &solver, &timeline);
        const C3dTake& take = document_.take();
        QCOMPARE(int(strip.gaps().size()), document_.markerCount());
        int gapFrames = 0;
        for (int k = 0; k < document_.markerCount(); ++k) {
            std::set<int> missing, drawn;
            for (int f = 0; f < document_.frameCount(); ++f)
                if (!take.samples.valid(f, document_.markerPoint(k))) missing.insert(f);
            const TimelineStrip::Gaps& gaps = strip.gaps()[k];
            for (size_t i = 0; i < gaps.size(); ++i) {
                QVERIFY(gaps[i].first <= gaps[i].second);
                // Runs are whole: the next one starts after a visible frame.
                if (i > 0) QVERIFY(gaps[i].first > gaps[i - 1].second + 1);
                for (int f = gaps[i].first; f <= gaps[i].second; ++f) drawn.insert(f);
            }
            QCOMPARE(drawn, missing);
            gapFrames += int(missing.size());
        }
        QVERIFY2(gapFrames > 0, "the demo take has occlusion gaps");
    }

    void solvedFramesAreMarkedAsCached() {
        FrameSolver solver;
        Timeline timeline;
        timeline.setFrameCount(document_.frameCount());
        TimelineStrip strip(&document_, &solver, &timeline);
        QVERIFY(solver.setProblem(document_));
        QVERIFY(marked(strip.cachedFrames()).empty());
        QSignalSpy ready(&solver, &FrameSolver::frameReady);
        solver.requestFrame(3);
        QVERIFY(ready.wait(60000));
        solver.requestFrame(41);
        QVERIFY(ready.wait(60000));
        QCOMPARE(marked(strip.cachedFrames()), (std::set<int>{3, 41}));
    }

    void aClickOnTheStripScrubsThere() {
        FrameSolver solver;
        Timeline timeline;
        timeline.setFrameCount(document_.frameCount());
        TimelineStrip strip(&document_, &solver, &timeline);
        strip.resize(600, strip.sizeHint().height());
        strip.show();
        QVERIFY(QTest::qWaitForWindowExposed(&strip));
        for (int frame : {20, 0, document_.frameCount() - 1}) {
            QTest::mouseClick(&strip, Qt::LeftButton, {}, QPoint(strip.xOfFrame(frame), 5));
            QCOMPARE(timeline.frame(), frame);
        }
    }
};

QTEST_MAIN(TimelineStripTest)
#include "TimelineStripTest.moc"
