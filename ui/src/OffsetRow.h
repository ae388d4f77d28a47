#pragma once

class QAction;
class QLayout;

namespace boneless::ui {

class Document;

// The marker panel's "Offset off the skin" row: the selected marker's offset (mm, as the
// correspondence file's offset_mm), editable when it is mapped, and "All mapped" to give every
// mapped marker that value. Markers sit 5–20 mm off the skin; without it every map made in the
// app said 0 and the solve pulled the skin out to the markers. Object names: offsetSpin,
// offsetAll. `allMapped` is the button's menu twin: the row enables it and does what it says.
QLayout* makeOffsetRow(Document* document, QAction* allMapped);

}  // namespace boneless::ui
