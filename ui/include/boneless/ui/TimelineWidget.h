#pragma once

#include <QWidget>

class QSlider;
class QSpinBox;
class QToolButton;
class QComboBox;
class QLabel;
class QVBoxLayout;

namespace boneless::ui {

class Timeline;

// Slider, frame number, first/previous/play/next/last, loop and speed for a Timeline. Dragging
// the slider or typing a frame and Enter scrubs (and so stops playback). Keyboard shortcuts belong
// to the window, which calls the Timeline's slots.
class TimelineWidget : public QWidget {
    Q_OBJECT
  public:
    explicit TimelineWidget(Timeline* timeline, QWidget* parent = nullptr);

    QSlider* slider() const { return slider_; }
    QSpinBox* frameBox() const { return frameBox_; }
    QToolButton* playButton() const { return play_; }
    QComboBox* speedBox() const { return speed_; }
    // Puts `strip` right over the slider, the same width (TimelineStrip lines up its frames).
    void setOverview(QWidget* strip);

  private:
    void syncFrame(int frame);
    void syncRange(int frames);

    Timeline* timeline_;
    QSlider* slider_;
    QVBoxLayout* sliderColumn_;
    QSpinBox* frameBox_;
    QLabel* countLabel_;
    QToolButton *first_, *previous_, *play_, *next_, *last_, *loop_;
    QComboBox* speed_;
};

}  // namespace boneless::ui
