#pragma once

#include <QAbstractTableModel>
#include <QSortFilterProxyModel>
#include <vector>

namespace boneless::ui {

class Document;
struct FrameResult;

// The Document's markers as a table: label, mapped vertex, visible/missing at the current frame,
// residual (mm) in the last solved frame (none while a rest is shown). One row per Document
// marker, same order.
class MarkerListModel : public QAbstractTableModel {
    Q_OBJECT
  public:
    enum Column { LabelColumn, VertexColumn, VisibleColumn, ResidualColumn, ColumnCount };
    enum Role {
        MarkerRole = Qt::UserRole + 1,  // int: the Document's marker index
        MappedRole,                     // bool
        VisibleRole,                    // bool, at the current frame
        ResidualRole,                   // double mm, NaN when unknown
        ToCheckRole,                    // bool: a suggestion marked for the user's review
    };

    explicit MarkerListModel(Document* document, QObject* parent = nullptr);

    int rowCount(const QModelIndex& parent = {}) const override;
    int columnCount(const QModelIndex& parent = {}) const override;
    QVariant data(const QModelIndex& index, int role = Qt::DisplayRole) const override;
    QVariant headerData(int section, Qt::Orientation orientation,
                        int role = Qt::DisplayRole) const override;

    int frame() const { return frame_; }
    // The frame the residual column was solved for (-1: none yet). It can lag frame() while
    // playback outruns the solver; the residual cells' tooltips say which frame they show.
    int residualFrame() const { return residualFrame_; }

  public slots:
    void setFrame(int frame);  // visibility column follows the timeline
    void setFrameResult(const boneless::ui::FrameResult& result);  // residual column
    // A rest on screen has no frame: the residual column is blank until the frame is back, as
    // the status bar drops the frame's residual.
    void setRestShown(bool rest);

  private:
    void rebuild();
    void emitColumnChanged(int column);

    Document* document_;
    int frame_ = 0;
    std::vector<double> residualMm_;
    int residualFrame_ = -1;
    bool restShown_ = false;
};

// Filters the marker list: text in the label (case-insensitive), and a state.
class MarkerFilterProxy : public QSortFilterProxyModel {
    Q_OBJECT
  public:
    enum class State { All, Mapped, Unmapped, Visible, Missing, ToCheck };
    Q_ENUM(State)

    explicit MarkerFilterProxy(QObject* parent = nullptr);

    State state() const { return state_; }
    QString text() const { return text_; }
    // The Document marker of a proxy row, -1 if invalid; and the proxy row of a marker.
    int markerAt(int proxyRow) const;
    int rowOfMarker(int marker) const;

  public slots:
    void setState(boneless::ui::MarkerFilterProxy::State state);
    void setText(const QString& text);

  protected:
    bool filterAcceptsRow(int sourceRow, const QModelIndex& sourceParent) const override;

  private:
    State state_ = State::All;
    QString text_;
};

}  // namespace boneless::ui
