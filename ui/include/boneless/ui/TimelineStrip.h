#pragma once

#include <QColor>
#include <QWidget>
#include <utility>
#include <vector>

class QSlider;

namespace boneless::ui {

class Document;
class FrameSolver;
class Timeline;

// A strip over the timeline's slider, frame for frame: the frames already solved (cached, so
// they show at once) as a thin line on top, and below it where markers are missing in the take:
// the selected marker's gaps in full, every marker's faintly (darker where more are missing).
// A tick through both marks the calibration frame of the frames solved (automatic or chosen).
// Hovering names the missing markers; a click scrubs there.
class TimelineStrip : public QWidget {
    Q_OBJECT
  public:
    TimelineStrip(Document* document, FrameSolver* solver, Timeline* timeline,
                  QWidget* parent = nullptr);

    // The slider the strip lines up with (same width and left edge in its layout).
    void setSlider(QSlider* slider);

    using Gaps = std::vector<std::pair<int, int>>;  // [first, last] frames, inclusive
    // Per Document marker, its runs of missing frames in the take.
    const std::vector<Gaps>& gaps() const { return gaps_; }
    // Per frame, whether it is marked as cached.
    const std::vector<bool>& cachedFrames() const { return cached_; }
    // The frame the solved frames were calibrated at; -1 before one is solved.
    int calibrationFrame() const { return calibrationFrame_; }
    static QColor calibrationColour() { return {30, 140, 60}; }

    // The x (widget pixels) of a frame's centre, and the frame under an x.
    int xOfFrame(int frame) const;
    int frameAtX(int x) const;

    QSize sizeHint() const override;
    QSize minimumSizeHint() const override;

  public slots:
    void refreshCache();

  protected:
    void paintEvent(QPaintEvent* event) override;
    void mousePressEvent(QMouseEvent* event) override;
    bool event(QEvent* event) override;  // tooltips

  private:
    void rebuildGaps();
    std::pair<int, int> span() const;  // x of the first and of the last frame

    Document* document_;
    FrameSolver* solver_;
    Timeline* timeline_;
    QSlider* slider_ = nullptr;
    std::vector<Gaps> gaps_;
    std::vector<int> missingCount_;  // per frame, markers missing
    std::vector<bool> cached_;
    int calibrationFrame_ = -1;
    static constexpr quint64 kNoGeneration = ~quint64(0);
    // The solver's generation when the take or map last changed: its cached frames are not this
    // take's (TimelineStrip.cpp, rebuildGaps).
    quint64 staleGeneration_ = kNoGeneration;
};

}  // namespace boneless::ui
