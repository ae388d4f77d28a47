// Keys whichever widget has focus: the frame box applies on Enter and never on the way, Space
// plays after typing a frame, the arrows step once the number is applied; menu shortcuts.
#include <QAbstractItemView>
#include <QComboBox>
#include <QDoubleSpinBox>
#include <QFile>
#include <QFileInfo>
#include <QInputDialog>
#include <QLabel>
#include <QLineEdit>
#include <QMenuBar>
#include <QMessageBox>
#include <QPushButton>
#include <QSlider>
#include <QSpinBox>
#include <QStatusBar>
#include <QTableView>
#include <QToolButton>
#include <QToolTip>
#include <QtTest>
#include <functional>

#include "ViewTestSupport.h"
#include "boneless/ui/Document.h"
#include "boneless/ui/MainWindow.h"
#include "boneless/ui/MarkerListModel.h"
#include "boneless/ui/MeshView.h"
#include "boneless/ui/Timeline.h"
#include "boneless/ui/TimelineStrip.h"
#include "boneless/ui/TimelineWidget.h"

using namespace boneless::ui;

class KeysTest : public QObject {
    Q_OBJECT
  public:
    static void initMain() { setDefaultSurfaceFormat(); }

  private slots:
    void initTestCase() { project_ = test::demoProjectFor("KeysTest"); }

    void init() {
        window_ = test::openShown(project_);
        QVERIFY(window_);
    }
    void cleanup() { window_.reset(); }

    void theFrameBoxGoesToTheNumberOnEnterOnly() {
        Timeline* timeline = window_->timeline();
        QSpinBox* box = window_->timelineWidget()->frameBox();
        QSignalSpy moves(timeline, &Timeline::frameChanged);
        box->setFocus();
        QTRY_VERIFY(box->hasFocus());
        box->selectAll();
        QTest::keyClicks(box, "45");
        QCOMPARE(moves.count(), 0);  // not frame 4 on the way
        QTest::keyClick(box, Qt::Key_Return);
        QCOMPARE(timeline->frame(), 45);
        QCOMPARE(moves.count(), 1);
        // Applied, the box lets go: the arrows step frames again.
        QVERIFY(!box->hasFocus());
        QTest::keyClick(window_.get(), Qt::Key_Right);
        QCOMPARE(timeline->frame(), 46);
        QVERIFY(test::waitForFrame(*window_));
        QCOMPARE(window_->displayedFrame(), 46);
    }

    void spaceAfterTypingAFramePlaysFromIt() {
        Timeline* timeline = window_->timeline();
        timeline->setSpeed(Timeline::Speed::Quarter);
        QSpinBox* box = window_->timelineWidget()->frameBox();
        box->setFocus();
        QTRY_VERIFY(box->hasFocus());
        box->selectAll();
        QTest::keyClicks(box, "12");
        QTest::keyClick(box, Qt::Key_Space);
        QVERIFY(timeline->isPlaying());
        QVERIFY2(timeline->frame() >= 12 && timeline->frame() < 20,
                 qPrintable(QString::number(timeline->frame())));
        QCOMPARE(box->text().trimmed().isEmpty(), false);
        QTest::keyClick(window_.get(), Qt::Key_Space);
        QVERIFY(!timeline->isPlaying());
    }

    // A line edit takes Ctrl+Z for its own undo of the typing: in the offset and filter boxes it
    // undid nothing the user could see.
    void undoAndRedoWorkAfterTypingAnOffsetOrAFilter() {
        Document* document = window_->document();
        document->setSelectedMarker(0);  // mapped in the demo
        auto* offset = window_->findChild<QDoubleSpinBox*>("offsetSpin");
        QVERIFY(offset && offset->isEnabled());
        const double before = document->markerOffsetMm(0);
        offset->setFocus();
        QTRY_VERIFY(offset->hasFocus());
        offset->selectAll();
        QTest::keyClicks(offset, "30");
        QTest::keyClick(offset, Qt::Key_Return);
        QCOMPARE(document->markerOffsetMm(0), 30.0);
        QTest::keyClick(offset, Qt::Key_Z, Qt::ControlModifier);
        QCOMPARE(document->markerOffsetMm(0), before);
        offset->setFocus();
        QTRY_VERIFY(offset->hasFocus());
        QTest::keyClick(offset, Qt::Key_Z, Qt::ControlModifier | Qt::ShiftModifier);
        QCOMPARE(document->markerOffsetMm(0), 30.0);

        QLineEdit* filter = window_->markerFilter();
        filter->setFocus();
        QTRY_VERIFY(filter->hasFocus());
        QTest::keyClicks(filter, "LF");
        QTest::keyClick(filter, Qt::Key_Z, Qt::ControlModifier);
        QCOMPARE(document->markerOffsetMm(0), before);
    }

    // Frames are numbered from 0, as --frame, the export's range and its files number them: a
    // 60-frame take's last frame read "59 / 60", as if one were left. The timeline and the status
    // bar give the last frame's number: "59 / 59".
    void theLastFrameReadsAsTheLastInTheTimelineAndTheStatusBar() {
        const int frames = window_->timeline()->frameCount();
        QCOMPARE(frames, 60);
        QStringList texts;
        for (auto* label : window_->timelineWidget()->findChildren<QLabel*>())
            texts << label->text();
        QVERIFY2(texts.contains("/ 59"), qPrintable(texts.join(" | ")));
        window_->timeline()->goToLast();
        QVERIFY(test::waitForFrame(*window_));
        QCOMPARE(window_->timelineWidget()->findChild<QSpinBox*>("frameBox")->value(), 59);
        QVERIFY2(window_->frameSummary().startsWith("Frame 59 / 59"),
                 qPrintable(window_->frameSummary()));
        window_->timeline()->goToFirst();
        QVERIFY(test::waitForFrame(*window_));
        QVERIFY2(window_->frameSummary().startsWith("Frame 0 / 59"),
                 qPrintable(window_->frameSummary()));
    }

    // A C3D take numbers its frames from its header's first frame (CMU 85_02 from 1): the app
    // numbered them from 0 alone, so an animator comparing frames with Vicon or MotionBuilder was
    // one off without knowing. The app still counts from 0, and gives the capture's number too.
    void theCurrentFrameIsAlsoGivenByTheCapturesNumber() {
        const qint64 first = window_->document()->take().firstFrame;
        QVERIFY2(first != 0, "a take numbered from 0 cannot tell the two numbers apart");
        const QString capture = QString("capture frame %1").arg(first + 20);
        window_->timeline()->scrubTo(20);
        QVERIFY(test::waitForFrame(*window_));
        QVERIFY2(window_->frameSummary().startsWith("Frame 20 / 59 (" + capture + ")"),
                 qPrintable(window_->frameSummary()));
        QSpinBox* box = window_->timelineWidget()->frameBox();
        QCOMPARE(box->value(), 20);
        QVERIFY2(box->toolTip().contains(capture), qPrintable(box->toolTip()));
        const QString last = QString("capture frames %1 to %2").arg(first).arg(first + 59);
        QStringList tips;
        for (auto* label : window_->timelineWidget()->findChildren<QLabel*>())
            tips << label->toolTip();
        QVERIFY2(tips.join(" | ").contains(last), qPrintable(tips.join(" | ")));

        // Hovering the strip over the slider names the frame under the pointer both ways.
        auto* strip = window_->findChild<TimelineStrip*>();
        QVERIFY(strip);
        const QPoint at(strip->xOfFrame(30), strip->height() / 2);
        QHelpEvent hover(QEvent::ToolTip, at, strip->mapToGlobal(at));
        QApplication::sendEvent(strip, &hover);
        const QString tip = QToolTip::text();
        QToolTip::hideText();
        QVERIFY2(tip.startsWith(QString("Frame 30 (capture frame %1)").arg(first + 30)),
                 qPrintable(tip));
    }

    void menusHaveShortcutsAndHelp() {
        auto* mesh = window_->findChild<QAction*>("actionOpenMesh");
        auto* take = window_->findChild<QAction*>("actionOpenTake");
        QVERIFY(mesh && take);
        QCOMPARE(mesh->shortcut(), QKeySequence(Qt::CTRL | Qt::Key_M));
        QCOMPARE(take->shortcut(), QKeySequence(Qt::CTRL | Qt::Key_T));
        QVERIFY(window_->findChild<QAction*>("actionShortcuts"));
        QVERIFY(window_->findChild<QAction*>("actionGettingStarted"));
        window_->findChild<QAction*>("actionShortcuts")->trigger();
        auto* help = window_->findChild<QWidget*>("helpMessage");
        QVERIFY(help && help->isVisible());
        help->close();
    }

    // QKeySequence::SaveAs has no key on X11: Save Project As showed none and Ctrl+Shift+S, which
    // the shortcuts help promises, did nothing.
    void ctrlShiftSSavesAs() {
        QAction* saveAs = nullptr;
        for (QAction* action : window_->findChildren<QAction*>())
            if (action->text() == "Save Project &As…") saveAs = action;
        QVERIFY(saveAs);
        QCOMPARE(saveAs->shortcut(), QKeySequence(Qt::CTRL | Qt::SHIFT | Qt::Key_S));
        bool asked = false;
        QTimer::singleShot(300, [&asked] {
            if (QWidget* dialog = QApplication::activeModalWidget()) {
                asked = dialog->windowTitle() == "Save Project As";
                dialog->close();
            }
        });
        QTest::keyClick(window_.get(), Qt::Key_S, Qt::ControlModifier | Qt::ShiftModifier);
        QTRY_VERIFY(asked);
    }

    // A click maps the selected marker only in Map Markers mode: the help said it always did.
    void theShortcutsHelpSaysWhenAClickMaps() {
        window_->findChild<QAction*>("actionShortcuts")->trigger();
        auto* help = window_->findChild<QMessageBox*>("helpMessage");
        QVERIFY(help);
        QVERIFY2(help->text().contains("in Edit → Map Markers mode"), qPrintable(help->text()));
        help->close();
    }

    // Tab went from the filter boxes into the marker table and then from cell to cell, changing
    // the selected marker, round and round: the buttons and the offset under it could be reached
    // only backwards. The table is one stop (the arrows move within it), and Tab from the view
    // visits every control once, in the order they read, back to the view.
    void tabVisitsEveryControlOnceInReadingOrder() {
        window_->document()->setSelectedMarker(0);  // mapped: Clear and the offset are enabled
        QWidget* panel = window_->markerFilter()->parentWidget();
        QToolButton* map = nullptr;
        for (auto* button : panel->findChildren<QToolButton*>())
            if (button->defaultAction() == window_->findChild<QAction*>("actionMapMarkers"))
                map = button;
        QToolButton* loopButton = nullptr;
        for (auto* button : window_->timelineWidget()->findChildren<QToolButton*>())
            if (button->text() == "Loop") loopButton = button;
        const QList<QWidget*> expected = {window_->meshView(),
                                          window_->findChild<QWidget*>("timelineSlider"),
                                          window_->timelineWidget()->frameBox(),
                                          loopButton,
                                          window_->timelineWidget()->speedBox(),
                                          window_->markerFilter(),
                                          panel->findChild<QComboBox*>(),
                                          window_->markerTable(),
                                          map,
                                          window_->findChild<QWidget*>("clearMarker"),
                                          window_->findChild<QWidget*>("suggestRest"),
                                          window_->findChild<QWidget*>("alignTake"),
                                          window_->findChild<QWidget*>("offsetSpin"),
                                          window_->findChild<QWidget*>("offsetAll")};
        QVERIFY(!expected.contains(nullptr));
        QWidget* view = window_->meshView();
        view->setFocus();
        QTRY_VERIFY(view->hasFocus());
        QList<QWidget*> cycle{view};
        QStringList names;
        for (int i = 0; i < 40; ++i) {
            QTest::keyClick(window_->focusWidget(), Qt::Key_Tab);
            QWidget* now = window_->focusWidget();
            if (now == view) break;
            cycle << now;
            names << (now->objectName().isEmpty() ? now->metaObject()->className()
                                                  : now->objectName());
        }
        QCOMPARE(window_->document()->selectedMarker(), 0);  // Tab selects no other marker
        QVERIFY2(cycle == expected, qPrintable(names.join(" → ")));
        // And back the same way.
        for (qsizetype i = expected.size() - 1; i >= 0; --i) {
            QTest::keyClick(window_->focusWidget(), Qt::Key_Backtab);
            QCOMPARE(window_->focusWidget(), expected[i]);
        }
    }

    // Space, the arrows, Home and End were the window's whatever had the focus: Space on a
    // focused button or combo played the take instead of pressing it. A focused control keeps
    // the keys it uses; from the view the keys move the take.
    void aFocusedControlKeepsTheKeysItUses() {
        Timeline* timeline = window_->timeline();
        Document* document = window_->document();
        document->setSelectedMarker(0);
        timeline->scrubTo(30);
        auto* align = window_->findChild<QPushButton*>("alignTake");
        QSignalSpy aligned(align, &QPushButton::clicked);
        align->setFocus();
        QTRY_VERIFY(align->hasFocus());
        QTest::keyClick(align, Qt::Key_Space);
        QCOMPARE(aligned.count(), 1);
        QVERIFY(!timeline->isPlaying());
        QTest::keyClick(align, Qt::Key_Return);  // Enter presses it too
        QCOMPARE(aligned.count(), 2);

        QComboBox* state = window_->markerFilter()->parentWidget()->findChild<QComboBox*>();
        state->setFocus();
        QTRY_VERIFY(state->hasFocus());
        QTest::keyClick(state, Qt::Key_Space);
        QTRY_VERIFY(state->view()->isVisible());
        state->hidePopup();
        QVERIFY(!timeline->isPlaying());

        QWidget* boxes[] = {window_->findChild<QWidget*>("offsetSpin"), window_->markerFilter()};
        for (QWidget* box : boxes) {
            box->setFocus();
            QTRY_VERIFY(box->hasFocus());
            for (Qt::Key key : {Qt::Key_Home, Qt::Key_End, Qt::Key_Left, Qt::Key_Right})
                QTest::keyClick(box, key);
            QCOMPARE(timeline->frame(), 30);
        }

        QTableView* table = window_->markerTable();
        table->setFocus();
        QTRY_VERIFY(table->hasFocus());
        QTest::keyClick(table, Qt::Key_Right);  // the table's cell cursor, not the next frame
        QCOMPARE(timeline->frame(), 30);
        QCOMPARE(table->currentIndex().column(), 1);
        QTest::keyClick(table, Qt::Key_End, Qt::ControlModifier);  // its last marker
        QCOMPARE(table->currentIndex().row(), table->model()->rowCount() - 1);
        QCOMPARE(timeline->frame(), 30);
        // Home and End move across a row's cells in a table, nothing a row selection shows:
        // they stay the first and last frame.
        QTest::keyClick(table, Qt::Key_End);
        QCOMPARE(timeline->frame(), timeline->frameCount() - 1);
        timeline->scrubTo(30);

        QWidget* view = window_->meshView();
        view->setFocus();
        QTRY_VERIFY(view->hasFocus());
        QTest::keyClick(view, Qt::Key_Right);
        QCOMPARE(timeline->frame(), 31);
        QTest::keyClick(view, Qt::Key_Home);
        QCOMPARE(timeline->frame(), 0);
        QTest::keyClick(view, Qt::Key_Space);
        QVERIFY(timeline->isPlaying());
        QTest::keyClick(view, Qt::Key_Space);
        QVERIFY(!timeline->isPlaying());
    }

    // The slider took no focus, so Tab never reached it and PageUp and PageDown did nothing. It
    // is a Tab stop: PageUp and PageDown move a tenth of the take, its other keys are the
    // window's (the arrows step one frame, not two; Home and End, Space plays).
    void theFocusedSliderPagesATenthOfTheTake() {
        Timeline* timeline = window_->timeline();
        auto* slider = window_->findChild<QSlider*>("timelineSlider");
        QVERIFY(slider);
        timeline->scrubTo(30);
        QWidget* view = window_->meshView();
        view->setFocus();
        QTRY_VERIFY(view->hasFocus());
        QTest::keyClick(view, Qt::Key_Tab);  // as a user reaches it
        QCOMPARE(window_->focusWidget(), static_cast<QWidget*>(slider));
        const int tenth = timeline->frameCount() / 10;
        QVERIFY(tenth > 1);
        QTest::keyClick(slider, Qt::Key_PageUp);
        QCOMPARE(timeline->frame(), 30 + tenth);
        QTest::keyClick(slider, Qt::Key_PageDown);
        QTest::keyClick(slider, Qt::Key_PageDown);
        QCOMPARE(timeline->frame(), 30 - tenth);
        QTest::keyClick(slider, Qt::Key_Right);
        QCOMPARE(timeline->frame(), 31 - tenth);
        QTest::keyClick(slider, Qt::Key_End);
        QCOMPARE(timeline->frame(), timeline->frameCount() - 1);
        QTest::keyClick(slider, Qt::Key_Home);
        QCOMPARE(timeline->frame(), 0);
        QTest::keyClick(slider, Qt::Key_Space);
        QVERIFY(timeline->isPlaying());
        QTest::keyClick(slider, Qt::Key_Space);
        QVERIFY(!timeline->isPlaying());
        QVERIFY(slider->hasFocus());
    }

    // "All mapped" was the one panel button with no menu item: without the pointer or a long
    // walk of Tab it could not be reached.
    void everyPanelButtonHasAMenuItem() {
        QMenu* edit = nullptr;
        for (QAction* action : window_->menuBar()->actions())
            if (action->text() == "&Edit") edit = action->menu();
        QVERIFY(edit);
        QAction* all = window_->findChild<QAction*>("actionOffsetAll");
        QVERIFY(all && edit->actions().contains(all));
        for (const char* name :
             {"actionMapMarkers", "actionClearMapping", "actionSuggestRest", "actionAlign"})
            QVERIFY2(edit->actions().contains(window_->findChild<QAction*>(name)), name);
        Document* document = window_->document();
        document->setSelectedMarker(0);
        auto* offset = window_->findChild<QDoubleSpinBox*>("offsetSpin");
        offset->setValue(12.5);
        QVERIFY(all->isEnabled());
        all->trigger();
        for (int m = 0; m < document->markerCount(); ++m)
            if (document->mappedVertex(m) >= 0) QCOMPARE(document->markerOffsetMm(m), 12.5);
    }

    // Loop and the playback speed could not be reached from the keyboard: not focusable, in no
    // menu. Playback has them, with keys; the timeline's Loop and speed box are Tab stops.
    void loopAndSpeedHaveMenuItemsAndKeys() {
        Timeline* timeline = window_->timeline();
        QAction* loop = window_->findChild<QAction*>("actionLoop");
        QVERIFY(loop);
        QMenu* playback = nullptr;
        for (QAction* action : window_->menuBar()->actions())
            if (action->text() == "&Playback") playback = action->menu();
        QVERIFY(playback && playback->actions().contains(loop));
        const bool looped = timeline->loops();
        QTest::keyClick(window_.get(), Qt::Key_L, Qt::ControlModifier);
        QCOMPARE(timeline->loops(), !looped);
        QCOMPARE(loop->isChecked(), !looped);
        const std::tuple<Qt::Key, Timeline::Speed, const char*> speeds[] = {
            {Qt::Key_2, Timeline::Speed::Half, "speedHalf"},
            {Qt::Key_3, Timeline::Speed::Quarter, "speedQuarter"},
            {Qt::Key_4, Timeline::Speed::EveryFrame, "speedEveryFrame"},
            {Qt::Key_1, Timeline::Speed::Realtime, "speedRealtime"}};
        QComboBox* box = window_->timelineWidget()->speedBox();
        for (const auto& [key, speed, name] : speeds) {
            QTest::keyClick(window_.get(), key, Qt::ControlModifier);
            QCOMPARE(timeline->speed(), speed);
            QCOMPARE(box->currentData().toInt(), int(speed));
            QAction* action = window_->findChild<QAction*>(name);
            QVERIFY2(action && action->isChecked(), name);
        }
        timeline->setSpeed(Timeline::Speed::Quarter);  // the menu follows the box and a project
        QVERIFY(window_->findChild<QAction*>("speedQuarter")->isChecked());
        QVERIFY(box->focusPolicy() & Qt::TabFocus);
        // A focused Loop is pressed by Space, not the take played.
        QToolButton* loopButton = nullptr;
        for (auto* button : window_->timelineWidget()->findChildren<QToolButton*>())
            if (button->text() == "Loop") loopButton = button;
        QVERIFY(loopButton && (loopButton->focusPolicy() & Qt::TabFocus));
        loopButton->setFocus();
        QTRY_VERIFY(loopButton->hasFocus());
        QTest::keyClick(loopButton, Qt::Key_Space);
        QCOMPARE(timeline->loops(), looped);
        QVERIFY(!timeline->isPlaying());
    }

    // The letter after a single '&', lower case; none for "&&" alone.
    static QChar mnemonic(const QString& text) {
        for (qsizetype i = 0; i + 1 < text.size(); ++i) {
            if (text[i] != '&') continue;
            if (text[i + 1] == '&') {
                ++i;
                continue;
            }
            return text[i + 1].toLower();
        }
        return {};
    }

    // Edit had U for Undo, Calibrate Automatically and Mesh Up, A for Align and Clear All
    // Mappings; File had R for Recent Files and Save Correspondence As: Alt and the letter went
    // to the first, or only highlighted, and a keyboard user could not tell which.
    void noTwoItemsOfAMenuShareAMnemonic() {
        QStringList clashes;
        int menus = 0;
        std::function<void(const QString&, const QList<QAction*>&)> walk =
            [&](const QString& where, const QList<QAction*>& actions) {
                ++menus;
                QMap<QChar, QString> taken;
                for (QAction* action : actions) {
                    if (action->isSeparator() || !action->isVisible()) continue;
                    const QChar letter = mnemonic(action->text());
                    if (!letter.isNull()) {
                        if (taken.contains(letter))
                            clashes << QString("%1: %2 and %3")
                                           .arg(where, taken[letter], action->text());
                        else
                            taken[letter] = action->text();
                    }
                    if (QMenu* sub = action->menu()) {
                        emit sub->aboutToShow();  // the recent files are listed then
                        walk(where + " → " + action->text(), sub->actions());
                    }
                }
            };
        walk("menu bar", window_->menuBar()->actions());
        QVERIFY(menus >= 8);  // the bar, File, Recent Files, Edit, Mesh Up, View, Show, Help
        QVERIFY2(clashes.isEmpty(), qPrintable(clashes.join("\n")));
    }

    // A marker could be mapped only by a click on the mesh: the first markers Suggest needs
    // could not be mapped from the keyboard. Edit → Map Selected Marker to Vertex asks for the
    // vertex's number, within the mesh's, and maps as a click does: one undoable edit.
    void theSelectedMarkerIsMappedToAVertexTypedIn() {
        Document* document = window_->document();
        const int marker = 0;  // the demo maps every marker: this one is unmapped first
        document->clearMapping(marker);
        QCOMPARE(document->mappedVertex(marker), -1);
        int vertex = 0;
        while (document->markerForVertex(vertex) >= 0) ++vertex;
        document->setSelectedMarker(marker);
        QAction* action = window_->findChild<QAction*>("actionMapToVertex");
        QVERIFY(action && action->isEnabled());
        int lowest = -1, highest = -1;
        QTimer answer;
        connect(&answer, &QTimer::timeout, [&] {
            auto* dialog = qobject_cast<QInputDialog*>(QApplication::activeModalWidget());
            if (!dialog) return;
            lowest = dialog->intMinimum();
            highest = dialog->intMaximum();
            dialog->setIntValue(vertex);
            dialog->accept();
        });
        answer.start(50);
        QTest::keyClick(window_.get(), Qt::Key_M, Qt::ControlModifier | Qt::ShiftModifier);
        QTRY_COMPARE(document->mappedVertex(marker), vertex);
        QCOMPARE(lowest, 0);
        QCOMPARE(highest, document->mesh().vertexCount() - 1);
        QVERIFY2(window_->statusBar()->currentMessage().contains(
                     QString("mapped to vertex %1").arg(vertex)),
                 qPrintable(window_->statusBar()->currentMessage()));
        window_->findChild<QAction*>("actionUndo")->trigger();
        QCOMPARE(document->mappedVertex(marker), -1);

        // No marker selected: it says what to do, and asks nothing.
        document->setSelectedMarker(-1);
        lowest = -1;
        action->trigger();
        QCOMPARE(lowest, -1);
        QVERIFY2(window_->statusBar()->currentMessage().contains("Select a marker"),
                 qPrintable(window_->statusBar()->currentMessage()));
    }

    // An "&" in an edit's name, or in the mesh's or marker's name in Map to Vertex, underlined
    // the next letter and was gone: "Undo Units RD". What the menu or the label shows is its
    // text with Qt's mnemonic marks taken out, which QAction::iconText() does.
    void anAmpersandInAnEditsOrTheMeshsNameIsShownAsWritten() {
        const auto shown = [](const QString& text) { return QAction(text).iconText(); };
        Document* document = window_->document();
        boneless::TakeSolveOptions settings = document->settings();
        settings.markerWeight *= 2;
        document->setSettings(settings, "Weights for R&D");
        QAction* undo = window_->findChild<QAction*>("actionUndo");
        QAction* redo = window_->findChild<QAction*>("actionRedo");
        QCOMPARE(shown(undo->text()), QString("Undo Weights for R&D"));
        undo->trigger();
        QCOMPARE(shown(redo->text()), QString("Redo Weights for R&D"));
        QCOMPARE(shown(undo->text()), QString("Undo"));

        // The mesh as "R&D walker.obj": the dialog's label is its spin box's buddy.
        const QString folder = QFileInfo(project_).absolutePath();
        const QString mesh = folder + "/R&D walker.obj";
        QFile::remove(mesh);
        QVERIFY(QFile::copy(folder + "/walker.obj", mesh));
        QVERIFY(window_->openFiles({mesh, folder + "/walker.c3d", folder + "/walker.map.json"}));
        window_->document()->setSelectedMarker(0);
        QString label;
        QTimer answer;
        connect(&answer, &QTimer::timeout, [&] {
            auto* dialog = qobject_cast<QInputDialog*>(QApplication::activeModalWidget());
            if (!dialog) return;
            for (auto* l : dialog->findChildren<QLabel*>())
                if (l->buddy()) label = shown(l->text());
            dialog->reject();
        });
        answer.start(50);
        window_->findChild<QAction*>("actionMapToVertex")->trigger();
        QVERIFY2(label.startsWith("The vertex of R&D walker.obj that carries "), qPrintable(label));
    }

    // The slider's PageUp and PageDown (a tenth of the take) were in the help's table and
    // docs/view.md but not in the README's Timeline row, the manual's list of the keys there;
    // the README stays within its 15,000 bytes.
    void theReadmesTimelineRowNamesThePageKeys() {
        QFile readme(QStringLiteral(BONELESS_SOURCE_DIR) + "/README.md");
        QVERIFY(readme.open(QIODevice::ReadOnly));
        const QString text = QString::fromUtf8(readme.readAll());
        QVERIFY2(readme.size() <= 15000, qPrintable(QString::number(readme.size())));
        const qsizetype start = text.indexOf("- **Timeline**");
        QVERIFY(start >= 0);
        const QString row = text.mid(start, text.indexOf("\n- **", start + 1) - start);
        QVERIFY2(row.contains("PageUp/PageDown") && row.contains("a tenth of the take"),
                 qPrintable(row));
    }

  private:
    QString project_;
    std::unique_ptr<MainWindow> window_;
};

QTEST_MAIN(KeysTest)
#include "KeysTest.moc"
