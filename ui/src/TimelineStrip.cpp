#include "boneless/ui/TimelineStrip.h"

#include <QHelpEvent>
#include <QMouseEvent>
#include <QPainter>
#include <QSlider>
#include <QStyle>
#include <QStyleOptionSlider>
#include <QToolTip>
#include <algorithm>

#include "boneless/ui/Document.h"
#include "boneless/ui/FrameSolver.h"
#include "boneless/ui/Timeline.h"

namespace boneless::ui {

namespace {
constexpr int kCacheRow = 3;  // pixels
constexpr int kGapRow = 8;
// The least share of a pixel's frames a gap among them is drawn as (TimelineStrip::paintEvent).
constexpr double kLeastShare = 0.25;
}  // namespace

TimelineStrip::TimelineStrip(Document* document, FrameSolver* solver, Timeline* timeline,
                             QWidget* parent)
    : QWidget(parent), document_(document), solver_(solver), timeline_(timeline) {
    setObjectName("timelineStrip");
    setMouseTracking(true);
    setSizePolicy(QSizePolicy::Expanding, QSizePolicy::Fixed);
    connect(document_, &Document::takeChanged, this, &TimelineStrip::rebuildGaps);
    connect(document_, &Document::correspondenceChanged, this, &TimelineStrip::rebuildGaps);
    connect(document_, &Document::selectionChanged, this, qOverload<>(&QWidget::update));
    connect(timeline_, &Timeline::frameChanged, this, qOverload<>(&QWidget::update));
    // Read-ahead fills the cache without delivering: the worker going idle says when.
    connect(solver_, &FrameSolver::frameReady, this, [this](const FrameResult& result) {
        if (result.calibration.frame != calibrationFrame_) {
            calibrationFrame_ = result.calibration.frame;
            update();
        }
        refreshCache();
    });
    connect(solver_, &FrameSolver::busyChanged, this, &TimelineStrip::refreshCache);
    connect(solver_, &FrameSolver::problemChanged, this, [this](bool solvable) {
        if (!solvable) calibrationFrame_ = -1;
        refreshCache();
        update();
    });
    rebuildGaps();
    staleGeneration_ = kNoGeneration;  // the solver's frames so far may be this document's
    refreshCache();
}

void TimelineStrip::setSlider(QSlider* slider) {
    slider_ = slider;
    update();
}

QSize TimelineStrip::sizeHint() const {
    return {200, kCacheRow + 1 + kGapRow};
}

QSize TimelineStrip::minimumSizeHint() const {
    return {20, kCacheRow + 1 + kGapRow};
}

void TimelineStrip::rebuildGaps() {
    const int frames = document_->frameCount();
    gaps_.assign(document_->markerCount(), {});
    missingCount_.assign(frames, 0);
    const std::vector<std::vector<C3dGap>> pointGaps = document_->take().samples.gaps();
    const std::vector<C3dGap> throughout{{0, std::size_t(frames)}};
    for (int k = 0; k < document_->markerCount(); ++k) {
        const int point = document_->markerPoint(k);
        // A marker the take does not hold is missing throughout.
        const auto& runs =
            point >= 0 && point < int(pointGaps.size()) ? pointGaps[point] : throughout;
        for (const C3dGap& run : runs) {
            if (run.frames == 0) continue;
            const int first = int(run.first), last = int(run.first + run.frames) - 1;
            gaps_[k].push_back({first, last});
            for (int f = first; f <= last; ++f) ++missingCount_[f];
        }
    }
    cached_.assign(frames, false);
    calibrationFrame_ = -1;  // another take's, until a frame of this one is solved
    // The solver still holds the old take's or map's frames until its problem is rebuilt (on the
    // next turn of the event loop): none of them is this one's.
    staleGeneration_ = solver_->generation();
    update();
}

void TimelineStrip::refreshCache() {
    const int frames = document_->frameCount();
    if (int(cached_.size()) != frames) cached_.assign(frames, false);
    bool changed = false;
    for (int f = 0; f < frames; ++f) {
        const bool cached = solver_->generation() != staleGeneration_ && solver_->hasProblem() &&
                            solver_->isCached(f);
        changed |= cached != cached_[f];
        cached_[f] = cached;
    }
    if (changed) update();
}

std::pair<int, int> TimelineStrip::span() const {
    if (!slider_) return {0, std::max(0, width() - 1)};
    // Where the slider's handle centre sits at its first and last value.
    QStyleOptionSlider option;
    option.initFrom(slider_);
    option.orientation = Qt::Horizontal;
    option.minimum = slider_->minimum();
    option.maximum = slider_->maximum();
    option.sliderPosition = option.sliderValue = slider_->minimum();
    const QStyle* style = slider_->style();
    const QRect groove =
        style->subControlRect(QStyle::CC_Slider, &option, QStyle::SC_SliderGroove, slider_);
    const int handle =
        style->subControlRect(QStyle::CC_Slider, &option, QStyle::SC_SliderHandle, slider_).width();
    const int first = groove.x() + handle / 2;
    return {first, first + std::max(0, groove.width() - handle)};
}

int TimelineStrip::xOfFrame(int frame) const {
    const int last = std::max(1, document_->frameCount() - 1);
    const auto [x0, x1] = span();
    return x0 + int(double(frame) / last * (x1 - x0) + 0.5);
}

int TimelineStrip::frameAtX(int x) const {
    const int last = std::max(0, document_->frameCount() - 1);
    const auto [x0, x1] = span();
    if (x1 <= x0) return 0;
    return std::clamp(int(double(x - x0) / (x1 - x0) * last + 0.5), 0, last);
}

void TimelineStrip::paintEvent(QPaintEvent*) {
    QPainter painter(this);
    const int frames = document_->frameCount();
    if (frames == 0) return;
    const QColor cached = palette().color(QPalette::Highlight);
    const QColor gap(200, 40, 40);
    // Each frame spans half-way to its neighbours, so runs of frames draw as one bar.
    const auto [left, right] = span();
    const double x0 = left;  // a plain variable: clang before C++20 cannot capture a binding
    const double step = frames > 1 ? double(right - left) / (frames - 1) : double(right - left);
    auto frameRect = [&](int first, int last, int top, int height) {
        return QRectF(x0 + (first - 0.5) * step, top, std::max(1.0, (last - first + 1) * step),
                      height);
    };
    for (int f = 0; f < frames; ++f)
        if (cached_[f]) painter.fillRect(frameRect(f, f, 0, kCacheRow), cached);
    const int top = kCacheRow + 1;
    const int markers = std::max(1, document_->markerCount());
    // Other markers' gaps faintly, darker where more are missing.
    auto faintness = [&](int f) { return 0.15 + 0.45 * missingCount_[f] / markers; };
    const int selected = document_->selectedMarker();
    const Gaps* selectedGaps =
        selected >= 0 && selected < int(gaps_.size()) ? &gaps_[selected] : nullptr;
    if (step >= 1.0) {
        for (int f = 0; f < frames; ++f) {
            if (missingCount_[f] == 0) continue;
            QColor faint = gap;
            faint.setAlphaF(faintness(f));
            painter.fillRect(frameRect(f, f, top, kGapRow), faint);
        }
        if (selectedGaps)
            for (const auto& [first, last] : *selectedGaps)
                painter.fillRect(frameRect(first, last, top, kGapRow), gap);
    } else {
        // More frames than pixels (a long take): a pixel painted as a frame's would be red for
        // any one frame of its hundreds missing, and a strip of short gaps solid red. A pixel
        // shows instead the share of its frames with a gap: a long gap solid, a short one faint.
        const int columns = right - left + 1;
        std::vector<int> count(columns, 0), selectedMissing(columns, 0);
        std::vector<double> faintSum(columns, 0.0);
        std::vector<int> withGap(columns, 0);
        auto column = [&](int f) { return std::clamp(int(f * step + 0.5), 0, columns - 1); };
        for (int f = 0; f < frames; ++f) {
            const int c = column(f);
            ++count[c];
            if (missingCount_[f] > 0) ++withGap[c], faintSum[c] += faintness(f);
        }
        if (selectedGaps)
            for (const auto& [first, last] : *selectedGaps)
                for (int f = first; f <= last; ++f) ++selectedMissing[column(f)];
        auto fill = [&](int c, int n, double strength) {
            if (n == 0) return;
            // A gap of one frame in hundreds still shows, faintly.
            const double share = std::max(double(n) / count[c], kLeastShare);
            QColor colour = gap;
            colour.setAlphaF(std::min(1.0, strength * share));
            painter.fillRect(QRect(left + c, top, 1, kGapRow), colour);
        };
        for (int c = 0; c < columns; ++c) {
            if (withGap[c] > 0) fill(c, withGap[c], faintSum[c] / withGap[c]);
            fill(c, selectedMissing[c], 1.0);
        }
    }
    if (calibrationFrame_ >= 0 && calibrationFrame_ < frames)
        painter.fillRect(QRect(xOfFrame(calibrationFrame_) - 1, 0, 3, height()),
                         calibrationColour());
    painter.setPen(palette().color(QPalette::WindowText));
    const int x = xOfFrame(timeline_->frame());
    painter.drawLine(x, 0, x, height());
}

void TimelineStrip::mousePressEvent(QMouseEvent* event) {
    if (event->button() == Qt::LeftButton && document_->frameCount() > 0)
        timeline_->scrubTo(frameAtX(event->position().toPoint().x()));
}

bool TimelineStrip::event(QEvent* event) {
    if (event->type() != QEvent::ToolTip) return QWidget::event(event);
    const auto* help = static_cast<QHelpEvent*>(event);
    if (document_->frameCount() == 0) return true;
    const int frame = frameAtX(help->pos().x());
    QStringList missing;
    for (int k = 0; k < document_->markerCount(); ++k)
        if (!document_->markerVisible(k, frame)) missing << document_->markerLabel(k);
    QString text =
        tr("Frame %1%2%3")
            .arg(timeline_->frameName(frame))
            .arg(frame < int(cached_.size()) && cached_[frame] ? tr(", solved") : QString())
            .arg(frame == calibrationFrame_ ? tr(", the calibration frame") : QString());
    if (!missing.isEmpty())
        text += "\n" + tr("Missing: %1").arg(missing.mid(0, 12).join(", ")) +
                (missing.size() > 12 ? tr(" and %1 more").arg(missing.size() - 12) : QString());
    QToolTip::showText(help->globalPos(), text, this);
    return true;
}

}  // namespace boneless::ui
