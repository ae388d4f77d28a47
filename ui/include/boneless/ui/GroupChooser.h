#pragma once

#include <QDialog>
#include <QString>
#include <vector>

#include "boneless/MeshReader.h"

class QListWidget;

namespace boneless::ui {

// Asks which OBJ group to animate: each group with its vertex count, largest first and
// preselected (a character file's body, not its eyelashes), then the whole file.
class GroupChooser : public QDialog {
    Q_OBJECT
  public:
    GroupChooser(const QString& fileName, const std::vector<ObjGroup>& groups,
                 QWidget* parent = nullptr);

    QListWidget* list() const { return list_; }
    // The chosen group's name; empty for the whole file.
    QString group() const;

  private:
    QListWidget* list_;
};

}  // namespace boneless::ui
