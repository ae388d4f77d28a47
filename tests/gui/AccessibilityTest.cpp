// What a screen reader announces: every control of the main window and the Export dialog has a
// name, its own or its label's (a buddy), not only a value or nothing at all.
#include <QAbstractButton>
#include <QAbstractItemView>
#include <QAbstractScrollArea>
#include <QAbstractSlider>
#include <QAbstractSpinBox>
#include <QAccessible>
#include <QComboBox>
#include <QLineEdit>
#include <QMenu>
#include <QMenuBar>
#include <QProgressBar>
#include <QtTest>

#include "ViewTestSupport.h"
#include "boneless/ui/ExportDialog.h"
#include "boneless/ui/MainWindow.h"

using namespace boneless;
using namespace boneless::ui;

namespace {

// A control: takes the keyboard focus, or is one of the kinds a screen reader reads as one.
bool isControl(const QWidget* w) {
    return w->focusPolicy() != Qt::NoFocus || qobject_cast<const QAbstractButton*>(w) ||
           qobject_cast<const QAbstractSpinBox*>(w) || qobject_cast<const QLineEdit*>(w) ||
           qobject_cast<const QAbstractSlider*>(w) || qobject_cast<const QComboBox*>(w) ||
           qobject_cast<const QProgressBar*>(w) || qobject_cast<const QAbstractItemView*>(w);
}

// Qt's own parts of a control (a spin box's line edit, a filter's clear button, a table's headers
// and scroll bars) are
// announced through the control; the menus are named by their items.
bool isPartOfAnother(const QWidget* w, const QWidget* top) {
    for (const QWidget* p = w->parentWidget(); p && p != top; p = p->parentWidget())
        if (qobject_cast<const QAbstractSpinBox*>(p) || qobject_cast<const QComboBox*>(p) ||
            qobject_cast<const QLineEdit*>(p) || qobject_cast<const QAbstractScrollArea*>(p) ||
            qobject_cast<const QMenuBar*>(p) || qobject_cast<const QMenu*>(p))
            return true;
    return qobject_cast<const QMenuBar*>(w) || qobject_cast<const QMenu*>(w) ||
           w->objectName().startsWith("qt_");
}

QString describe(const QWidget* w) {
    return QString("%1 \"%2\"").arg(w->metaObject()->className(), w->objectName());
}

// The controls under `top` that a screen reader would announce without a name.
QStringList unnamedControls(QWidget* top) {
    QStringList unnamed;
    for (QWidget* w : top->findChildren<QWidget*>()) {
        if (!isControl(w) || isPartOfAnother(w, top) || w->isWindow()) continue;
        QAccessibleInterface* a = QAccessible::queryAccessibleInterface(w);
        const QString name = a ? a->text(QAccessible::Name).trimmed() : QString();
        // A combo box read by its value alone ("Realtime", "All") says nothing of what it sets.
        // On Linux Qt gives its value as its name whatever is set: it is named by its own
        // accessible name (other platforms), or by a label (AT-SPI's labelled-by relation).
        const auto* combo = qobject_cast<const QComboBox*>(w);
        const bool comboNamed =
            combo && a &&
            (!w->accessibleName().isEmpty() || !a->relations(QAccessible::Label).isEmpty());
        if (name.isEmpty() || (combo && !comboNamed))
            unnamed << describe(w) + (name.isEmpty() ? "" : " named only \"" + name + "\"");
    }
    return unnamed;
}

}  // namespace

class AccessibilityTest : public QObject {
    Q_OBJECT
  public:
    static void initMain() { setDefaultSurfaceFormat(); }

  private slots:
    void initTestCase() { project_ = test::demoProjectFor("AccessibilityTest"); }

    // Over AT-SPI the timeline's buttons, slider and frame box, the marker panel's filter,
    // table and offset, the 3D view and the Export dialog's folder, range and progress bar had
    // no name; the combo boxes were read by their value.
    void everyControlOfTheWindowAndTheExportDialogHasAName() {
        std::unique_ptr<MainWindow> window = test::openShown(project_);
        QVERIFY(window);
        const QStringList inWindow = unnamedControls(window.get());
        QVERIFY2(inWindow.isEmpty(), qPrintable(inWindow.join(", ")));
        window->showExportDialog();
        QVERIFY(window->exportDialog());
        const QStringList inExport = unnamedControls(window->exportDialog());
        QVERIFY2(inExport.isEmpty(), qPrintable(inExport.join(", ")));
    }

  private:
    QString project_;
};

QTEST_MAIN(AccessibilityTest)
#include "AccessibilityTest.moc"
