// The strip over the timeline: each marker's gaps are the take's missing frames, solved frames
// are marked as they come, both are painted at their frames, and a click there scrubs.
#include <QSignalSpy>
#include <QUndoStack>
#include <QtTest>
#include <set>

#include "ModelTestFixtures.h"
#include "boneless/C3dWriter.h"
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

// A strip over its own solver and a timeline as long as the document's take.
struct StripRig {
    FrameSolver solver;
    Timeline timeline;
    TimelineStrip strip;
    explicit StripRig(Document& document) : strip(&document, &solver, &timeline) {
        timeline.setFrameCount(document.frameCount());
    }
};

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
        StripRig rig(document_);
        auto& [solver, timeline, strip] = rig;
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
        StripRig rig(document_);
        auto& [solver, timeline, strip] = rig;
        QVERIFY(solver.setProblem(document_));
        QVERIFY(marked(strip.cachedFrames()).empty());
        QSignalSpy ready(&solver, &FrameSolver::frameReady);
        solver.requestFrame(3);
        QVERIFY(ready.wait(60000));
        solver.requestFrame(41);
        QVERIFY(ready.wait(60000));
        QCOMPARE(marked(strip.cachedFrames()), (std::set<int>{3, 41}));
    }

    // A new problem (another take, a map that does not fit) has solved nothing yet, and no
    // problem has nothing solved: the marks of the old one went on showing as solved.
    void theSolvedMarksGoWhenTheProblemChanges() {
        StripRig rig(document_);
        auto& [solver, timeline, strip] = rig;
        QVERIFY(solver.setProblem(document_));
        QSignalSpy ready(&solver, &FrameSolver::frameReady);
        solver.requestFrame(7);
        QVERIFY(ready.wait(60000));
        QCOMPARE(marked(strip.cachedFrames()), (std::set<int>{7}));
        solver.clearProblem();
        QVERIFY(marked(strip.cachedFrames()).empty());

        QVERIFY(solver.setProblem(document_));
        solver.requestFrame(7);
        QVERIFY(ready.wait(60000));
        QCOMPARE(marked(strip.cachedFrames()), (std::set<int>{7}));
        // The map changed: until the problem is rebuilt, the solver's frames are the old map's.
        QVERIFY(document_.clearMapping(0));
        QVERIFY(marked(strip.cachedFrames()).empty());
        document_.undoStack()->undo();
        QVERIFY(solver.setProblem(document_));
        QVERIFY(marked(strip.cachedFrames()).empty());
    }

    void itPaintsTheSolvedFramesAndTheSelectedMarkersGapsAtTheirFrames() {
        StripRig rig(document_);
        auto& [solver, timeline, strip] = rig;
        // The marker missing the most frames, so both its gaps and its visible frames are drawn.
        int selected = 0;
        for (int k = 0; k < document_.markerCount(); ++k)
            if (strip.gaps()[k].size() > strip.gaps()[selected].size()) selected = k;
        QVERIFY(!strip.gaps()[selected].empty());
        document_.setSelectedMarker(selected);
        QVERIFY(solver.setProblem(document_));
        QSignalSpy ready(&solver, &FrameSolver::frameReady);
        for (int frame : {3, 41}) {
            solver.requestFrame(frame);
            QVERIFY(ready.wait(60000));
        }
        timeline.scrubTo(document_.frameCount() - 1);  // the playhead away from the calibration
        strip.resize(600, strip.sizeHint().height());
        strip.show();
        QVERIFY(QTest::qWaitForWindowExposed(&strip));
        const QImage image = strip.grab().toImage();
        const QRgb background = strip.palette().color(QPalette::Window).rgb();
        const QRgb cached = strip.palette().color(QPalette::Highlight).rgb();
        const QRgb gap = qRgb(200, 40, 40);
        const int cacheY = 1, gapY = strip.height() - 3;
        int faint = 0;
        for (int f = 0; f < document_.frameCount(); ++f) {
            const int x = strip.xOfFrame(f);
            if (std::abs(x - strip.xOfFrame(timeline.frame())) <= 1) continue;  // the playhead
            if (std::abs(x - strip.xOfFrame(strip.calibrationFrame())) <= 2) continue;
            const QString at = QString("frame %1 at x %2: cache row %3, gap row %4")
                                   .arg(f)
                                   .arg(x)
                                   .arg(image.pixel(x, cacheY), 0, 16)
                                   .arg(image.pixel(x, gapY), 0, 16);
            QVERIFY2(image.pixel(x, cacheY) == (f == 3 || f == 41 ? cached : background),
                     qPrintable(at));
            bool anyMissing = false;
            for (int k = 0; k < document_.markerCount(); ++k)
                anyMissing |= !document_.markerVisible(k, f);
            const QRgb g = image.pixel(x, gapY);
            if (!document_.markerVisible(selected, f)) {
                QVERIFY2(g == gap, qPrintable(at));
            } else if (anyMissing) {
                // Another marker's gap, faintly: reddish, not the selected marker's red.
                QVERIFY2(g != gap && qGreen(g) < qGreen(background) - 10, qPrintable(at));
                ++faint;
            } else {
                QVERIFY2(g == background, qPrintable(at));
            }
        }
        QVERIFY2(faint > 0, "no frame where only other markers are missing");
        // The calibration frame the solved frames were fitted at, ticked through both rows.
        const int calibration = ready.last().at(0).value<FrameResult>().calibration.frame;
        QVERIFY(calibration >= 0);
        QCOMPARE(strip.calibrationFrame(), calibration);
        const int x = strip.xOfFrame(calibration);
        QVERIFY(std::abs(x - strip.xOfFrame(timeline.frame())) > 1);
        for (int y : {cacheY, gapY})
            QCOMPARE(QColor(image.pixel(x, y)), TimelineStrip::calibrationColour());
        document_.setSelectedMarker(-1);
    }

    // A 25-minute take puts 300 frames in a pixel: any gap among them painted the pixel as
    // though all were missing, and the strip was solid red. A pixel now shows how many of its
    // frames have the gap: a long gap solid, a short one faint.
    void onALongTakeAShortGapIsFaintAndALongOneSolid() {
        C3dTake take;
        take.rate = 120;
        for (const char* label : {"A", "B", "C"}) {
            C3dPoint p;
            p.label = p.name = label;
            take.points.push_back(p);
        }
        const int frames = 18000;  // 30 frames a pixel over 600 pixels
        take.samples = C3dSamples(frames, 3);
        for (int f = 0; f < frames; ++f)
            for (int k = 0; k < 3; ++k) take.samples.set(f, k, 100.0 * k, f * 0.1, 1000.0);
        const int shortGap = 4000, longGap = 9000, longEnd = 12000;  // A: 2 frames, 3,000 frames
        for (int f : {shortGap, shortGap + 1}) take.samples.setMissing(f, 0);
        for (int f = longGap; f < longEnd; ++f) take.samples.setMissing(f, 0);
        const QString path = work_ + "/gaps.c3d";
        writeC3d(take, path.toStdString());
        Document document;
        QVERIFY(document.loadTake(path));
        StripRig rig(document);
        auto& [solver, timeline, strip] = rig;
        strip.resize(600, strip.sizeHint().height());
        strip.show();
        QVERIFY(QTest::qWaitForWindowExposed(&strip));
        const QRgb background = strip.palette().color(QPalette::Window).rgb();
        const QRgb gap = qRgb(200, 40, 40);
        const int gapY = strip.height() - 3;
        const int atShort = strip.xOfFrame(shortGap),
                  atLong = strip.xOfFrame((longGap + longEnd) / 2);
        const int clear = strip.xOfFrame(15000);
        for (int selected : {0, -1}) {
            document.setSelectedMarker(selected);
            const QImage image = strip.grab().toImage();
            const QRgb shortPixel = image.pixel(atShort, gapY),
                       longPixel = image.pixel(atLong, gapY);
            const QString at = QString("selected %1: short gap %2, long gap %3, no gap %4")
                                   .arg(selected)
                                   .arg(shortPixel, 0, 16)
                                   .arg(longPixel, 0, 16)
                                   .arg(image.pixel(clear, gapY), 0, 16);
            QVERIFY2(image.pixel(clear, gapY) == background, qPrintable(at));
            if (selected == 0) QVERIFY2(longPixel == gap, qPrintable(at));
            // Both show, the short one much fainter: nearer the background than the gap colour.
            QVERIFY2(qGreen(longPixel) < qGreen(background) - 10, qPrintable(at));
            QVERIFY2(qGreen(shortPixel) < qGreen(background) - 2, qPrintable(at));
            QVERIFY2(qGreen(shortPixel) - qGreen(longPixel) >
                         (qGreen(background) - qGreen(longPixel)) / 2,
                     qPrintable(at));
        }
    }

    void aClickOnTheStripScrubsThere() {
        StripRig rig(document_);
        auto& [solver, timeline, strip] = rig;
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
