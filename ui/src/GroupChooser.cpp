#include "boneless/ui/GroupChooser.h"

#include <QDialogButtonBox>
#include <QLabel>
#include <QListWidget>
#include <QVBoxLayout>
#include <algorithm>

#include "Counted.h"

namespace boneless::ui {

namespace {
constexpr int kGroupRole = Qt::UserRole + 1;  // the group's name; absent for the whole file
}

GroupChooser::GroupChooser(const QString& fileName, const std::vector<ObjGroup>& groups,
                           QWidget* parent)
    : QDialog(parent), list_(new QListWidget) {
    setObjectName("groupChooser");
    setWindowTitle(tr("Open Mesh"));
    list_->setObjectName("groupList");
    std::vector<ObjGroup> bySize = groups;
    std::stable_sort(bySize.begin(), bySize.end(),
                     [](const ObjGroup& a, const ObjGroup& b) { return a.vertices > b.vertices; });
    for (const ObjGroup& g : bySize) {
        auto* item =
            new QListWidgetItem(counted(g.vertices, tr("%1 — %n vertex"), tr("%1 — %n vertices"))
                                    .arg(QString::fromStdString(g.name)),
                                list_);
        item->setData(kGroupRole, QString::fromStdString(g.name));
    }
    new QListWidgetItem(tr("(whole file)"), list_);
    list_->setCurrentRow(0);

    auto* buttons = new QDialogButtonBox(QDialogButtonBox::Ok | QDialogButtonBox::Cancel);
    connect(buttons, &QDialogButtonBox::accepted, this, &QDialog::accept);
    connect(buttons, &QDialogButtonBox::rejected, this, &QDialog::reject);
    connect(list_, &QListWidget::itemDoubleClicked, this, &QDialog::accept);

    auto* layout = new QVBoxLayout(this);
    layout->addWidget(new QLabel(counted(int(groups.size()), tr("%1 has %n group. Animate:"),
                                         tr("%1 has %n groups. Animate:"))
                                     .arg(fileName)));
    layout->addWidget(list_, 1);
    layout->addWidget(buttons);
    resize(420, 360);
}

QString GroupChooser::group() const {
    const QListWidgetItem* item = list_->currentItem();
    return item ? item->data(kGroupRole).toString() : QString();
}

}  // namespace boneless::ui
