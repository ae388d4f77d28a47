#pragma once

#include <QUndoCommand>

#include "boneless/ui/Document.h"

namespace boneless::ui {

// Snapshots rather than deltas: a map is a few hundred entries at most, and a snapshot cannot
// drift from what the user saw.
class EditCommand : public QUndoCommand {
  public:
    EditCommand(Document* document, const QString& text, Document::EditState before,
                Document::EditState after)
        : QUndoCommand(text),
          document_(document),
          before_(std::move(before)),
          after_(std::move(after)) {}
    void redo() override { document_->applyEditState(after_); }
    void undo() override { document_->applyEditState(before_); }

  private:
    Document* document_;
    Document::EditState before_, after_;
};

}  // namespace boneless::ui
