#include "SuggestionHighlight.h"

#include <QBrush>
#include <QColor>

#include "boneless/ui/Document.h"

namespace boneless::ui {

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
    doubtful_.assign(document_->markerCount(), false);
    for (int k = 0; k < int(doubtful_.size()); ++k)
        doubtful_[k] = !document_->markerReviewReason(k).isEmpty();
    if (rowCount() > 0)
        emit dataChanged(index(0, 0), index(rowCount() - 1, columnCount() - 1),
                         {Qt::BackgroundRole});
}

QVariant SuggestionHighlight::data(const QModelIndex& index, int role) const {
    if (role == Qt::BackgroundRole && index.isValid() && doubtful(index.row()))
        return QBrush(QColor(255, 200, 120));
    return QIdentityProxyModel::data(index, role);
}

}  // namespace boneless::ui
