// Dragging the timeline slider as a user does, fast, over cached and uncached frames: once the
// slider is let go, the view and the status bar show the frame it was let go on, and stay there.
#include <QLabel>
#include <QRandomGenerator>
#include <QSlider>
#include <QtTest>

#include "ViewTestSupport.h"
#include "boneless/ui/Document.h"
#include "boneless/ui/FrameSolver.h"
#include "boneless/ui/MainWindow.h"
#include "boneless/ui/Timeline.h"
#include "boneless/ui/TimelineWidget.h"

using namespace boneless::ui;

class SliderDragTest : public QObject {
    Q_OBJECT
  public:
    static void initMain() { setDefaultSurfaceFormat(); }

  private slots:
    void initTestCase() {
        test::isolate("SliderDragTest");
        project_ = test::writeDemoProject(test::freshFolder("SliderDragTest") + "/demo");
    }

    void theFrameShownIsTheOneTheSliderWasReleasedOn() {
        MainWindow window;
        window.setMessageBoxesEnabled(false);
        QVERIFY(window.openProject(project_));
        QVERIFY(test::showAndWait(window));
        QSlider* slider = window.timelineWidget()->slider();
        auto* frameLabel = window.findChild<QLabel*>("frameLabel");
        const int frames = window.timeline()->frameCount();

        // Some frames cached, the others not, as after a little work.
        for (int frame : {5, 16, 33, 46}) {
            slider->setValue(frame);
            QVERIFY(test::waitForFrame(window));
        }

        QRandomGenerator random(31);
        int at = slider->value();
        QList<int> released{5, 16, 33, 46};
        for (int drag = 0; drag < 16; ++drag) {
            // Every other drag ends on a frame released on before, so cached, with the frames
            // passed on the way still being solved.
            const int target =
                drag % 2 ? released[random.bounded(released.size())] : int(random.bounded(frames));
            released << target;
            slider->setSliderDown(true);
            // One step per event-loop turn, a few milliseconds apart: a quick drag.
            const int step = target >= at ? 1 : -1;
            for (int value = at; value != target + step; value += step) {
                slider->setValue(value);
                QTest::qWait(int(random.bounded(4)));
            }
            slider->setSliderDown(false);
            at = target;
            QCOMPARE(window.timeline()->frame(), target);

            QVERIFY2(test::waitForFrame(window, 30000),
                     qPrintable(QString("drag %1 to %2: showing %3")
                                    .arg(drag)
                                    .arg(target)
                                    .arg(window.displayedFrame())));
            // Whatever was still in flight when the slider stopped must not replace it.
            QVERIFY(QTest::qWaitFor([&] { return !window.frameSolver()->isBusy(); }, 30000));
            QTest::qWait(100);
            QCOMPARE(window.displayedFrame(), target);
            QVERIFY2(frameLabel->text().startsWith(QString("Frame %1 /").arg(target)),
                     qPrintable(frameLabel->text()));
            QVERIFY2(!frameLabel->text().contains("preview"), qPrintable(frameLabel->text()));
        }
    }

    void whilePlayingTheStatusBarNamesTheFrameOnScreen() {
        MainWindow window;
        window.setMessageBoxesEnabled(false);
        QVERIFY(window.openProject(project_));
        QVERIFY(test::showAndWait(window));
        auto* frameLabel = window.findChild<QLabel*>("frameLabel");
        int checks = 0;
        connect(&window, &MainWindow::frameDisplayed, this, [&](int frame) {
            ++checks;
            const QString text = frameLabel->text();
            // The frame on screen is named; when the playhead has moved on, so is the playhead.
            QVERIFY2(text.startsWith(QString("Frame %1 /").arg(frame)), qPrintable(text));
            const int playhead = window.timeline()->frame();
            if (playhead != frame)
                QVERIFY2(text.contains(QString("playhead at %1").arg(playhead)), qPrintable(text));
        });
        window.timeline()->play();
        QVERIFY(QTest::qWaitFor([&] { return checks >= 30; }, 60000));
        window.timeline()->pause();
        QVERIFY(test::waitForFrame(window));
        QCOMPARE(window.displayedFrame(), window.timeline()->frame());
    }

    void afterLoadingAMapTheOldSolveIsNotShownAsCurrent() {
        MainWindow window;
        window.setMessageBoxesEnabled(false);
        QVERIFY(window.openProject(project_));
        QVERIFY(test::showAndWait(window));
        window.timeline()->scrubTo(20);
        QVERIFY(test::waitForFrame(window));
        auto* solveLabel = window.findChild<QLabel*>("solveLabel");
        const QString map = QFileInfo(project_).absolutePath() + "/walker.map.json";
        QVERIFY(window.openFile(map));
        // Until the new map's frame is drawn, the picture is not called this frame's answer.
        QVERIFY(!window.frameUpToDate());
        QVERIFY2(solveLabel->text().contains("solving"), qPrintable(solveLabel->text()));
        QVERIFY(test::waitForFrame(window));
        QVERIFY2(solveLabel->text().contains("solved"), qPrintable(solveLabel->text()));
    }

  private:
    QString project_;
};

QTEST_MAIN(SliderDragTest)
#include "SliderDragTest.moc"
