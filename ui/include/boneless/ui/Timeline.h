#pragma once

#include <QObject>
#include <QString>
#include <functional>

class QTimer;

namespace boneless::ui {

// A frame as the app names it to the user, as the status bar names the current one: the 0-based
// frame the CLI and files use, then the capture's own number, "576 (capture frame 577)".
QString frameName(int frame, qint64 firstFrame);

// The playhead: frame, play/pause, step, loop and speed, without any widget. Realtime speeds
// place the playhead by the wall clock (frame = start + elapsed × rate × speed), so playback skips
// frames rather than falling behind when frames take longer to show than they last. EveryFrame
// advances one frame per tick, and only once the current frame was shown (frameShown()).
class Timeline : public QObject {
    Q_OBJECT
  public:
    enum class Speed { Realtime, Half, Quarter, EveryFrame };
    Q_ENUM(Speed)

    explicit Timeline(QObject* parent = nullptr);

    void setFrameCount(int frames);  // keeps the frame in range; 0 = nothing to play
    int frameCount() const { return frameCount_; }
    void setRate(double framesPerSecond);  // the take's rate; <= 0 is treated as 30
    double rate() const { return rate_; }
    // The take's first_frame: the number the capture gives frame 0 (C3dTake::firstFrame, 1 for
    // CMU's takes). The playhead counts from 0, as the CLI and every file do; what the app shows
    // of the current frame gives the capture's number beside it, as Vicon and MotionBuilder show.
    void setFirstFrame(qint64 number);
    qint64 firstFrame() const { return firstFrame_; }
    qint64 captureFrame(int frame) const { return firstFrame_ + frame; }
    QString frameName(int frame) const { return boneless::ui::frameName(frame, firstFrame_); }

    int frame() const { return frame_; }
    bool isPlaying() const { return playing_; }
    bool loops() const { return loop_; }
    Speed speed() const { return speed_; }
    static double speedFactor(Speed speed);  // 1, 0.5, 0.25; 0 for EveryFrame

    // Milliseconds since an arbitrary origin; replaceable so that tests drive time themselves.
    void setClock(std::function<qint64()> clock);
    // The playback timer's period (ms); 0 stops the internal timer, so only tick() advances.
    void setTickInterval(int ms);

  public slots:
    // Moves the playhead (clamped) without touching playback.
    void setFrame(int frame);
    // What the user does: scrubbing, stepping and first/last also stop playback.
    void scrubTo(int frame);
    void play();
    void pause();
    void togglePlay();
    void stepForward(int frames = 1);
    void stepBackward(int frames = 1);
    void goToFirst();
    void goToLast();
    void setLoop(bool loop);
    void setSpeed(boneless::ui::Timeline::Speed speed);
    // The view reports the frame it has displayed; EveryFrame playback waits for it.
    void frameShown(int frame);
    // One playback step (the timer calls it; tests may too).
    void tick();

  signals:
    void frameChanged(int frame);
    void playingChanged(bool playing);
    void loopChanged(bool loop);
    void speedChanged(boneless::ui::Timeline::Speed speed);
    void frameCountChanged(int frames);
    void firstFrameChanged(qint64 number);

  private:
    void restartClock();
    void changeFrame(int frame);
    int lastFrame() const { return frameCount_ > 0 ? frameCount_ - 1 : 0; }

    int frameCount_ = 0;
    double rate_ = 30.0;
    qint64 firstFrame_ = 0;
    int frame_ = 0;
    bool playing_ = false;
    bool loop_ = true;
    Speed speed_ = Speed::Realtime;
    int shownFrame_ = -1;
    std::function<qint64()> clock_;
    qint64 startMs_ = 0;  // clock at startFrame_
    int startFrame_ = 0;
    QTimer* timer_;
};

}  // namespace boneless::ui
