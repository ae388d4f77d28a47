#include "ShortcutPassThrough.h"

#include <QAbstractSpinBox>
#include <QEvent>
#include <QKeyEvent>
#include <QWidget>

namespace boneless::ui {
namespace {

QKeySequence typedKey(const QKeyEvent* key) {
    return QKeySequence(
        QKeyCombination(key->modifiers() & ~Qt::KeypadModifier, Qt::Key(key->key())));
}

class ShortcutPassThrough : public QObject {
  public:
    ShortcutPassThrough(QWidget* box, const QList<QKeySequence>& keys)
        : QObject(box), keys_(keys) {}

    bool eventFilter(QObject* watched, QEvent* event) override {
        // Before a key press the focus widget is asked whether it takes the key itself
        // (ShortcutOverride); ignored here, the key goes to the window's shortcut.
        if (event->type() != QEvent::ShortcutOverride) return false;
        if (!keys_.contains(typedKey(static_cast<QKeyEvent*>(event)))) return false;
        if (auto* spin = qobject_cast<QAbstractSpinBox*>(watched)) spin->interpretText();
        if (auto* widget = qobject_cast<QWidget*>(watched)) widget->clearFocus();
        event->ignore();
        return true;
    }

  private:
    QList<QKeySequence> keys_;
};

class KeyKeeper : public QObject {
  public:
    KeyKeeper(QWidget* widget, const QList<QKeySequence>& keys) : QObject(widget), keys_(keys) {}

    bool eventFilter(QObject*, QEvent* event) override {
        // Accepted, the override keeps the key from the window's shortcut: it goes to the widget.
        if (event->type() != QEvent::ShortcutOverride) return false;
        if (!keys_.contains(typedKey(static_cast<QKeyEvent*>(event)))) return false;
        event->accept();
        return true;
    }

  private:
    QList<QKeySequence> keys_;
};

}  // namespace

QList<QKeySequence> undoRedoKeys() {
    return {QKeySequence(Qt::CTRL | Qt::Key_Z), QKeySequence(Qt::CTRL | Qt::SHIFT | Qt::Key_Z)};
}

void passShortcuts(QWidget* box, const QList<QKeySequence>& keys) {
    box->installEventFilter(new ShortcutPassThrough(box, keys));
}

void keepKeys(QWidget* widget, const QList<QKeySequence>& keys) {
    widget->installEventFilter(new KeyKeeper(widget, keys));
}

}  // namespace boneless::ui
