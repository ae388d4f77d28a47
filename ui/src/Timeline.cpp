#include "boneless/ui/Timeline.h"

#include <QCoreApplication>
#include <QElapsedTimer>
#include <QTimer>
#include <algorithm>
#include <cmath>

namespace boneless::ui {

QString frameName(int frame, qint64 firstFrame) {
    return QCoreApplication::translate("Timeline", "%1 (capture frame %2)")
        .arg(frame)
        .arg(firstFrame + frame);
}

Timeline::Timeline(QObject* parent) : QObject(parent), timer_(new QTimer(this)) {
    auto monotonic = std::make_shared<QElapsedTimer>();
    monotonic->start();
    clock_ = [monotonic] { return monotonic->elapsed(); };
    // Faster than any take's frame period worth showing; realtime playback reads the clock each
    // tick, so the period only bounds how late a frame change can be.
    timer_->setInterval(10);
    timer_->setTimerType(Qt::PreciseTimer);
    connect(timer_, &QTimer::timeout, this, &Timeline::tick);
}

void Timeline::setFrameCount(int frames) {
    frames = std::max(0, frames);
    if (frames == frameCount_) return;
    frameCount_ = frames;
    emit frameCountChanged(frames);
    if (frames == 0) pause();
    changeFrame(std::clamp(frame_, 0, lastFrame()));
}

void Timeline::setFirstFrame(qint64 number) {
    if (number == firstFrame_) return;
    firstFrame_ = number;
    emit firstFrameChanged(number);
}

void Timeline::setRate(double framesPerSecond) {
    rate_ = framesPerSecond > 0 ? framesPerSecond : 30.0;
    restartClock();
}

double Timeline::speedFactor(Speed speed) {
    switch (speed) {
        case Speed::Realtime:
            return 1.0;
        case Speed::Half:
            return 0.5;
        case Speed::Quarter:
            return 0.25;
        case Speed::EveryFrame:
            return 0.0;
    }
    return 1.0;
}

void Timeline::setClock(std::function<qint64()> clock) {
    clock_ = std::move(clock);
    restartClock();
}

void Timeline::setTickInterval(int ms) {
    if (ms <= 0) {
        timer_->stop();
        timer_->setInterval(0);
        return;
    }
    timer_->setInterval(ms);
    if (playing_) timer_->start();
}

void Timeline::restartClock() {
    startMs_ = clock_();
    startFrame_ = frame_;
}

void Timeline::changeFrame(int frame) {
    if (frame == frame_) return;
    frame_ = frame;
    emit frameChanged(frame);
}

void Timeline::setFrame(int frame) {
    changeFrame(std::clamp(frame, 0, lastFrame()));
    restartClock();
}

void Timeline::scrubTo(int frame) {
    pause();
    setFrame(frame);
}

void Timeline::play() {
    if (playing_ || frameCount_ < 2) return;
    // Play from the last frame would end at once: start over, as players do.
    if (frame_ == lastFrame()) changeFrame(0);
    playing_ = true;
    restartClock();
    if (timer_->interval() > 0) timer_->start();
    emit playingChanged(true);
}

void Timeline::pause() {
    if (!playing_) return;
    playing_ = false;
    timer_->stop();
    emit playingChanged(false);
}

void Timeline::togglePlay() {
    playing_ ? pause() : play();
}

void Timeline::stepForward(int frames) {
    pause();
    setFrame(frame_ + frames);
}

void Timeline::stepBackward(int frames) {
    pause();
    setFrame(frame_ - frames);
}

void Timeline::goToFirst() {
    pause();
    setFrame(0);
}

void Timeline::goToLast() {
    pause();
    setFrame(lastFrame());
}

void Timeline::setLoop(bool loop) {
    if (loop == loop_) return;
    loop_ = loop;
    emit loopChanged(loop);
}

void Timeline::setSpeed(Speed speed) {
    if (speed == speed_) return;
    speed_ = speed;
    restartClock();
    emit speedChanged(speed);
}

void Timeline::frameShown(int frame) {
    shownFrame_ = frame;
}

void Timeline::tick() {
    if (!playing_ || frameCount_ < 2) return;
    int next;
    if (speed_ == Speed::EveryFrame) {
        if (shownFrame_ != frame_) return;  // still waiting for the view
        next = frame_ + 1;
    } else {
        const double elapsedS = double(clock_() - startMs_) / 1000.0;
        next = startFrame_ + int(std::floor(elapsedS * rate_ * speedFactor(speed_)));
    }
    if (next > lastFrame()) {
        if (!loop_) {
            changeFrame(lastFrame());
            pause();
            return;
        }
        // Wrap by the clock too, so that a long stall does not replay the skipped frames.
        next %= frameCount_;
        changeFrame(next);
        restartClock();
        return;
    }
    changeFrame(next);
}

}  // namespace boneless::ui
