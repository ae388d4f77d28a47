#pragma once
// What an edit needs before it can do anything: its button and menu item are enabled while the
// document has it (enableWhile), and edits are not held (an export is running). Suggest and Align
// also need markers mapped (4, 3): clicked before, they say so.
#include <QObject>

#include "boneless/ui/Document.h"

namespace boneless::ui {

inline bool hasMarkersToMap(const Document* d) {
    return d->hasMesh() && d->markerCount() > 0;
}
inline bool hasSelectedMapping(const Document* d) {
    return d->mappedVertex(d->selectedMarker()) >= 0;
}
inline bool hasMappings(const Document* d) {
    return !d->correspondence().markers.empty();
}
inline bool hasTake(const Document* d) {
    return d->hasTake();
}
inline bool hasMeshAndTake(const Document* d) {
    return d->hasMesh() && d->hasTake();
}
// A calibration at a frame aligns the take's mapped markers to their vertices there.
inline bool hasMeshTakeAndMappings(const Document* d) {
    return hasMeshAndTake(d) && hasMappings(d);
}

// Anything can be opened as far as the document goes.
inline bool always(const Document*) {
    return true;
}

// Enables `item` (an edit's action or button) while `ready` holds for the document and its edits
// are not held, checked again at each change of what it holds or selects, and of the hold.
template <class Item>
void enableWhile(Item* item, Document* document, bool (*ready)(const Document*)) {
    const auto update = [item, document, ready] {
        item->setEnabled(!document->editsHeld() && ready(document));
    };
    for (auto changed :
         {&Document::meshChanged, &Document::takeChanged, &Document::correspondenceChanged})
        QObject::connect(document, changed, item, update);
    QObject::connect(document, &Document::selectionChanged, item, update);
    QObject::connect(document, &Document::editsHeldChanged, item, update);
    update();
}

}  // namespace boneless::ui
