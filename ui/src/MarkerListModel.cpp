#include "boneless/ui/MarkerListModel.h"

#include <QBrush>
#include <QPalette>
#include <cmath>
#include <limits>

#include "boneless/ui/Document.h"
#include "boneless/ui/FrameSolver.h"
#include "boneless/ui/Timeline.h"

namespace boneless::ui {

MarkerListModel::MarkerListModel(Document* document, QObject* parent)
    : QAbstractTableModel(parent), document_(document) {
    // Rows come and go with the take (and, without one, with the map).
    connect(document, &Document::takeChanged, this, &MarkerListModel::rebuild);
    connect(document, &Document::meshChanged, this, &MarkerListModel::rebuild);
    connect(document, &Document::correspondenceChanged, this, [this] {
        if (rowCount() != document_->markerCount()) return rebuild();
        // The solved residuals belonged to the old map.
        residualMm_.clear();
        residualFrame_ = -1;
        emitColumnChanged(LabelColumn);
        emitColumnChanged(VertexColumn);
        emitColumnChanged(ResidualColumn);
    });
    rebuild();
}

void MarkerListModel::rebuild() {
    beginResetModel();
    residualMm_.clear();
    residualFrame_ = -1;
    endResetModel();
}

void MarkerListModel::emitColumnChanged(int column) {
    if (rowCount() == 0) return;
    emit dataChanged(index(0, column), index(rowCount() - 1, column));
}

int MarkerListModel::rowCount(const QModelIndex& parent) const {
    return parent.isValid() ? 0 : document_->markerCount();
}

int MarkerListModel::columnCount(const QModelIndex& parent) const {
    return parent.isValid() ? 0 : ColumnCount;
}

void MarkerListModel::setFrame(int frame) {
    if (frame == frame_) return;
    frame_ = frame;
    emitColumnChanged(VisibleColumn);
}

void MarkerListModel::setFrameResult(const FrameResult& result) {
    if (int(result.residualMm.size()) != rowCount()) return;
    residualMm_ = result.residualMm;
    residualFrame_ = result.frame;
    emitColumnChanged(ResidualColumn);
}

void MarkerListModel::setRestShown(bool rest) {
    if (rest == restShown_) return;
    restShown_ = rest;
    emitColumnChanged(ResidualColumn);
}

QVariant MarkerListModel::data(const QModelIndex& index, int role) const {
    if (!index.isValid() || index.row() >= rowCount()) return {};
    const int m = index.row();
    const int vertex = document_->mappedVertex(m);
    const bool visible = document_->markerVisible(m, frame_);
    // The residuals are kept while a rest is shown, for the frame's return.
    const double residual = !restShown_ && m < int(residualMm_.size())
                                ? residualMm_[m]
                                : std::numeric_limits<double>::quiet_NaN();
    switch (role) {
        case MarkerRole:
            return m;
        case MappedRole:
            return vertex >= 0;
        case VisibleRole:
            return visible;
        case ResidualRole:
            return residual;
        case ToCheckRole:
            return !document_->markerReviewReason(m).isEmpty();
        default:
            break;
    }
    if (role == Qt::DisplayRole) {
        switch (index.column()) {
            case LabelColumn:
                return document_->markerLabel(m);
            case VertexColumn:
                if (vertex < 0) return tr("—");
                if (!document_->markerReviewReason(m).isEmpty())
                    return tr("%1 (check) \u26a0").arg(vertex);
                return document_->markerSuggested(m) ? tr("%1 (suggested)").arg(vertex)
                                                     : QString::number(vertex);
            case VisibleColumn:
                return document_->hasTake() ? (visible ? tr("visible") : tr("missing")) : QString();
            case ResidualColumn:
                return std::isfinite(residual) ? QString::number(residual, 'f', 2) : QString();
        }
    }
    if (role == Qt::ToolTipRole && index.column() == LabelColumn) {
        const QString shared = document_->sharedLabelText(m);
        if (!shared.isEmpty())
            return tr("In the take, %1: no map label can say which, so it cannot be mapped")
                .arg(shared);
    }
    if (role == Qt::ToolTipRole && index.column() == VertexColumn && vertex >= 0) {
        QString offset =
            tr("Offset off the skin: %1 mm").arg(document_->markerOffsetMm(m), 0, 'f', 1);
        // The column names the vertex; a clicked marker sits on a point of one of its faces.
        if (const int face = document_->mappedPoint(m).face; face >= 0)
            offset = tr("On a point of face %1, by this vertex.\n%2").arg(face).arg(offset);
        const QString review = document_->markerReviewReason(m);
        return review.isEmpty() ? offset : tr("Suggested, check it: %1.\n%2").arg(review, offset);
    }
    if (role == Qt::ToolTipRole && index.column() == ResidualColumn && std::isfinite(residual))
        return tr("Marker to the posed mesh at frame %1")
            .arg(frameName(residualFrame_, document_->take().firstFrame));
    if (role == Qt::ToolTipRole && index.column() == ResidualColumn && restShown_)
        return tr("A rest is shown: residuals are a frame's (View → Show → Frame)");
    if (role == Qt::ForegroundRole && document_->hasTake() && !visible)
        return QBrush(QPalette().color(QPalette::Disabled, QPalette::Text));
    if (role == Qt::TextAlignmentRole && index.column() != LabelColumn)
        return int(Qt::AlignRight | Qt::AlignVCenter);
    return {};
}

QVariant MarkerListModel::headerData(int section, Qt::Orientation orientation, int role) const {
    if (orientation != Qt::Horizontal || role != Qt::DisplayRole) return {};
    switch (section) {
        case LabelColumn:
            return tr("Marker");
        case VertexColumn:
            return tr("Vertex");
        case VisibleColumn:
            return tr("State");
        case ResidualColumn:
            return tr("Residual (mm)");
    }
    return {};
}

MarkerFilterProxy::MarkerFilterProxy(QObject* parent) : QSortFilterProxyModel(parent) {
    // The visible/missing state changes with the frame; re-filter when the source says so.
    setDynamicSortFilter(true);
    setFilterKeyColumn(-1);  // any column's change re-filters, the state column's included
}

void MarkerFilterProxy::setState(State state) {
    if (state == state_) return;
    state_ = state;
    invalidateFilter();
}

void MarkerFilterProxy::setText(const QString& text) {
    if (text == text_) return;
    text_ = text;
    invalidateFilter();
}

int MarkerFilterProxy::markerAt(int proxyRow) const {
    const QModelIndex i = index(proxyRow, 0);
    return i.isValid() ? i.data(MarkerListModel::MarkerRole).toInt() : -1;
}

int MarkerFilterProxy::rowOfMarker(int marker) const {
    if (!sourceModel() || marker < 0 || marker >= sourceModel()->rowCount()) return -1;
    return mapFromSource(sourceModel()->index(marker, 0)).row();
}

bool MarkerFilterProxy::filterAcceptsRow(int sourceRow, const QModelIndex& sourceParent) const {
    const QModelIndex i = sourceModel()->index(sourceRow, 0, sourceParent);
    if (!text_.isEmpty() &&
        !i.data(Qt::DisplayRole).toString().contains(text_, Qt::CaseInsensitive))
        return false;
    switch (state_) {
        case State::All:
            return true;
        case State::Mapped:
            return i.data(MarkerListModel::MappedRole).toBool();
        case State::Unmapped:
            return !i.data(MarkerListModel::MappedRole).toBool();
        case State::Visible:
            return i.data(MarkerListModel::VisibleRole).toBool();
        case State::Missing:
            return !i.data(MarkerListModel::VisibleRole).toBool();
        case State::ToCheck:
            return i.data(MarkerListModel::ToCheckRole).toBool();
    }
    return true;
}

}  // namespace boneless::ui
