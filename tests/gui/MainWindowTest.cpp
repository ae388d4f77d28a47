// The window as a user drives it: open the demo, scrub, play, keyboard, and bad files that must
// give a message while the window keeps working.
#include <QAction>
#include <QComboBox>
#include <QDir>
#include <QFile>
#include <QLabel>
#include <QMenu>
#include <QMessageBox>
#include <QMimeData>
#include <QSettings>
#include <QSlider>
#include <QStandardPaths>
#include <QStatusBar>
#include <QUrl>
#include <QtTest>
#include <map>

#include "ViewTestSupport.h"
#include "boneless/C3dReader.h"
#include "boneless/C3dWriter.h"
#include "boneless/Correspondence.h"
#include "boneless/ui/Document.h"
#include "boneless/ui/ExportDialog.h"
#include "boneless/ui/FrameSolver.h"
#include "boneless/ui/MainWindow.h"
#include "boneless/ui/MeshView.h"
#include "boneless/ui/Timeline.h"
#include "boneless/ui/TimelineWidget.h"

using namespace boneless;
using namespace boneless::ui;

namespace {

double maxDistance(const Positions& a, const Positions& b) {
    return (a - b).rowwise().norm().maxCoeff();
}

}  // namespace

class MainWindowTest : public QObject {
    Q_OBJECT
  public:
    static void initMain() { setDefaultSurfaceFormat(); }

  private slots:
    void initTestCase() { project_ = test::demoProjectFor("MainWindowTest", &folder_); }

    void init() {
        window_ = test::openShown(project_);
        QVERIFY(window_);
    }
    void cleanup() { window_.reset(); }

    void opensDemoSolvedAndAnimated() {
        Document* document = window_->document();
        QVERIFY(document->hasMesh());
        QVERIFY(document->hasTake());
        QVERIFY(window_->isSolving());
        QCOMPARE(window_->displayedFrame(), 0);
        const QString status = window_->findChild<QLabel*>("residualLabel")->text();
        QVERIFY2(status.contains("mm"), qPrintable(status));

        // A solved frame is a deformed mesh, not the rest pose.
        window_->timeline()->scrubTo(30);
        QVERIFY(test::waitForFrame(*window_));
        QCOMPARE(window_->displayedFrame(), 30);
        const double moved = maxDistance(window_->meshView()->positions(), document->mesh().V);
        const double size = boundingBoxDiagonal(document->mesh().V);
        QVERIFY2(moved > 0.02 * size, qPrintable(QString("moved %1 of %2").arg(moved).arg(size)));
    }

    // At start-up the status bar said "Frame -1 / 809 (preview; playhead at 0) solving frame 0…"
    // for the whole preparation (12 s on a 100K-face mesh). Until the first frame is solved it
    // says what is happening, over the playhead's frame.
    void untilTheFirstFrameIsSolvedTheStatusSaysTheSolverIsBeingPrepared() {
        MainWindow window;
        window.setMessageBoxesEnabled(false);
        QStringList said;
        // Queued: read after the window has shown the new problem, before any frame of it
        // arrives (the worker posts that after this, once its solver is built).
        connect(
            window.frameSolver(), &FrameSolver::problemChanged, &window,
            [&] { said << window.frameSummary(); }, Qt::QueuedConnection);
        QVERIFY(window.openProject(project_));
        QVERIFY(test::showAndWait(window));
        QVERIFY(test::waitForFrame(window));
        QVERIFY(!said.isEmpty());
        for (const QString& summary : said) {
            QVERIFY2(!summary.contains("Frame -1"), qPrintable(summary));
            QVERIFY2(!summary.contains("preview"), qPrintable(summary));
        }
        QVERIFY2(said.back().contains("preparing the solver for walker.obj"),
                 qPrintable(said.back()));
        QVERIFY2(window.frameSummary().startsWith("Frame 0 / "), qPrintable(window.frameSummary()));
    }

    void looseFilesOpenedOneByOneStandTheMeshUp() {
        // The demo's mesh is Z-up; the take and its map say so once both are open, whichever
        // comes last (a map after the take used to leave the view Y-up, the body on the floor).
        MainWindow window;
        window.setMessageBoxesEnabled(false);
        QVERIFY(window.openFile(folder_ + "/demo/walker.obj"));
        QVERIFY(window.meshView()->upAxis().isApprox(Eigen::Vector3d::UnitY()));
        QVERIFY(window.openFile(folder_ + "/demo/walker.c3d"));
        QVERIFY(window.openFile(folder_ + "/demo/walker.map.json"));
        QVERIFY(window.meshView()->upAxis().isApprox(Eigen::Vector3d::UnitZ()));
    }

    // A version 1 map whose entry gives a "face" (which only version 2 reads) opened in silence:
    // `solve` warned, naming the file and the entry, and the app said "Opened" alone, the marker
    // sitting on its vertex unknown to the user. The map's own notes are said as a take's are.
    void aMapsOwnWarningIsSaidWhenItOpens() {
        Correspondence map =
            Correspondence::read((folder_ + "/demo/walker.map.json").toStdString());
        map.markers[0].extraJson = R"({"face": 7})";  // a key of its own in a version 1 file
        const QString path = folder_ + "/v1face.map.json";
        map.write(path.toStdString());
        MainWindow window;
        window.setMessageBoxesEnabled(false);
        QVERIFY(window.openFile(folder_ + "/demo/walker.obj"));
        QVERIFY(window.openFile(folder_ + "/demo/walker.c3d"));
        QVERIFY(window.openFile(path));
        const QString said = window.statusBar()->currentMessage();
        QVERIFY2(said.startsWith("Opened v1face.map.json, with a note: " + path + ": marker " +
                                 QString::fromStdString(map.markers[0].label) + " has \"face\": 7"),
                 qPrintable(said));
        QVERIFY(window.openFile(folder_ + "/demo/walker.map.json"));
        QCOMPARE(window.statusBar()->currentMessage(), QString("Opened walker.map.json"));
    }

    void aTakeWhoseYScreenSaysPlusYStandsTheMeshUpAsItsZUpTwin() {
        // The demo's take turned a quarter about X, Y up, and saying so: its +Z, now horizontal,
        // used to go to the mesh's up, and the view's floor stood on end.
        C3dTake take = readC3d((folder_ + "/demo/walker.c3d").toStdString());
        for (std::size_t f = 0; f < take.frameCount(); ++f)
            for (std::size_t k = 0; k < take.points.size(); ++k)
                if (const auto x = take.samples.position(f, k))
                    take.samples.set(f, k, x->x(), x->z(), -x->y());
        take.parameters.set("POINT", C3dParameter::chars("Y_SCREEN", {"+Y"}));
        const QString yUp = folder_ + "/demo/walker_y_up.c3d";
        writeC3d(take, yUp.toStdString());
        MainWindow window;
        window.setMessageBoxesEnabled(false);
        QVERIFY(window.openFile(folder_ + "/demo/walker.obj"));
        QVERIFY(window.openFile(yUp));
        QVERIFY(window.openFile(folder_ + "/demo/walker.map.json"));
        QVERIFY(window.meshView()->upAxis().isApprox(Eigen::Vector3d::UnitZ()));
    }

    void scrubbingShowsEachFrame() {
        TimelineWidget* widget = window_->timelineWidget();
        std::map<int, Positions> shown;
        for (int frame : {12, 40, 12}) {
            widget->slider()->setValue(frame);  // what dragging the slider does
            QCOMPARE(window_->timeline()->frame(), frame);
            QVERIFY(test::waitForFrame(*window_));
            QCOMPARE(window_->displayedFrame(), frame);
            if (shown.count(frame))
                // The second visit comes from the cache: the very same shape.
                QCOMPARE(maxDistance(shown[frame], window_->meshView()->positions()), 0.0);
            shown[frame] = window_->meshView()->positions();
        }
        QVERIFY(maxDistance(shown[12], shown[40]) > 0);
        QVERIFY(window_->frameSolver()->isCached(12));
    }

    void keyboardMovesThePlayhead() {
        Timeline* timeline = window_->timeline();
        const int last = timeline->frameCount() - 1;
        QTest::keyClick(window_.get(), Qt::Key_Right);
        QCOMPARE(timeline->frame(), 1);
        QTest::keyClick(window_.get(), Qt::Key_Right, Qt::ShiftModifier);
        QCOMPARE(timeline->frame(), 11);
        QTest::keyClick(window_.get(), Qt::Key_Left);
        QCOMPARE(timeline->frame(), 10);
        QTest::keyClick(window_.get(), Qt::Key_End);
        QCOMPARE(timeline->frame(), last);
        QTest::keyClick(window_.get(), Qt::Key_Left, Qt::ShiftModifier);
        QCOMPARE(timeline->frame(), last - 10);
        QTest::keyClick(window_.get(), Qt::Key_Home);
        QCOMPARE(timeline->frame(), 0);
        QTest::keyClick(window_.get(), Qt::Key_Space);
        QVERIFY(timeline->isPlaying());
        QTest::keyClick(window_.get(), Qt::Key_Space);
        QVERIFY(!timeline->isPlaying());
        QVERIFY(test::waitForFrame(*window_));
    }

    void playingAnimatesTheMesh() {
        Timeline* timeline = window_->timeline();
        // Every frame: playback waits for each frame to be shown, so none is skipped.
        timeline->setSpeed(Timeline::Speed::EveryFrame);
        timeline->setLoop(false);
        std::map<int, Positions> shown;
        connect(window_.get(), &MainWindow::frameDisplayed, this,
                [&](int frame) { shown[frame] = window_->meshView()->positions(); });
        timeline->play();
        QVERIFY(QTest::qWaitFor([&] { return shown.size() >= 4; }, 60000));
        timeline->pause();
        QVERIFY(shown.count(1) && shown.count(2) && shown.count(3));
        QVERIFY(maxDistance(shown[1], shown[2]) > 0);
        QVERIFY(maxDistance(shown[2], shown[3]) > 0);
        QVERIFY(test::waitForFrame(*window_));
    }

    // Every Frame waits for each frame to be shown. A take with no mesh, or with too few markers
    // mapped to solve (where a user scrubs to find frames to map on), reported no frame shown,
    // and play stood still on its first frame.
    void everyFramePlaysATakeThatIsNotSolved() {
        MainWindow window;
        window.setMessageBoxesEnabled(false);
        QVERIFY(window.openFile(folder_ + "/demo/walker.c3d"));
        Timeline* timeline = window.timeline();
        timeline->setSpeed(Timeline::Speed::EveryFrame);
        timeline->setLoop(false);
        for (const QString& mesh : {QString(), folder_ + "/demo/walker.obj"}) {
            if (!mesh.isEmpty()) QVERIFY(window.openFile(mesh));
            QVERIFY(!window.document()->canSolve());
            timeline->setFrame(0);
            timeline->play();
            QVERIFY2(QTest::qWaitFor([&] { return timeline->frame() >= 5; }, 10000),
                     qPrintable(mesh));
            timeline->pause();
        }
    }

    void corruptTakeGivesMessageAndWindowKeepsWorking() {
        window_->setMessageBoxesEnabled(true);
        QSignalSpy errors(window_.get(), &MainWindow::errorShown);
        const QString takeBefore = window_->document()->takePath();

        // The demo take cut short, and a file of garbage.
        QFile good(folder_ + "/demo/walker.c3d");
        QVERIFY(good.open(QIODevice::ReadOnly));
        const QByteArray bytes = good.readAll();
        const QString truncated = folder_ + "/truncated.c3d", garbage = folder_ + "/garbage.c3d";
        QFile cut(truncated);
        QVERIFY(cut.open(QIODevice::WriteOnly));
        cut.write(bytes.left(700));
        cut.close();
        QFile junk(garbage);
        QVERIFY(junk.open(QIODevice::WriteOnly));
        junk.write(QByteArray(5000, '\x7f'));
        junk.close();

        for (const QString& path : {truncated, garbage}) {
            const int before = errors.count();
            QVERIFY(!window_->openFile(path));
            QCOMPARE(errors.count(), before + 1);
            const QString message = errors.last().at(0).toString();
            QVERIFY2(message.contains(QFileInfo(path).fileName()), qPrintable(message));
        }
        // The message is on screen without blocking anything.
        auto* box = window_->findChild<QMessageBox*>("errorMessage");
        QVERIFY(box);
        QVERIFY(box->isVisible());
        QVERIFY(!box->isModal());

        QVERIFY(!window_->openFile(folder_ + "/no-such-file.c3d"));
        QVERIFY(!window_->openFile(project_ + ".txt"));
        for (auto* open : window_->findChildren<QMessageBox*>("errorMessage")) open->close();

        // The previous take is still there and still solves.
        QCOMPARE(window_->document()->takePath(), takeBefore);
        window_->timeline()->scrubTo(25);
        QVERIFY(test::waitForFrame(*window_));
        QCOMPARE(window_->displayedFrame(), 25);
    }

    // The frame's figures on the right cut a long status message short ("…more than 300 r"):
    // the bar's tooltip holds it whole while it is up.
    void aStatusMessageCutShortReadsWholeInTheBarsTooltip() {
        const QString message =
            "Frame 25 aligns the take much worse than the automatic choice (256.3 mm against "
            "104.6 mm). Undo (Ctrl+Z) goes back; Edit → Calibrate Automatically picks it.";
        window_->statusBar()->showMessage(message);
        QCOMPARE(window_->statusBar()->toolTip(), message);
        window_->statusBar()->clearMessage();
        QCOMPARE(window_->statusBar()->toolTip(), QString());
    }

    void droppedFilesOpen() {
        // A fresh window, then the demo's files dropped on it in the "wrong" order.
        MainWindow window;
        window.setMessageBoxesEnabled(false);
        QSignalSpy errors(&window, &MainWindow::errorShown);
        QMimeData mime;
        mime.setUrls({QUrl::fromLocalFile(folder_ + "/demo/walker.map.json"),
                      QUrl::fromLocalFile(folder_ + "/demo/walker.c3d"),
                      QUrl::fromLocalFile(folder_ + "/demo/walker.obj")});
        QDragEnterEvent enter(QPoint(20, 20), Qt::CopyAction, &mime, Qt::LeftButton, {});
        QCoreApplication::sendEvent(&window, &enter);
        QVERIFY(enter.isAccepted());
        QDropEvent drop(QPointF(20, 20), Qt::CopyAction, &mime, Qt::LeftButton, {});
        QCoreApplication::sendEvent(&window, &drop);
        QCOMPARE(errors.count(), 0);
        QVERIFY(window.document()->hasMesh());
        QVERIFY(window.document()->hasTake());
        QCOMPARE(window.document()->mappedCount(), window.document()->markerCount());
        QVERIFY(test::showAndWait(window));
        QVERIFY(window.isSolving());
    }

    void exportWritesObjSequence() {
        const QString out = folder_ + "/export";
        QDir(out).removeRecursively();
        window_->findChild<QAction*>("actionExport")->trigger();
        ExportDialog* dialog = window_->exportDialog();
        QVERIFY(dialog->isVisible());
        QSignalSpy finished(dialog, &ExportDialog::finished);
        dialog->setFolder(out);
        dialog->setFormat(ExportFormat::Obj);
        dialog->setRange(ExportDialog::Range::All);
        QVERIFY(dialog->startExport());
        QVERIFY(finished.wait(120000));
        QVERIFY2(finished.at(0).at(0).toBool(), qPrintable(finished.at(0).at(1).toString()));
        const QStringList objs = QDir(out).entryList({"*.obj"}, QDir::Files);
        QCOMPARE(objs.size(), window_->document()->frameCount());
        QVERIFY(QFileInfo::exists(out + "/walker.json"));
        // The window is still alive and solving.
        window_->timeline()->scrubTo(7);
        QVERIFY(test::waitForFrame(*window_));
    }

    void theExportDialogOffersEveryFormatAndWritesAGlb() {
        ExportDialog* dialog = window_->exportDialog();
        QCOMPARE(dialog->findChild<QComboBox*>("exportFormat")->count(),
                 int(exportFormats().size()));
        const QString out = folder_ + "/export-glb";
        QDir(out).removeRecursively();
        QSignalSpy finished(dialog, &ExportDialog::finished);
        dialog->setFolder(out);
        dialog->setFormat(ExportFormat::Glb);
        dialog->setRange(ExportDialog::Range::All);
        QVERIFY(dialog->startExport());
        QVERIFY(finished.wait(120000));
        QVERIFY2(finished.at(0).at(0).toBool(), qPrintable(finished.at(0).at(1).toString()));
        QVERIFY(QFileInfo(out + "/walker.glb").size() > 0);
        QVERIFY(QDir(out).entryList({"*.obj"}, QDir::Files).isEmpty());
    }

    // An export goes where the user's own work is, never beside the mesh, which may be a shared,
    // read-only library: beside the project, else the last folder chosen, else the documents.
    void theExportFolderIsBesideTheProjectElseTheLastChosenElseTheDocuments() {
        QSettings().setValue("export/folder", folder_ + "/chosen");
        window_->showExportDialog();
        QCOMPARE(window_->exportDialog()->folder(), folder_ + "/demo/demo_export");
        window_->exportDialog()->close();

        // What the export dialog of an untitled window offers.
        auto untitled = [this] {
            MainWindow window;
            window.setMessageBoxesEnabled(false);
            if (!window.openFiles({folder_ + "/demo/walker.obj", folder_ + "/demo/walker.c3d",
                                   folder_ + "/demo/walker.map.json"}))
                return QString("(the demo's files did not open)");
            window.showExportDialog();
            return window.exportDialog()->folder();
        };
        QCOMPARE(untitled(), folder_ + "/chosen");
        QSettings().remove("export/folder");
        QCOMPARE(untitled(),
                 QStandardPaths::writableLocation(QStandardPaths::DocumentsLocation) + "/Boneless");
    }

    void scrubLatency() {
        // Not asserted (machines differ): printed for the record.
        std::map<int, std::pair<double, bool>> latency;
        connect(window_.get(), &MainWindow::latencyMeasured, this,
                [&](int frame, double ms, bool cached) {
                    latency[frame] = {ms, cached};
                });
        window_->timeline()->scrubTo(50);
        QVERIFY(test::waitForFrame(*window_));
        window_->timeline()->scrubTo(0);
        QVERIFY(test::waitForFrame(*window_));
        QVERIFY(latency.count(50) && latency.count(0));
        QVERIFY(!latency[50].second);
        QVERIFY(latency[0].second);
        qInfo("scrub latency on the demo: uncached frame 50 %.1f ms, cached frame 0 %.1f ms",
              latency[50].first, latency[0].first);
    }

  private:
    QString folder_, project_;
    std::unique_ptr<MainWindow> window_;
};

QTEST_MAIN(MainWindowTest)
#include "MainWindowTest.moc"
