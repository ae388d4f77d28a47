#pragma once

#include <QIdentityProxyModel>
#include <vector>

namespace boneless::ui {

class Document;

// The marker list with the suggestions to review painted: `suggest` marks an entry
// "needs_review" when its marker lies far from the fitted mesh, fits another part of the body
// about as well, or lands on the wrong side (the list's tooltip gives the reason).
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
};

}  // namespace boneless::ui
