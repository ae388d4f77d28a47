#pragma once

#include <QKeySequence>
#include <QList>

class QWidget;

namespace boneless::ui {

// The window's undo and redo keys (Edit → Undo, Redo), which a text box passes on.
QList<QKeySequence> undoRedoKeys();

// `keys` typed in the text box `box` go to the window's shortcuts instead of the box's own editing
// (a line edit takes Ctrl+Z for its own undo of what was typed, a spin box Space as a character):
// a spin box first applies the number typed, and the box lets go of the focus, so that the arrows
// step frames again.
void passShortcuts(QWidget* box, const QList<QKeySequence>& keys);

// The opposite: `keys` go to `widget` while it has the focus, not to the window's shortcuts (a
// focused button is pressed by Space, a combo opens its list, the marker table goes to its last
// row on End). From anywhere else they stay the window's.
void keepKeys(QWidget* widget, const QList<QKeySequence>& keys);

}  // namespace boneless::ui
