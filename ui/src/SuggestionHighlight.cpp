#include "SuggestionHighlight.h"

#include <QBrush>
#include <QColor>
#include <algorithm>

#include "boneless/ui/Document.h"

namespace boneless::ui {

namespace {
// Markers sit a roughly even distance off the skin; one twice as far as the typical suggestion
// and a centimetre more is on the wrong part of the surface.
constexpr double kTimesTypical = 2.0, kMarginMm = 10.0;
}  // namespace

SuggestionHighlight::SuggestionHighlight(Document* document, QObject* parent)
    : QIdentityProxyModel(parent), document_(document) {
    connect(document_, &Document::correspondenceChanged, this, &SuggestionHighlight::recompute);
    connect(document_, &Document::takeChanged, this, &SuggestionHighlight::recompute);
    recompute();
}

bool SuggestionHighlight::doubtful(int marker) const {
    return marker >= 0 && marker < int(doubtful_.size()) && doubtful_[marker];
}

void SuggestionHighlight::recompute() {
    const int count = document_->markerCount();
    std::vector<double> offsets;
    for (int k = 0; k < count; ++k)
        if (document_->markerSuggested(k)) offsets.push_back(document_->markerOffsetMm(k));
    doubtful_.assign(count, false);
    if (!offsets.empty()) {
        std::nth_element(offsets.begin(), offsets.begin() + offsets.size() / 2, offsets.end());
        limitMm_ = kTimesTypical * offsets[offsets.size() / 2] + kMarginMm;
        for (int k = 0; k < count; ++k)
            doubtful_[k] = document_->markerSuggested(k) && document_->markerOffsetMm(k) > limitMm_;
    }
    if (rowCount() > 0)
        emit dataChanged(index(0, 0), index(rowCount() - 1, columnCount() - 1),
                         {Qt::BackgroundRole, Qt::ToolTipRole});
}

QVariant SuggestionHighlight::data(const QModelIndex& index, int role) const {
    if (index.isValid() && doubtful(index.row())) {
        if (role == Qt::BackgroundRole) return QBrush(QColor(255, 200, 120));
        if (role == Qt::ToolTipRole)
            return tr("Suggested, but %1 mm off the surface (typical: under %2 mm): check it")
                .arg(document_->markerOffsetMm(index.row()), 0, 'f', 0)
                .arg(limitMm_, 0, 'f', 0);
    }
    return QIdentityProxyModel::data(index, role);
}

}  // namespace boneless::ui
