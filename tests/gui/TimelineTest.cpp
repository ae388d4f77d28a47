// Timeline logic driven by a fake clock (no waiting on real time), and its widget.
#include <QComboBox>
#include <QSignalSpy>
#include <QSlider>
#include <QSpinBox>
#include <QtTest>

#include "boneless/ui/Timeline.h"
#include "boneless/ui/TimelineWidget.h"

using namespace boneless::ui;

class TimelineTest : public QObject {
    Q_OBJECT
    qint64 now_ = 0;

    // 60 frames at 100 Hz, time advanced by hand, ticks only when the test says.
    void setUp(Timeline& t) {
        now_ = 1000;
        t.setClock([this] { return now_; });
        t.setTickInterval(0);
        t.setFrameCount(60);
        t.setRate(100);
    }

  private slots:
    void realtimeFollowsTheClockAndSkipsFrames() {
        Timeline t;
        setUp(t);
        QSignalSpy frames(&t, &Timeline::frameChanged);
        t.play();
        QVERIFY(t.isPlaying());
        now_ += 105;
        t.tick();
        QCOMPARE(t.frame(), 10);
        // A stall (a slow frame): the playhead jumps to where the clock says, not one frame on.
        now_ += 300;
        t.tick();
        QCOMPARE(t.frame(), 40);
        QCOMPARE(frames.count(), 2);
    }

    void slowerSpeeds() {
        Timeline t;
        setUp(t);
        t.setSpeed(Timeline::Speed::Half);
        t.play();
        now_ += 200;
        t.tick();
        QCOMPARE(t.frame(), 10);
        t.setSpeed(Timeline::Speed::Quarter);  // continues from here at the new speed
        now_ += 400;
        t.tick();
        QCOMPARE(t.frame(), 20);
    }

    void everyFrameWaitsForTheView() {
        Timeline t;
        setUp(t);
        t.setSpeed(Timeline::Speed::EveryFrame);
        t.play();
        now_ += 10000;
        t.tick();
        QCOMPARE(t.frame(), 0);  // frame 0 not shown yet
        t.frameShown(0);
        t.tick();
        QCOMPARE(t.frame(), 1);
        t.tick();
        QCOMPARE(t.frame(), 1);
        t.frameShown(1);
        t.tick();
        QCOMPARE(t.frame(), 2);
    }

    void loopsOrStopsAtTheEnd() {
        Timeline t;
        setUp(t);
        t.setLoop(true);
        t.play();
        now_ += 650;  // frame 65 of 60
        t.tick();
        QCOMPARE(t.frame(), 5);
        QVERIFY(t.isPlaying());

        t.setLoop(false);
        now_ += 1000;
        t.tick();
        QCOMPARE(t.frame(), 59);
        QVERIFY(!t.isPlaying());
        // Play at the last frame starts over.
        t.play();
        QCOMPARE(t.frame(), 0);
    }

    void scrubbingAndSteppingStopPlayback() {
        Timeline t;
        setUp(t);
        QSignalSpy playing(&t, &Timeline::playingChanged);
        t.play();
        t.scrubTo(30);
        QVERIFY(!t.isPlaying());
        QCOMPARE(t.frame(), 30);
        t.play();
        t.stepForward(10);
        QCOMPARE(t.frame(), 40);
        QVERIFY(!t.isPlaying());
        t.stepBackward(100);
        QCOMPARE(t.frame(), 0);
        t.goToLast();
        QCOMPARE(t.frame(), 59);
        t.goToFirst();
        QCOMPARE(t.frame(), 0);
        t.setFrame(500);
        QCOMPARE(t.frame(), 59);
        QCOMPARE(playing.count(), 4);  // two plays, two stops
        t.togglePlay();
        QVERIFY(t.isPlaying());
        t.togglePlay();
        QVERIFY(!t.isPlaying());
    }

    void shorterTakeClampsTheFrame() {
        Timeline t;
        setUp(t);
        t.setFrame(50);
        t.setFrameCount(20);
        QCOMPARE(t.frame(), 19);
        t.setFrameCount(0);
        QCOMPARE(t.frame(), 0);
        t.play();
        QVERIFY(!t.isPlaying());  // nothing to play
    }

    void widgetScrubsAndFollows() {
        Timeline t;
        setUp(t);
        TimelineWidget w(&t);
        QCOMPARE(w.slider()->maximum(), 59);
        t.play();
        now_ += 120;
        t.tick();
        // Following the playhead is not scrubbing: playback goes on.
        QCOMPARE(w.slider()->value(), 12);
        QCOMPARE(w.frameBox()->value(), 12);
        QVERIFY(t.isPlaying());
        w.slider()->setValue(33);  // the user drags
        QCOMPARE(t.frame(), 33);
        QVERIFY(!t.isPlaying());
        w.frameBox()->setValue(7);
        QCOMPARE(t.frame(), 7);
        w.speedBox()->setCurrentIndex(w.speedBox()->findData(int(Timeline::Speed::Quarter)));
        QCOMPARE(t.speed(), Timeline::Speed::Quarter);
        t.setFrameCount(10);
        QCOMPARE(w.slider()->maximum(), 9);
    }
};

QTEST_MAIN(TimelineTest)
#include "TimelineTest.moc"
