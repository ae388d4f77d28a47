#pragma once

#include <QUndoCommand>

#include "boneless/ui/Document.h"

namespace boneless::ui {

// Snapshots rather than deltas: a map is a few hundred entries at most, and a snapshot cannot
// drift from what the user saw.
class MapEditCommand : public QUndoCommand {
  public:
    MapEditCommand(Document* document, const QString& text, Document::MapState before,
                   Document::MapState after)
        : QUndoCommand(text),
          document_(document),
          before_(std::move(before)),
          after_(std::move(after)) {}
    void redo() override { document_->applyMapState(after_); }
    void undo() override { document_->applyMapState(before_); }

  private:
    Document* document_;
    Document::MapState before_, after_;
};

}  // namespace boneless::ui
