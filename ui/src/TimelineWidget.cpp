#include "boneless/ui/TimelineWidget.h"

#include <QComboBox>
#include <QHBoxLayout>
#include <QLabel>
#include <QSignalBlocker>
#include <QSlider>
#include <QSpinBox>
#include <QStyle>
#include <QToolButton>
#include <QVBoxLayout>

#include "ShortcutPassThrough.h"
#include "boneless/ui/Timeline.h"

namespace boneless::ui {

namespace {

QToolButton* makeButton(QWidget* parent, QStyle::StandardPixmap icon, const QString& tip) {
    auto* button = new QToolButton(parent);
    button->setIcon(parent->style()->standardIcon(icon));
    button->setToolTip(tip);
    button->setAutoRaise(true);
    // The window's shortcuts (Space, arrows) must reach it, not press a focused button.
    button->setFocusPolicy(Qt::NoFocus);
    return button;
}

}  // namespace

TimelineWidget::TimelineWidget(Timeline* timeline, QWidget* parent)
    : QWidget(parent), timeline_(timeline) {
    first_ = makeButton(this, QStyle::SP_MediaSkipBackward, tr("First frame (Home)"));
    previous_ = makeButton(this, QStyle::SP_MediaSeekBackward, tr("Previous frame (←)"));
    play_ = makeButton(this, QStyle::SP_MediaPlay, tr("Play/pause (Space)"));
    next_ = makeButton(this, QStyle::SP_MediaSeekForward, tr("Next frame (→)"));
    last_ = makeButton(this, QStyle::SP_MediaSkipForward, tr("Last frame (End)"));
    loop_ = new QToolButton(this);
    loop_->setText(tr("Loop"));
    loop_->setCheckable(true);
    loop_->setChecked(timeline->loops());

    slider_ = new QSlider(Qt::Horizontal, this);
    slider_->setObjectName("timelineSlider");
    // A Tab stop for PageUp and PageDown (a tenth of the take); its arrows, Home and End stay the
    // window's, which step the playhead from anywhere.
    slider_->setFocusPolicy(Qt::StrongFocus);
    // At the window's narrowest the side panel kept its width and the slider shrank to nothing.
    slider_->setMinimumWidth(160);
    frameBox_ = new QSpinBox(this);
    frameBox_->setObjectName("frameBox");
    // Typing "100" must not visit frames 1 and 10 on the way: the box applies on Enter.
    frameBox_->setKeyboardTracking(false);
    // Space applies the number typed and plays instead of being typed into the box; undo and
    // redo are the window's.
    passShortcuts(frameBox_, QList<QKeySequence>{QKeySequence(Qt::Key_Space)} + undoRedoKeys());
    countLabel_ = new QLabel(this);

    // Loop and the speed box are Tab stops (and in Playback, with keys): they were not.
    speed_ = new QComboBox(this);
    speed_->addItem(tr("Realtime"), int(Timeline::Speed::Realtime));
    speed_->addItem(tr("½ speed"), int(Timeline::Speed::Half));
    speed_->addItem(tr("¼ speed"), int(Timeline::Speed::Quarter));
    speed_->addItem(tr("Every frame"), int(Timeline::Speed::EveryFrame));
    speed_->setCurrentIndex(speed_->findData(int(timeline->speed())));

    // What a screen reader announces: the buttons show only icons, the combo box its value.
    first_->setAccessibleName(tr("First frame"));
    previous_->setAccessibleName(tr("Previous frame"));
    play_->setAccessibleName(tr("Play or pause"));
    next_->setAccessibleName(tr("Next frame"));
    last_->setAccessibleName(tr("Last frame"));
    slider_->setAccessibleName(tr("Frame"));
    frameBox_->setAccessibleName(tr("Frame number"));
    speed_->setAccessibleName(tr("Playback speed"));

    auto* layout = new QHBoxLayout(this);
    layout->setContentsMargins(4, 2, 4, 2);
    for (QWidget* w :
         {static_cast<QWidget*>(first_), static_cast<QWidget*>(previous_),
          static_cast<QWidget*>(play_), static_cast<QWidget*>(next_), static_cast<QWidget*>(last_)})
        layout->addWidget(w);
    sliderColumn_ = new QVBoxLayout;
    sliderColumn_->setContentsMargins(0, 0, 0, 0);
    sliderColumn_->setSpacing(0);
    sliderColumn_->addWidget(slider_);
    layout->addLayout(sliderColumn_, 1);
    layout->addWidget(frameBox_);
    layout->addWidget(countLabel_);
    layout->addWidget(loop_);
    layout->addWidget(speed_);
    // Tab in the order they read (Loop was made first).
    setTabOrder(frameBox_, loop_);
    setTabOrder(loop_, speed_);

    connect(first_, &QToolButton::clicked, timeline, &Timeline::goToFirst);
    connect(previous_, &QToolButton::clicked, timeline, [timeline] { timeline->stepBackward(); });
    connect(play_, &QToolButton::clicked, timeline, &Timeline::togglePlay);
    connect(next_, &QToolButton::clicked, timeline, [timeline] { timeline->stepForward(); });
    connect(last_, &QToolButton::clicked, timeline, &Timeline::goToLast);
    connect(loop_, &QToolButton::toggled, timeline, &Timeline::setLoop);
    // valueChanged also fires for clicks on the groove and keyboard moves: all of them scrub.
    connect(slider_, &QSlider::valueChanged, timeline, &Timeline::scrubTo);
    connect(frameBox_, &QSpinBox::valueChanged, timeline, &Timeline::scrubTo);
    // Once applied, the window's keys (arrows, Home, End) move the playhead again.
    connect(frameBox_, &QSpinBox::editingFinished, frameBox_, [this] {
        if (frameBox_->hasFocus()) frameBox_->clearFocus();
    });
    connect(speed_, &QComboBox::currentIndexChanged, timeline, [this](int index) {
        timeline_->setSpeed(Timeline::Speed(speed_->itemData(index).toInt()));
    });

    connect(timeline, &Timeline::frameChanged, this, &TimelineWidget::syncFrame);
    connect(timeline, &Timeline::frameCountChanged, this, &TimelineWidget::syncRange);
    connect(timeline, &Timeline::firstFrameChanged, this,
            [this] { syncRange(timeline_->frameCount()); });
    connect(timeline, &Timeline::loopChanged, loop_, &QToolButton::setChecked);
    connect(timeline, &Timeline::playingChanged, this, [this](bool playing) {
        play_->setIcon(
            style()->standardIcon(playing ? QStyle::SP_MediaPause : QStyle::SP_MediaPlay));
    });
    connect(timeline, &Timeline::speedChanged, this, [this](Timeline::Speed speed) {
        const QSignalBlocker block(speed_);
        speed_->setCurrentIndex(speed_->findData(int(speed)));
    });
    syncRange(timeline->frameCount());
}

void TimelineWidget::setOverview(QWidget* strip) {
    sliderColumn_->insertWidget(0, strip);
}

void TimelineWidget::syncFrame(int frame) {
    // Blocked, or following the playhead during playback would count as scrubbing and stop it.
    const QSignalBlocker blockSlider(slider_);
    const QSignalBlocker blockBox(frameBox_);
    slider_->setValue(frame);
    frameBox_->setValue(frame);
    frameBox_->setToolTip(tr("Frame %1 (0-based), capture frame %2; Enter goes to the frame typed")
                              .arg(frame)
                              .arg(timeline_->captureFrame(frame)));
}

void TimelineWidget::syncRange(int frames) {
    {
        const QSignalBlocker blockSlider(slider_);
        const QSignalBlocker blockBox(frameBox_);
        slider_->setRange(0, std::max(0, frames - 1));
        frameBox_->setRange(0, std::max(0, frames - 1));
        slider_->setPageStep(std::max(1, frames / 10));
    }
    // The last frame's number, as the status bar gives it: frames are numbered from 0, as
    // --frame, the export's range and its files number them, so a 60-frame take ends at "59 / 59"
    // (the count read "59 / 60" there, as if a frame were left). The tooltips add the capture's
    // numbers, which an animator compares with Vicon's.
    const int last = std::max(0, frames - 1);
    countLabel_->setText(tr("/ %1").arg(last));
    countLabel_->setToolTip(
        frames > 0 ? tr("The last frame: %1 frames, numbered 0 to %2 (capture frames %3 to %4)")
                         .arg(frames)
                         .arg(last)
                         .arg(timeline_->firstFrame())
                         .arg(timeline_->captureFrame(last))
                   : QString());
    setEnabled(frames > 0);
    syncFrame(timeline_->frame());
}

}  // namespace boneless::ui
