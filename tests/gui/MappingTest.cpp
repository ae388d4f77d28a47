// Mapping as a user does it: a click beside the mesh says so, opening a correspondence file over
// mappings already made asks first (replace, merge or cancel), the picture holds still while
// mapping (each mapping re-solves the frame, which would move the surface under the cursor) and
// leaving shows the playhead's frame, and suggestions to review stand out.
#include <QAction>
#include <QComboBox>
#include <QDoubleSpinBox>
#include <QElapsedTimer>
#include <QFile>
#include <QFileInfo>
#include <QJsonArray>
#include <QJsonDocument>
#include <QJsonObject>
#include <QLabel>
#include <QMenu>
#include <QMessageBox>
#include <QProgressBar>
#include <QPushButton>
#include <QSignalSpy>
#include <QStatusBar>
#include <QTableView>
#include <QUndoStack>
#include <QtTest>

#include "ViewTestSupport.h"
#include "boneless/Correspondence.h"
#include "boneless/ui/Document.h"
#include "boneless/ui/ExportDialog.h"
#include "boneless/ui/FrameSolver.h"
#include "boneless/ui/MainWindow.h"
#include "boneless/ui/MarkerListModel.h"
#include "boneless/ui/MeshView.h"
#include "boneless/ui/Timeline.h"

using namespace boneless;
using namespace boneless::ui;

namespace {

// Answers the next modal question by the button with this object name.
void answer(const QString& button) {
    QTimer::singleShot(200, [button] {
        auto* box = qobject_cast<QMessageBox*>(QApplication::activeModalWidget());
        QVERIFY(box);
        QCOMPARE(box->objectName(), QString("mapLoadQuestion"));
        box->findChild<QPushButton*>(button)->click();
    });
}

}  // namespace

class MappingTest : public QObject {
    Q_OBJECT
  public:
    static void initMain() { setDefaultSurfaceFormat(); }

  private slots:
    void initTestCase() {
        test::isolate("MappingTest");
        folder_ = test::freshFolder("MappingTest");
        project_ = test::writeDemoProject(folder_ + "/demo");
    }

    // Outside Map Markers, a click beside the body with a marker selected said "The click missed
    // the mesh: nothing was mapped to RWRA", and a click on it with none selected "select a
    // marker in the list, then click the mesh to map it", as if mapping. They say nothing of
    // mapping there but Map Markers, the way to map; in Map Markers a miss says what it missed.
    void aClickSpeaksOfMappingOnlyInMapMarkersMode() {
        const auto shown = test::openShown(freshProject());
        QVERIFY(shown);
        MainWindow& window = *shown;
        QVERIFY(test::waitForFrame(window));
        Document* d = window.document();
        MeshView* view = window.meshView();
        const auto said = [&] { return window.statusBar()->currentMessage(); };
        d->setSelectedMarker(0);
        const int before = d->mappedVertex(0);
        window.statusBar()->clearMessage();
        QTest::mouseClick(view, Qt::LeftButton, {}, QPoint(3, 3));
        QVERIFY2(!said().contains("mapped"), qPrintable(said()));
        QCOMPARE(d->mappedVertex(0), before);

        QPoint at;
        for (int y = view->height() / 3; y < 2 * view->height() / 3 && at.isNull(); y += 7)
            for (int x = view->width() / 3; x < 2 * view->width() / 3 && at.isNull(); x += 7) {
                const int v = view->pickPoint(QPoint(x, y)).vertex;
                if (v >= 0 && d->markerForVertex(v) < 0) at = QPoint(x, y);
            }
        QVERIFY(!at.isNull());
        d->setSelectedMarker(-1);
        QTest::mouseClick(view, Qt::LeftButton, {}, at);
        QVERIFY2(!said().contains("select a marker") && said().contains("Map Markers"),
                 qPrintable(said()));

        window.findChild<QAction*>("actionMapMarkers")->trigger();
        QTest::mouseClick(view, Qt::LeftButton, {}, at);
        QVERIFY2(said().contains("select a marker"), qPrintable(said()));
        d->setSelectedMarker(0);
        QTest::mouseClick(view, Qt::LeftButton, {}, QPoint(3, 3));
        QVERIFY2(said().contains("missed the mesh: nothing was mapped to"), qPrintable(said()));
        QCOMPARE(d->mappedVertex(0), before);
    }

    // With nothing loaded, Map Markers, Clear, Suggest and Align were enabled and did nothing (or
    // said what was missing). Each is enabled once what it needs is loaded: Map Markers a mesh and
    // markers, Clear a mapped marker selected, Clear All a mapping, Suggest and Align a mesh and
    // a take.
    void eachMarkerEditIsEnabledOnlyOnceWhatItNeedsIsThere() {
        MainWindow window;
        window.setMessageBoxesEnabled(false);
        Document* d = window.document();
        auto enabled = [&](const char* name) {
            const QObject* item = window.findChild<QObject*>(name);
            if (!item) qFatal("no %s in the window", name);
            return item->property("enabled").toBool();
        };
        auto enabledOnes = [&] {
            QStringList on;
            for (const char* name :
                 {"actionMapMarkers", "clearMarker", "actionClearMapping", "actionClearAllMappings",
                  "suggestRest", "actionSuggestRest", "alignTake", "actionAlign"})
                if (enabled(name)) on << name;
            return on.join(' ');
        };
        QVERIFY(!enabled("actionMapMarkers"));
        QVERIFY(!enabled("actionAlign"));
        QCOMPARE(enabledOnes(), QString());
        QVERIFY(window.openFile(folder_ + "/demo/walker.obj"));
        QCOMPARE(enabledOnes(), QString());
        QVERIFY(window.openFile(folder_ + "/demo/walker.c3d"));
        QCOMPARE(enabledOnes(),
                 QString("actionMapMarkers suggestRest actionSuggestRest alignTake actionAlign"));
        QVERIFY(window.openFile(folder_ + "/demo/walker.map.json"));
        QCOMPARE(enabledOnes(), QString("actionMapMarkers actionClearAllMappings suggestRest "
                                        "actionSuggestRest alignTake actionAlign"));
        d->setSelectedMarker(0);
        QVERIFY(enabled("clearMarker") && enabled("actionClearMapping"));
        QVERIFY(d->clearMapping(0));
        QVERIFY(!enabled("clearMarker") && !enabled("actionClearMapping"));
        d->undoStack()->undo();
        QVERIFY(enabled("clearMarker") && enabled("actionClearMapping"));
        QVERIFY(d->clearAllMappings());
        QVERIFY(!enabled("actionClearAllMappings") && !enabled("clearMarker"));
    }

    // A click to look at the body moves no marker: only Map Markers maps.
    void aClickOnTheMeshMapsTheSelectedMarkerOnlyInMapMarkersMode() {
        const auto shown = test::openShown(freshProject());
        QVERIFY(shown);
        MainWindow& window = *shown;
        QVERIFY(test::waitForFrame(window));
        Document* d = window.document();
        MeshView* view = window.meshView();
        QPoint at;
        int vertex = -1;
        for (int y = view->height() / 3; y < 2 * view->height() / 3 && vertex < 0; y += 7)
            for (int x = view->width() / 3; x < 2 * view->width() / 3 && vertex < 0; x += 7) {
                const int v = view->pickPoint(QPoint(x, y)).vertex;
                if (v >= 0 && d->markerForVertex(v) < 0) vertex = v, at = QPoint(x, y);
            }
        QVERIFY(vertex >= 0);
        d->setSelectedMarker(0);
        const int before = d->mappedVertex(0);
        QTest::mouseClick(view, Qt::LeftButton, {}, at);
        QCOMPARE(d->mappedVertex(0), before);
        QVERIFY2(window.statusBar()->currentMessage().contains("Map Markers"),
                 qPrintable(window.statusBar()->currentMessage()));
        auto* mapping = window.findChild<QAction*>("actionMapMarkers");
        mapping->trigger();
        QTest::mouseClick(view, Qt::LeftButton, {}, at);
        QCOMPARE(d->mappedVertex(0), vertex);
        // It sits where the click landed, a point of a face (version 2), drawn under the cursor.
        const SurfacePoint p = d->mappedPoint(0);
        QVERIFY(p.face >= 0);
        const QPoint drawn = view->projectPoint(surfacePosition(d->mesh(), view->positions(), p));
        QVERIFY2((drawn - at).manhattanLength() <= 2,
                 qPrintable(QString("(%1, %2)").arg(drawn.x()).arg(drawn.y())));
        QVERIFY2(window.statusBar()->currentMessage().contains(QString("face %1").arg(p.face)),
                 qPrintable(window.statusBar()->currentMessage()));
        const QJsonDocument written =
            QJsonDocument::fromJson(QByteArray::fromStdString(d->correspondence().toJson()));
        QCOMPARE(written["version"].toInt(), 2);
        // Clicked again a little aside, by the same vertex, it moves there: one more undo step.
        const int steps = d->undoStack()->count();
        QPoint aside;
        for (int dx = -3; dx <= 3 && aside.isNull(); ++dx)
            for (int dy = -3; dy <= 3 && aside.isNull(); ++dy) {
                const SurfacePoint q = view->pickPoint(at + QPoint(dx, dy));
                if (q.vertex == vertex && q.face == p.face &&
                    (q.barycentric - p.barycentric).norm() > 1e-3)
                    aside = QPoint(dx, dy);
            }
        QVERIFY(!aside.isNull());
        QTest::mouseClick(view, Qt::LeftButton, {}, at + aside);
        QCOMPARE(d->undoStack()->count(), steps + 1);
        QVERIFY2(d->undoStack()->undoText().startsWith("Move "),
                 qPrintable(d->undoStack()->undoText()));
        QVERIFY((d->mappedPoint(0).barycentric - p.barycentric).norm() > 1e-3);
    }

    // With the list showing Unmapped markers, selecting a mapped one on the mesh hid its row and
    // cleared the highlight, but the table's current row stayed on the marker chosen before:
    // clicking that row again changed nothing, and Map Markers then moved the hidden marker.
    void aRowClickedAgainAfterTheSelectionWasFilteredOutSelectsItsMarker() {
        const auto shown = test::openShown(freshProject());
        QVERIFY(shown);
        MainWindow& window = *shown;
        Document* d = window.document();
        QVERIFY(d->clearMapping(0));
        QComboBox* states = nullptr;
        for (QComboBox* box : window.findChildren<QComboBox*>())
            if (box->accessibleName() == "Markers shown") states = box;
        QVERIFY(states);
        states->setCurrentIndex(states->findText("Unmapped"));
        QTableView* table = window.markerTable();
        QCOMPARE(table->model()->rowCount(), 1);
        const QModelIndex row = table->model()->index(0, 0);
        const QPoint onRow = table->visualRect(row).center();
        QTest::mouseClick(table->viewport(), Qt::LeftButton, {}, onRow);
        QCOMPARE(d->selectedMarker(), 0);
        d->setSelectedMarker(1);  // as a click on marker 1's vertex does, Map Markers off
        QCOMPARE(d->selectedMarker(), 1);
        QVERIFY(!table->selectionModel()->currentIndex().isValid());
        QTest::mouseClick(table->viewport(), Qt::LeftButton, {}, onRow);
        QCOMPARE(d->selectedMarker(), 0);
    }

    // A head marker mapped onto a foot: the take cannot be solved with this map. The status says
    // so and the playhead's frame is shown unposed, not the last answer under "solving…".
    void aMapTheTakeCannotBeSolvedWithSaysSoAndShowsThePlayhead() {
        const auto shown = test::openShown(freshProject());
        QVERIFY(shown);
        MainWindow& window = *shown;
        QVERIFY(test::waitForFrame(window));
        Document* d = window.document();
        const int head = d->markerByLabel("LFHD");
        QVERIFY(head >= 0);
        const int foot = test::farthestFreeVertex(*d, head);
        QSignalSpy failed(window.frameSolver(), &FrameSolver::failed);
        QVERIFY(d->assign(head, foot));
        QVERIFY(failed.wait(60000));
        QTRY_VERIFY2(window.frameSummary().contains("Not solving"),
                     qPrintable(window.frameSummary()));
        window.timeline()->scrubTo(20);
        QTRY_COMPARE(window.displayedFrame(), 20);
        QVERIFY2(window.frameSummary().contains("Not solving"), qPrintable(window.frameSummary()));
        d->undoStack()->undo();
        QVERIFY(test::waitForFrame(window));
        QVERIFY2(window.frameSummary().contains("solved"), qPrintable(window.frameSummary()));
    }

    // Markers sit off the skin: the panel sets the selected marker's offset, or every mapped
    // marker's, each one undo step, and a marker mapped next takes the offset the others have.
    void theOffsetOffTheSkinIsSetForOneMarkerOrAllAndANewPickTakesIt() {
        MainWindow window;
        window.setMessageBoxesEnabled(false);
        QVERIFY(window.openProject(freshProject()));
        Document* d = window.document();
        auto* spin = window.findChild<QDoubleSpinBox*>("offsetSpin");
        auto* all = window.findChild<QPushButton*>("offsetAll");
        QVERIFY(spin && all);
        d->setSelectedMarker(-1);
        QVERIFY(!spin->isEnabled());
        d->setSelectedMarker(0);
        QVERIFY(spin->isEnabled());
        QCOMPARE(spin->value(), d->markerOffsetMm(0));
        const double before = d->markerOffsetMm(1);
        spin->setValue(12.5);
        QCOMPARE(d->markerOffsetMm(0), 12.5);
        QCOMPARE(d->markerOffsetMm(1), before);
        all->click();
        for (int m = 0; m < d->markerCount(); ++m)
            if (d->mappedVertex(m) >= 0) QCOMPARE(d->markerOffsetMm(m), 12.5);
        d->undoStack()->undo();
        QCOMPARE(d->markerOffsetMm(1), before);
        QCOMPARE(d->markerOffsetMm(0), 12.5);
        all->click();
        // Unmapped and mapped again, onto a free vertex: it takes the 12.5 mm the others have.
        const int vertex = d->mappedVertex(3);
        QVERIFY(d->clearMapping(3));
        QVERIFY(d->assign(3, vertex));
        QCOMPARE(d->markerOffsetMm(3), 12.5);
        // Saved as offset_mm, read back as such.
        const QString path = folder_ + "/offsets.json";
        QVERIFY(d->saveCorrespondence(path));
        QCOMPARE(Correspondence::read(path.toStdString()).markers.front().offsetMm, 12.5);
        // Not a marker's offset: refused, and nothing changes.
        QVERIFY(!d->setOffsetMm({0}, 5000));
        QVERIFY(!d->setOffsetMm({0}, std::nan("")));
        QCOMPARE(d->markerOffsetMm(0), 12.5);
    }

    // Four picks spread over the body, as DocumentTest's suggestion test makes them.
    static void keepFourPicks(Document* d) {
        for (int m = 0; m < d->markerCount(); ++m) {
            bool kept = false;
            for (const char* label : {"RFHD", "LWRA", "RANK", "LASI"})
                kept |= d->markerLabel(m).endsWith(label);
            if (!kept) QVERIFY(d->clearMapping(m));
        }
        QCOMPARE(d->mappedCount(), 4);
    }
    static QPushButton* suggestButton(MainWindow& window) {
        return window.findChild<QPushButton*>("suggestRest");
    }

    void suggestRestSaysHowManyItSuggested() {
        MainWindow window;
        window.setMessageBoxesEnabled(false);
        QVERIFY(window.openProject(freshProject()));
        Document* d = window.document();
        const Correspondence truth = d->correspondence();
        keepFourPicks(d);
        QPushButton* suggest = suggestButton(window);
        QVERIFY(suggest);
        // It runs on a worker: the status bar says so until it ends.
        const auto suggestAndWait = [&] {
            suggest->click();
            QTRY_VERIFY_WITH_TIMEOUT(!window.statusBar()->currentMessage().startsWith("Suggesting"),
                                     30000);
        };
        suggestAndWait();
        QCOMPARE(d->mappedCount(), d->markerCount());
        const QString said = window.statusBar()->currentMessage();
        QVERIFY2(said.startsWith(QString("%1 markers suggested").arg(d->markerCount() - 4)),
                 qPrintable(said));
        QCOMPARE(d->undoStack()->undoText(),
                 QString("Suggest %1 markers").arg(d->markerCount() - 4));
        // The demo's markers sit 10 mm off the skin; nearly all land on their own vertex.
        int same = 0;
        for (const MarkerMapping& m : d->correspondence().markers)
            for (const MarkerMapping& t : truth.markers)
                same += t.label == m.label && t.vertex == m.vertex;
        QVERIFY2(same >= 34, qPrintable(QString::number(same)));
        // Editing a suggestion makes it the user's own entry.
        int free = 0;
        while (d->markerForVertex(free) >= 0) ++free;
        int edited = 0;
        while (!d->markerSuggested(edited)) ++edited;
        QVERIFY(d->assign(edited, free));
        QVERIFY(!d->markerSuggested(edited));
        d->undoStack()->undo();
        // A later click counts what it adds, not the suggestions the map already holds.
        int dropped = 0;
        while (!d->markerSuggested(dropped)) ++dropped;
        QVERIFY(d->clearMapping(dropped));
        suggestAndWait();
        QCOMPARE(d->mappedCount(), d->markerCount());
        QVERIFY2(window.statusBar()->currentMessage().startsWith("1 marker suggested"),
                 qPrintable(window.statusBar()->currentMessage()));
        QCOMPARE(d->undoStack()->undoText(), QString("Suggest 1 marker"));
        suggestAndWait();
        QVERIFY2(window.statusBar()->currentMessage().startsWith("Nothing to suggest"),
                 qPrintable(window.statusBar()->currentMessage()));
    }

    // Suggest Rest ran on the window's thread: on a 100K-face koala the window froze for 43 s.
    // Now the event loop turns while it runs (a timer fires, the view repaints), the window says
    // it is suggesting, edits wait, and the map is applied as one step when it ends.
    void suggestRestKeepsTheWindowRunningAndMapsWhenItEnds() {
        MainWindow window;
        window.setMessageBoxesEnabled(false);
        QVERIFY(window.openProject(freshProject()));
        Document* d = window.document();
        keepFourPicks(d);
        const int steps = d->undoStack()->count();
        int ticks = 0, ticksWhenMapped = -1;
        QTimer timer;
        timer.setInterval(0);
        connect(&timer, &QTimer::timeout, [&] { ++ticks; });
        connect(d->undoStack(), &QUndoStack::indexChanged, [&] {
            if (ticksWhenMapped < 0) ticksWhenMapped = ticks;
        });
        timer.start();
        suggestButton(window)->click();
        QCOMPARE(d->mappedCount(), 4);  // not yet: it runs on a worker
        QVERIFY2(window.statusBar()->currentMessage().startsWith("Suggesting the rest of the map"),
                 qPrintable(window.statusBar()->currentMessage()));
        auto* busy = window.findChild<QProgressBar*>("busyBar");
        QVERIFY(busy && busy->isVisibleTo(&window));
        QVERIFY(d->editsHeld());
        QVERIFY(!d->clearMapping(0));
        QTRY_COMPARE_WITH_TIMEOUT(d->mappedCount(), d->markerCount(), 30000);
        QVERIFY2(ticksWhenMapped > 0, qPrintable(QString::number(ticksWhenMapped)));
        QCOMPARE(d->undoStack()->count(), steps + 1);
        QVERIFY(!busy->isVisibleTo(&window));
        QVERIFY(!d->editsHeld());
        QVERIFY2(window.statusBar()->currentMessage().contains("markers suggested"),
                 qPrintable(window.statusBar()->currentMessage()));
    }

    // A suggestion is made from the mesh, take and map as they were when it started: one that
    // ends after the take was opened again is dropped, not applied to inputs it was not made from.
    void aSuggestionWhoseTakeChangedMeanwhileIsDropped() {
        MainWindow window;
        window.setMessageBoxesEnabled(false);
        QVERIFY(window.openProject(freshProject()));
        Document* d = window.document();
        keepFourPicks(d);
        suggestButton(window)->click();
        QVERIFY(d->loadTake(d->takePath()));
        QTRY_VERIFY_WITH_TIMEOUT(window.statusBar()->currentMessage().contains("dropped"), 30000);
        QVERIFY(!d->undoStack()->undoText().startsWith("Suggest"));
        QCOMPARE(d->mappedCount(), 4);
    }

    // Saving the map changes no entry: until 2 December 2026 it counted as a new map, so a save
    // cleared every solved frame (the app solved them all again) and dropped a running suggestion.
    void savingTheMapKeepsTheSolvedFramesAndARunningSuggestion() {
        MainWindow window;
        window.setMessageBoxesEnabled(false);
        QVERIFY(window.openProject(freshProject()));
        Document* d = window.document();
        FrameSolver* solver = window.frameSolver();
        QTRY_VERIFY_WITH_TIMEOUT(solver->hasProblem(), 30000);  // set a turn of the loop later
        solver->requestFrame(5);
        QTRY_VERIFY_WITH_TIMEOUT(solver->isCached(5), 30000);
        const quint64 generation = solver->generation();
        const QString saved = QFileInfo(d->correspondencePath()).dir().filePath("saved.map.json");
        QVERIFY(window.saveCorrespondenceAs(saved));
        QCOMPARE(d->correspondencePath(), saved);
        QVERIFY(!d->correspondenceModified());
        QTest::qWait(200);  // a refresh of the solver's problem is queued, not run at once
        QCOMPARE(solver->generation(), generation);
        QVERIFY(solver->isCached(5));

        keepFourPicks(d);
        suggestButton(window)->click();
        QVERIFY(window.isSuggesting());
        QVERIFY(window.saveCorrespondenceAs(saved));
        QTRY_VERIFY_WITH_TIMEOUT(!window.isSuggesting(), 30000);
        QCOMPARE(d->mappedCount(), d->markerCount());
        QVERIFY(d->undoStack()->undoText().startsWith("Suggest"));
        QVERIFY(d->correspondenceModified());  // the suggestion is not in the saved file
        QCOMPARE(Correspondence::read(saved.toStdString()).markers.size(), std::size_t(4));
    }

    // Four picks cleared down to none: Suggest Rest says it needs four, and maps nothing. It ran,
    // then said only "Suggest Rest failed.", the reason under Show Details; now it says why
    // before it starts.
    void suggestRestNeedsFourMarkers() {
        MainWindow window;
        window.setMessageBoxesEnabled(false);
        QVERIFY(window.openProject(freshProject()));
        Document* d = window.document();
        QVERIFY(d->clearAllMappings());
        QSignalSpy errors(&window, &MainWindow::errorShown);
        QVERIFY(!window.suggestMappings());
        QVERIFY(!window.isSuggesting());
        QCOMPARE(errors.count(), 1);
        QVERIFY2(errors.first().at(0).toString().contains(
                     "Map at least 4 markers to suggest the rest: the take is aligned from them "
                     "(0 mapped)."),
                 qPrintable(errors.first().at(0).toString()));
        QCOMPARE(d->mappedCount(), 0);
    }

    // A suggestion running when the window closed ran to its end (half a minute on a 100K-face
    // mesh) before the app quit. Closing stops it between the fits it scans, and the map is left
    // as it was.
    void closingTheWindowStopsARunningSuggestionAndMapsNothing() {
        QElapsedTimer clock;
        qint64 whole = 0;
        {
            MainWindow window;
            window.setMessageBoxesEnabled(false);
            QVERIFY(window.openProject(freshProject()));
            keepFourPicks(window.document());
            QSignalSpy finished(&window, &MainWindow::suggestionFinished);
            clock.start();
            QVERIFY(window.suggestMappings());
            QVERIFY(finished.wait(30000));
            whole = clock.elapsed();
        }
        MainWindow window;
        window.setMessageBoxesEnabled(false);
        QVERIFY(window.openProject(freshProject()));
        Document* d = window.document();
        keepFourPicks(d);
        const int steps = d->undoStack()->count();
        QSignalSpy finished(&window, &MainWindow::suggestionFinished);
        QVERIFY(window.suggestMappings());
        QTest::qWait(int(whole / 4));  // under way
        QVERIFY2(finished.isEmpty(), "it ended before the window closed");
        clock.restart();
        QVERIFY(window.close());
        QVERIFY(finished.wait(30000));
        const qint64 stopping = clock.elapsed();
        QVERIFY2(
            stopping < whole / 2,
            qPrintable(QString("%1 ms to stop, %2 ms for the whole").arg(stopping).arg(whole)));
        QCOMPARE(finished.first().at(0).toBool(), false);
        QCOMPARE(d->mappedCount(), 4);
        QCOMPARE(d->undoStack()->count(), steps);
    }

    void openingAMapOverMappingsAsksReplaceMergeOrCancel() {
        MainWindow window;
        QVERIFY(window.openProject(project_));
        QVERIFY(test::showAndWait(window));
        Document* d = window.document();
        const QString map = folder_ + "/demo/walker.map.json";
        const int all = d->markerCount();
        const int fileVertex = d->mappedVertex(1);
        // A hand-made mapping the file disagrees with, on a vertex the file does not use.
        int mine = 0;
        while (d->markerForVertex(mine) >= 0) ++mine;
        QVERIFY(d->clearMapping(0));
        QVERIFY(d->clearMapping(1));
        QVERIFY(d->assign(1, mine));

        answer("cancelButton");
        QVERIFY(!window.openFile(map));
        QCOMPARE(d->mappedCount(), all - 1);

        answer("mergeButton");
        QVERIFY(window.openFile(map));
        QCOMPARE(d->mappedCount(), all);     // marker 0 from the file
        QCOMPARE(d->mappedVertex(1), mine);  // marker 1 kept as made

        answer("replaceButton");
        QVERIFY(window.openFile(map));
        QCOMPARE(d->mappedVertex(1), fileVertex);
        QCOMPARE(d->mappedCount(), all);
    }

    // A map that cannot be used is said so at once: asked first, the user chose Merge or Replace
    // for nothing. A merge that adds nothing says so, and is no undo step.
    void aMapIsCheckedBeforeAskingAndAMergeOfNothingSaysSo() {
        MainWindow window;
        const QString project = freshProject();
        QVERIFY(window.openProject(project));
        QVERIFY(test::showAndWait(window));
        Document* d = window.document();
        int asked = 0;
        QTimer answering;
        connect(&answering, &QTimer::timeout, [&asked] {
            auto* box = qobject_cast<QMessageBox*>(QApplication::activeModalWidget());
            if (!box || box->objectName() != "mapLoadQuestion") return;
            ++asked;
            box->findChild<QPushButton*>("cancelButton")->click();
        });
        answering.start(100);
        const QString broken = folder_ + "/broken.map.json";
        QFile file(broken);
        QVERIFY(file.open(QIODevice::WriteOnly));
        file.write("{\"markers\": [");
        file.close();
        QSignalSpy errors(&window, &MainWindow::errorShown);
        QVERIFY(!window.openFile(broken));
        answering.stop();
        QCOMPARE(asked, 0);
        QCOMPARE(errors.count(), 1);
        for (auto* box : window.findChildren<QMessageBox*>("errorMessage")) box->close();

        // The project's own map again: every marker is mapped, so there is nothing to merge.
        const int steps = d->undoStack()->count();
        answer("mergeButton");
        QVERIFY(window.openFile(QFileInfo(project).dir().filePath("walker.map.json")));
        QCOMPARE(d->undoStack()->count(), steps);
        QVERIFY2(window.statusBar()->currentMessage().startsWith("Nothing merged from"),
                 qPrintable(window.statusBar()->currentMessage()));
    }

    // A map of another actor's labels: the status bar said "Not solving: The map names markers
    // the take does not have: " and every label, cut off by the bar's end, and not what to do.
    void aMapTheTakeDoesNotFitSaysSoBrieflyAndWhatToDo() {
        MainWindow window;
        window.setMessageBoxesEnabled(false);
        const QString project = freshProject();
        QVERIFY(window.openProject(project));
        QVERIFY(test::showAndWait(window));
        QFile own(QFileInfo(project).dir().filePath("walker.map.json"));
        QVERIFY(own.open(QIODevice::ReadOnly));
        QJsonObject map = QJsonDocument::fromJson(own.readAll()).object();
        QJsonArray markers = map["markers"].toArray();
        QStringList labels;
        for (int k = 0; k < markers.size(); ++k) {
            QJsonObject m = markers[k].toObject();
            m["label"] = "X_" + m["label"].toString();  // no marker of the take
            labels << m["label"].toString();
            markers[k] = m;
        }
        map["markers"] = markers;
        const QString foreign = folder_ + "/foreign.map.json";
        QFile file(foreign);
        QVERIFY(file.open(QIODevice::WriteOnly));
        file.write(QJsonDocument(map).toJson());
        file.close();
        QVERIFY(window.openFile(foreign));

        auto* solve = window.findChild<QLabel*>("solveLabel");
        QVERIFY(solve);
        QTRY_VERIFY2(solve->text().startsWith("Not solving"), qPrintable(solve->text()));
        const QString said = solve->text();
        QVERIFY2(said.contains(QString("%1 markers the take does not have").arg(labels.size())),
                 qPrintable(said));
        QVERIFY2(said.contains("Edit → Clear All Mappings"), qPrintable(said));
        QVERIFY2(said.contains(labels[0]) && !said.contains(labels[5]), qPrintable(said));
        for (const QString& label : labels)
            QVERIFY2(solve->toolTip().contains(label), qPrintable(label));
    }

    // A mesh with a part no marker is on (a prop beside the body): the CLI notes that it is
    // carried rigidly, the app said nothing. The status bar says so, its tooltip as the CLI does.
    void aPartWithNoMarkerIsSaidToBeCarriedRigidly() {
        const QDir dir = QFileInfo(freshProject()).dir();
        QFile walker(dir.filePath("walker.obj"));
        QVERIFY(walker.open(QIODevice::ReadOnly));
        QByteArray obj = walker.readAll();
        const int n = obj.count("\nv ") + (obj.startsWith("v ") ? 1 : 0);
        obj += "v 1 1 0\nv 1.1 1 0\nv 1 1.1 0\nv 1 1 0.1\n";
        for (const char* face : {"1 3 2", "1 2 4", "1 4 3", "2 3 4"}) {
            const QStringList corners = QString(face).split(' ');
            obj += "f";
            for (const QString& c : corners) obj += " " + QByteArray::number(n + c.toInt());
            obj += "\n";
        }
        const QString prop = dir.filePath("walker-prop.obj");
        QFile out(prop);
        QVERIFY(out.open(QIODevice::WriteOnly));
        out.write(obj);
        out.close();
        boneless::Correspondence map =
            boneless::Correspondence::read(dir.filePath("walker.map.json").toStdString());
        map.meshVertices = n + 4;
        map.meshFile = "walker-prop.obj";
        map.write(dir.filePath("prop.map.json").toStdString());

        MainWindow window;
        window.setMessageBoxesEnabled(false);
        QVERIFY(
            window.openFiles({prop, dir.filePath("walker.c3d"), dir.filePath("prop.map.json")}));
        QVERIFY(test::showAndWait(window));
        auto* solve = window.findChild<QLabel*>("solveLabel");
        QVERIFY(solve);
        QTRY_VERIFY2(solve->text().contains("1 part carried rigidly"), qPrintable(solve->text()));
        QVERIFY2(solve->toolTip().contains("follows the nearest marked part rigidly"),
                 qPrintable(solve->toolTip()));

        // The walker alone: nothing carried, nothing said.
        QVERIFY(window.openFiles({dir.filePath("walker.obj"), dir.filePath("walker.c3d"),
                                  dir.filePath("walker.map.json")}));
        QTRY_VERIFY2(solve->text().startsWith("solved") || solve->text().startsWith("cached"),
                     qPrintable(solve->text()));
        QVERIFY2(!solve->text().contains("carried"), qPrintable(solve->text()));
    }

    void whileMappingTheMeshAndCameraHoldStillAndLeavingShowsThePlayhead() {
        MainWindow window;
        window.setMessageBoxesEnabled(false);
        QVERIFY(window.openProject(freshProject()));
        QVERIFY(test::showAndWait(window));
        window.timeline()->scrubTo(30);
        QVERIFY(test::waitForFrame(window));
        MeshView* view = window.meshView();
        Document* d = window.document();

        auto* mapping = window.findChild<QAction*>("actionMapMarkers");
        QVERIFY(mapping);
        mapping->trigger();
        QVERIFY(mapping->isChecked());
        const Positions held = view->positions();
        const QVariantMap camera = view->cameraState();

        // A mapping moved to a neighbouring vertex: the frame is solved again from the new map.
        const Faces& F = d->mesh().F;
        int neighbour = -1;
        for (int t = 0; t < F.rows() && neighbour < 0; ++t)
            for (int c = 0; c < 3; ++c)
                if (F(t, c) == d->mappedVertex(0))
                    for (int o = 1; o < 3; ++o)
                        if (neighbour < 0 && d->markerForVertex(F(t, (c + o) % 3)) < 0)
                            neighbour = F(t, (c + o) % 3);
        QVERIFY(neighbour >= 0);
        QVERIFY(d->assign(0, neighbour));
        window.timeline()->scrubTo(45);
        QTest::qWait(300);
        QVERIFY(QTest::qWaitFor([&] { return !window.frameSolver()->isBusy(); }, 60000));
        QTest::qWait(100);
        QCOMPARE(view->positions(), held);
        QCOMPARE(view->cameraState(), camera);
        QCOMPARE(window.displayedFrame(), 30);
        const QString status = window.frameSummary();
        QVERIFY2(status.contains("held while mapping; playhead at 45"), qPrintable(status));

        mapping->trigger();
        QVERIFY(!mapping->isChecked());
        QVERIFY(test::waitForFrame(window));
        QCOMPARE(window.displayedFrame(), 45);
        QVERIFY((view->positions() - held).cwiseAbs().maxCoeff() > 1e-6);
    }

    // An export solves the map, alignment and settings it started with: an edit made while it ran
    // was not in what it wrote, yet every edit stayed enabled. They wait for it to end, and Map
    // Markers is left.
    void theMapIsNotEditedWhileAnExportSolvesIt() {
        MainWindow window;
        window.setMessageBoxesEnabled(false);
        QVERIFY(window.openProject(freshProject()));
        QVERIFY(test::showAndWait(window));
        Document* d = window.document();
        d->setSelectedMarker(0);
        QVERIFY(d->setOffsetMm({0}, 12.0));  // something to undo
        auto* mapping = window.findChild<QAction*>("actionMapMarkers");
        mapping->trigger();
        QVERIFY(mapping->isChecked());
        const char* const edits[] = {"actionMapMarkers",
                                     "clearMarker",
                                     "actionClearMapping",
                                     "actionClearAllMappings",
                                     "suggestRest",
                                     "actionSuggestRest",
                                     "alignTake",
                                     "actionAlign",
                                     "calibrateAtFrame",
                                     "calibrateAutomatically",
                                     "calibrateNone",
                                     "offsetSpin",
                                     "offsetAll",
                                     "actionUndo",
                                     "actionOpenCorrespondence"};
        auto enabledOnes = [&] {
            QStringList on;
            for (const char* name : edits) {
                const QObject* item = window.findChild<QObject*>(name);
                if (!item || item->property("enabled").toBool()) on << name;
            }
            for (const char* menu : {"meshUp", "takeUnits"})
                if (window.findChild<QMenu*>(menu)->menuAction()->isEnabled()) on << menu;
            return on.join(' ');
        };
        const QString before = enabledOnes();
        QVERIFY2(before.contains("actionUndo") && before.contains("calibrateAtFrame") &&
                     before.contains("takeUnits"),
                 qPrintable(before));

        ExportDialog* dialog = window.exportDialog();
        QSignalSpy finished(dialog, &ExportDialog::finished);
        dialog->setFolder(folder_ + "/exportWhileEditing");
        dialog->setRange(ExportDialog::Range::All);
        QVERIFY(dialog->startExport());
        QCOMPARE(enabledOnes(), QString());
        QVERIFY(!mapping->isChecked());  // a click maps nothing
        QVERIFY(finished.wait(120000));
        QVERIFY(finished.at(0).at(0).toBool());
        QCOMPARE(enabledOnes(), before);
    }

    void openingAMeshOrTakeLeavesMappingMode() {
        MainWindow window;
        window.setMessageBoxesEnabled(false);
        QVERIFY(window.openProject(freshProject()));
        QVERIFY(test::showAndWait(window));
        auto* mapping = window.findChild<QAction*>("actionMapMarkers");
        mapping->trigger();
        QVERIFY(window.openFile(window.document()->takePath()));
        QVERIFY(!mapping->isChecked());
        QVERIFY(test::waitForFrame(window));
    }

    void suggestionsToReviewAreHighlighted() {
        // A map as `boneless-cli map suggest` writes it, one suggestion marked for review.
        const QString project = freshProject();
        QFile in(QFileInfo(project).absolutePath() + "/walker.map.json");
        QVERIFY(in.open(QIODevice::ReadOnly));
        QJsonObject map = QJsonDocument::fromJson(in.readAll()).object();
        QJsonArray markers = map["markers"].toArray();
        QVERIFY(markers.size() > 20);
        QString farLabel;
        for (int i = 4; i < 20; ++i) {
            QJsonObject entry = markers[i].toObject();
            entry["suggested"] = true;
            if (i == 11) {
                entry["needs_review"] = true;
                entry["review_reason"] = "80 mm from the fitted mesh";
                farLabel = entry["label"].toString();
            }
            markers[i] = entry;
        }
        map["markers"] = markers;
        const QString path = folder_ + "/suggested.json";
        QFile out(path);
        QVERIFY(out.open(QIODevice::WriteOnly));
        out.write(QJsonDocument(map).toJson());
        out.close();

        MainWindow window;
        window.setMessageBoxesEnabled(false);
        QVERIFY(window.openProject(project));
        QVERIFY(window.document()->loadCorrespondence(path));
        QAbstractItemModel* model = window.markerTable()->model();
        Document* d = window.document();
        const int far = d->markerByLabel(farLabel);
        QVERIFY(far >= 0);
        QList<int> highlighted;
        for (int row = 0; row < model->rowCount(); ++row)
            if (model->index(row, 0).data(Qt::BackgroundRole).isValid())
                highlighted << model->index(row, 0).data(MarkerListModel::MarkerRole).toInt();
        QCOMPARE(highlighted, QList<int>{far});
        // And the table paints it so: its row, and only its row, in the highlight's colour.
        QVERIFY(test::showAndWait(window));
        QVERIFY2(highlightedPixels(window, far) > 0.5, "the doubtful row is not highlighted");
        QCOMPARE(highlightedPixels(window, far == 0 ? 1 : 0), 0.0);
        // Mapping it onto its own vertex is the user's word that it is right; Undo doubts again.
        const int vertex = d->mappedVertex(far);
        QVERIFY(d->assign(far, vertex));
        QCOMPARE(d->mappedVertex(far), vertex);
        for (int row = 0; row < model->rowCount(); ++row)
            QVERIFY(!model->index(row, 0).data(Qt::BackgroundRole).isValid());
        d->undoStack()->undo();
        QVERIFY(model->index(0, 0).isValid());
        int doubtful = 0;
        for (int row = 0; row < model->rowCount(); ++row)
            doubtful += model->index(row, 0).data(Qt::BackgroundRole).isValid();
        QCOMPARE(doubtful, 1);
        // Unmapping it clears the doubt.
        QVERIFY(d->clearMapping(far));
        for (int row = 0; row < model->rowCount(); ++row)
            QVERIFY(!model->index(row, 0).data(Qt::BackgroundRole).isValid());
        QCOMPARE(highlightedPixels(window, far), 0.0);
    }

    // The solve's residual says how well frames meet the markers, not whether the take sits on
    // the mesh: the alignment's own residual is shown too, and a wrong mapping raises it.
    void aligningSaysHowFarTheMappedMarkersSitFromTheMesh() {
        const auto shown = test::openShown(freshProject());
        QVERIFY(shown);
        MainWindow& window = *shown;
        Document* d = window.document();
        auto* residual = window.findChild<QLabel*>("residualLabel");
        QVERIFY(residual);
        // As boneless-cli solve prints it: mesh units back to the take's millimetres.
        auto mm = [&](const Calibration& c) {
            return QString::number(c.residual * d->take().unitToMm / c.takeToMesh.scale, 'f', 1);
        };
        // Automatic: the alignment the frame was solved with.
        QVERIFY2(residual->text().contains(QRegularExpression("alignment \\d+\\.\\d mm")),
                 qPrintable(residual->text()));

        QPushButton* align = nullptr;
        for (QPushButton* b : window.findChildren<QPushButton*>())
            if (b->text() == "Align") align = b;
        QVERIFY(align);
        align->click();
        QVERIFY(d->alignment());
        const double good =
            d->alignment()->residual * d->take().unitToMm / d->alignment()->takeToMesh.scale;
        QString said = window.statusBar()->currentMessage();
        QVERIFY2(said.contains(QString("frame %1").arg(d->alignment()->frame)) &&
                     said.contains(mm(*d->alignment()) + " mm"),
                 qPrintable(said));
        QVERIFY(test::waitForFrame(window));
        QVERIFY2(residual->text().contains("alignment " + mm(*d->alignment()) + " mm"),
                 qPrintable(residual->text()));

        // A head marker mapped onto the far end of the body pulls the fit away.
        const int head = d->markerByLabel("LFHD");
        const int foot = test::farthestFreeVertex(*d, head);
        QVERIFY(d->assign(head, foot));
        align->click();
        const double bad =
            d->alignment()->residual * d->take().unitToMm / d->alignment()->takeToMesh.scale;
        QVERIFY2(bad > good + 20, qPrintable(QString("%1 mm, then %2 mm").arg(good).arg(bad)));
        said = window.statusBar()->currentMessage();
        QVERIFY2(said.contains(mm(*d->alignment()) + " mm"), qPrintable(said));
    }

    // A project's alignment is shown as it fits the take, whatever residual the file claims: a
    // hand-edited one that throws the take off the body must not read as 0 mm.
    void anAlignmentFromAProjectShowsItsMeasuredResidualNotTheStoredOne() {
        const QString project = freshProject();
        QFile file(project);
        QVERIFY(file.open(QIODevice::ReadOnly));
        QJsonObject root = QJsonDocument::fromJson(file.readAll()).object();
        file.close();
        root["alignment"] = QJsonObject{
            {"calibration_frame", 0},
            {"scale", 1},
            {"rotation", QJsonArray{QJsonArray{1, 0, 0}, QJsonArray{0, 1, 0}, QJsonArray{0, 0, 1}}},
            {"translation", QJsonArray{1000, 1000, 1000}},
            {"residual", 0},
            {"visible_markers", 39}};
        QVERIFY(file.open(QIODevice::WriteOnly | QIODevice::Truncate));
        file.write(QJsonDocument(root).toJson());
        file.close();

        const auto shown = test::openShown(project);
        QVERIFY(shown);
        QVERIFY(shown->document()->alignment());
        const QString text = shown->findChild<QLabel*>("residualLabel")->text();
        const QRegularExpressionMatch said =
            QRegularExpression("alignment (\\d+\\.\\d) mm").match(text);
        QVERIFY2(said.hasMatch(), qPrintable(text));
        QVERIFY2(said.captured(1).toDouble() > 10, qPrintable(text));
    }

  private:
    // The share of the marker's row, as the table draws it, in the doubtful suggestion's colour.
    static double highlightedPixels(MainWindow& window, int marker) {
        QTableView* table = window.markerTable();
        QAbstractItemModel* model = table->model();
        for (int row = 0; row < model->rowCount(); ++row) {
            const QModelIndex index = model->index(row, 0);
            if (index.data(MarkerListModel::MarkerRole).toInt() != marker) continue;
            table->scrollTo(index);
            const QImage image = table->viewport()->grab().toImage();
            QRect rect = table->visualRect(index);
            rect.setRight(table->visualRect(model->index(row, model->columnCount() - 1)).right());
            rect &= image.rect();
            int coloured = 0;
            for (int y = rect.top(); y <= rect.bottom(); ++y)
                for (int x = rect.left(); x <= rect.right(); ++x)
                    coloured += QColor(image.pixel(x, y)) == QColor(255, 200, 120);
            return rect.isEmpty() ? 0.0 : double(coloured) / (rect.width() * rect.height());
        }
        return 0.0;
    }

    // A demo project of its own: autosave writes each test's edits into its project.
    QString freshProject() {
        return test::writeDemoProject(folder_ + QString("/demo%1").arg(++projects_));
    }

    QString folder_, project_;
    int projects_ = 0;
};

QTEST_MAIN(MappingTest)
#include "MappingTest.moc"
