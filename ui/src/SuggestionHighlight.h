#pragma once

#include <QIdentityProxyModel>
#include <vector>

namespace boneless::ui {

class Document;

// The marker list with doubtful suggestions highlighted: a suggested mapping whose marker sits
// much further off the surface than the other suggestions' markers (its residual, recorded as
// offset_mm) most likely took the wrong vertex, e.g. one on the far side of a limb.
class SuggestionHighlight : public QIdentityProxyModel {
    Q_OBJECT
  public:
    explicit SuggestionHighlight(Document* document, QObject* parent = nullptr);

    bool doubtful(int marker) const;
    QVariant data(const QModelIndex& index, int role = Qt::DisplayRole) const override;

  private:
    void recompute();

    Document* document_;
    std::vector<bool> doubtful_;
    double limitMm_ = 0;
};

}  // namespace boneless::ui
