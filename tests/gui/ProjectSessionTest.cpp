// The window and its project files as a user meets them: the demo is never written over, a new
// mesh or take starts an untitled project, the frame, speed and camera come back with the
// project, a damaged or hostile project file gives one message, offers the last autosave when it
// was made from that project and is itself left alone, and closing asks before edits that no
// project file holds are left behind.
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>
#include <QFile>
#include <QFileDialog>
#include <QJsonArray>
#include <QJsonDocument>
#include <QJsonObject>
#include <QLabel>
#include <QLineEdit>
#include <QMenu>
#include <QMessageBox>
#include <QProcess>
#include <QPushButton>
#include <QSettings>
#include <QSignalSpy>
#include <QStatusBar>
#include <QUndoStack>
#include <QtTest>
#include <cstdio>

#include "../support/FileSizeLimit.h"
#include "ViewTestSupport.h"
#include "boneless/Correspondence.h"
#include "boneless/Process.h"
#include "boneless/ui/DemoProject.h"
#include "boneless/ui/Document.h"
#include "boneless/ui/FrameSolver.h"
#include "boneless/ui/MainWindow.h"
#include "boneless/ui/MeshView.h"
#include "boneless/ui/Project.h"
#include "boneless/ui/Timeline.h"

using namespace boneless::ui;

namespace {

QByteArray readAll(const QString& path) {
    QFile f(path);
    return f.open(QIODevice::ReadOnly) ? f.readAll() : QByteArray();
}

void writeAll(const QString& path, const QByteArray& bytes) {
    QFile f(path);
    QVERIFY(f.open(QIODevice::WriteOnly));
    f.write(bytes);
}

// Answers the question closing (or opening another file) asks with `button`, after `first` (e.g.
// scheduling the next dialog's answer).
void answerClose(const char* button, std::function<void()> first = {}) {
    QTimer::singleShot(300, [button, first] {
        auto* box = qobject_cast<QMessageBox*>(QApplication::activeModalWidget());
        QVERIFY(box);
        QCOMPARE(box->objectName(), QString("unsavedQuestion"));
        if (first) first();
        box->findChild<QPushButton*>(button)->click();
    });
}

// Answers the recovery question at start with `button` ("reopenButton" or "discardButton").
void answerRecovery(const char* button) {
    QTimer::singleShot(300, [button] {
        auto* box = qobject_cast<QMessageBox*>(QApplication::activeModalWidget());
        QVERIFY(box);
        QCOMPARE(box->objectName(), QString("recoveryQuestion"));
        box->findChild<QPushButton*>(button)->click();
    });
}

// Types `path` into the file dialog once it is up (it takes a moment to appear) and accepts it.
void answerFileDialog(const QString& path, int tries = 50) {
    QTimer::singleShot(100, [path, tries] {
        auto* dialog = qobject_cast<QFileDialog*>(QApplication::activeModalWidget());
        if (!dialog) {
            if (tries > 0) answerFileDialog(path, tries - 1);
            return;
        }
        // Typed, as a user would: selectFile() alone leaves a save dialog in the folder it opened.
        auto* name = dialog->findChild<QLineEdit*>("fileNameEdit");
        QVERIFY(name);
        name->setText(path);
        QMetaObject::invokeMethod(dialog, "accept");
    });
}

}  // namespace

class ProjectSessionTest : public QObject {
    Q_OBJECT
  public:
    static void initMain() { setDefaultSurfaceFormat(); }

    // Run as another Boneless beside the test's (BONELESS_TEST_ANOTHER_BONELESS=folder): opens the
    // walker from `folder`, unmaps two markers, autosaves, says "saved N" (N markers mapped) and
    // runs until it is killed.
    static int runAnotherBoneless(const QString& folder) {
        test::isolate("ProjectSessionTest");
        MainWindow window;
        window.setMessageBoxesEnabled(false);
        if (!window.openFiles({folder + "/mine/walker.obj", folder + "/mine/walker.c3d",
                               folder + "/mine/walker.map.json"}) ||
            !window.document()->clearMapping(0) || !window.document()->clearMapping(1) ||
            !window.autosave()->saveNow())
            return 1;
        std::printf("saved %d\n", window.document()->mappedCount());
        std::fflush(stdout);
        QTimer::singleShot(120000, qApp, &QCoreApplication::quit);  // if the test is gone
        return qApp->exec();
    }

  private:
    // Every recovery file, this Boneless's and any other's: a window destroyed without closing
    // (a crash here) must not leave its work to the next test.
    static void removeAutosaves() {
        QDir folder = QFileInfo(ProjectAutosave::recoveryPath()).absoluteDir();
        for (const QString& name : folder.entryList({"*.boneless"}, QDir::Files))
            QFile::remove(folder.filePath(name));
    }

    // A session that opened the walker, unmapped a marker (at `frame`, when given) and was gone
    // without closing, as in a crash: its work is in the recovery file (a load alone is no edit,
    // and is not autosaved). Returns how many markers that work maps; -1 when a step failed.
    int leaveWorkAsACrashDoes(int frame = -1) {
        MainWindow crashed;
        crashed.setMessageBoxesEnabled(false);
        if (!crashed.openFiles({folder_ + "/mine/walker.obj", folder_ + "/mine/walker.c3d",
                                folder_ + "/mine/walker.map.json"}))
            return -1;
        if (frame >= 0) crashed.timeline()->setFrame(frame);
        if (!crashed.document()->clearMapping(0) || !crashed.autosave()->saveNow()) return -1;
        return crashed.document()->mappedCount();
    }

  private slots:
    void initTestCase() {
        test::isolate("ProjectSessionTest");
        folder_ = test::freshFolder("ProjectSessionTest");
        project_ = test::writeDemoProject(folder_ + "/mine");
        QDir(DemoProject::defaultFolder()).removeRecursively();
        removeAutosaves();
    }

    // A window destroyed without closing is a crash here: its autosave must not hold the next
    // test's recovery file.
    void init() { removeAutosaves(); }

    void theDemoIsNeverWrittenAndOpensAsGenerated() {
        const QString demo = DemoProject::defaultFolder() + "/demo.boneless";
        {
            MainWindow window;
            window.setMessageBoxesEnabled(false);
            QVERIFY(window.openDemo());
            QVERIFY(window.isDemoOpen());
            QCOMPARE(window.projectPath(), demo);
            const QByteArray generated = readAll(demo);

            // Edits on the demo go to the recovery file only.
            QVERIFY(window.document()->clearMapping(0));
            QVERIFY(window.autosave()->saveNow());
            QCOMPARE(readAll(demo), generated);
            Document recovered;
            QVERIFY(Project::load(recovered, ProjectAutosave::recoveryPath()));
            QCOMPARE(recovered.mappedCount(), 38);

            // Someone else's mesh: an untitled project, still never written into the demo.
            QVERIFY(window.openFile(folder_ + "/mine/walker.obj"));
            QVERIFY(window.projectPath().isEmpty());
            QVERIFY(!window.isDemoOpen());
            QVERIFY(window.windowTitle().startsWith("untitled"));
            QVERIFY(window.openFile(folder_ + "/mine/walker.c3d"));
            QVERIFY(window.autosave()->saveNow());
            QCOMPARE(readAll(demo), generated);

            // Save on the demo asks for a new name; dismissing that dialog saves nothing.
            QVERIFY(window.openDemo());
            QVERIFY(window.document()->clearMapping(3));
            QTimer::singleShot(500, [] {
                if (QWidget* dialog = QApplication::activeModalWidget()) dialog->close();
            });
            QVERIFY(!window.saveProject());
            QVERIFY(!window.saveProjectAs(demo));
            QCOMPARE(readAll(demo), generated);
            window.close();
            QCOMPARE(readAll(demo), generated);
        }
        // Open Demo after all that: the original again, every marker mapped.
        writeAll(demo, "{\"format\": \"boneless-project\", \"version\": 1}");
        MainWindow window;
        window.setMessageBoxesEnabled(false);
        QVERIFY(window.openDemo());
        QCOMPARE(window.document()->mappedCount(), window.document()->markerCount());
        QVERIFY(window.document()->hasMesh() && window.document()->hasTake());
    }

    void theProjectKeepsFrameSpeedAndCamera() {
        const QString path = folder_ + "/session.boneless";
        QVariantMap camera;
        {
            MainWindow window;
            window.setMessageBoxesEnabled(false);
            QVERIFY(window.openProject(project_));
            QVERIFY(test::showAndWait(window));
            window.timeline()->scrubTo(17);
            window.timeline()->setSpeed(Timeline::Speed::Half);
            QVariantMap moved = window.meshView()->cameraState();
            QVariantList position = moved["position"].toList();
            position[0] = position[0].toDouble() + 0.3;
            moved["position"] = position;
            QVERIFY(window.meshView()->setCameraState(moved));
            camera = window.meshView()->cameraState();
            QVERIFY(window.saveProjectAs(path));
        }
        MainWindow window;
        window.setMessageBoxesEnabled(false);
        QVERIFY(window.openProject(path));
        QVERIFY(test::showAndWait(window));
        QCOMPARE(window.timeline()->frame(), 17);
        QCOMPARE(window.displayedFrame(), 17);
        QCOMPARE(window.timeline()->speed(), Timeline::Speed::Half);
        const QVariantMap restored = window.meshView()->cameraState();
        for (const char* key : {"position", "focal_point"})
            for (int k = 0; k < 3; ++k)
                QVERIFY(qAbs(restored[key].toList()[k].toDouble() -
                             camera[key].toList()[k].toDouble()) < 1e-6);
    }

    // With the project changed on disk, turning the heat map on (no edit, no `*`) asked about
    // the file on disk as an edit would: the toggle autosaved. It is kept as the frame is, when
    // the project is left.
    void aViewToggleIsNoEditAndIsKeptWhenTheProjectIsLeft() {
        const QString project = test::writeDemoProject(folder_ + "/toggle");
        const QByteArray opened = readAll(project);
        {
            MainWindow window;
            window.setMessageBoxesEnabled(false);
            QVERIFY(window.openProject(project));
            QSignalSpy errors(&window, &MainWindow::errorShown);
            writeAll(project, opened + "\n");  // another program wrote it
            QAction* heatMap = nullptr;
            for (QAction* action : window.findChildren<QAction*>())
                if (action->text() == "Shape Error &Heat Map") heatMap = action;
            QVERIFY(heatMap);
            heatMap->setChecked(true);
            QVERIFY(!window.autosave()->isPending());
            QVERIFY(window.autosave()->saveNow());
            QVERIFY(!window.isWindowModified());
            QCOMPARE(errors.count(), 0);
            writeAll(project, opened);  // as it was: leaving it may write it
            QVERIFY(window.close());
        }
        Document left;
        QVERIFY(Project::load(left, project));
        QCOMPARE(left.viewSettings().value("heatMap").toBool(), true);
    }

    // Opening another project left this one's frame, speed and camera unsaved, and the next
    // project (the demo, a file without them) started from them, still playing.
    void aProjectLeftForAnotherKeepsItsViewAndTheNextStartsFromItsOwn() {
        const QString first = test::writeDemoProject(folder_ + "/left");
        const QString second = test::writeDemoProject(folder_ + "/next");
        MainWindow window;
        window.setMessageBoxesEnabled(false);
        Timeline* timeline = window.timeline();
        QVERIFY(window.openProject(first));
        QVERIFY(test::showAndWait(window));
        timeline->scrubTo(23);
        timeline->setSpeed(Timeline::Speed::Half);
        QVERIFY(window.openProject(second));
        Document left;
        QVERIFY(Project::load(left, first));
        QCOMPARE(left.viewSettings().value("frame").toInt(), 23);
        QCOMPARE(left.viewSettings().value("speed").toString(), QString("half"));
        QCOMPARE(timeline->frame(), 0);
        QCOMPARE(timeline->speed(), Timeline::Speed::Realtime);

        timeline->play();
        QVERIFY(window.openProject(first));
        QVERIFY(!timeline->isPlaying());
        QCOMPARE(timeline->frame(), 23);
        QCOMPARE(timeline->speed(), Timeline::Speed::Half);
        QVERIFY(window.openDemo());
        QCOMPARE(timeline->frame(), 0);
        QCOMPARE(timeline->speed(), Timeline::Speed::Realtime);
    }

    void aDamagedProjectGivesAMessageAndIsLeftAlone() {
        const QByteArray good = readAll(project_);
        QByteArray huge = good, wrongType = good, badAlignment = good;
        huge.replace("\"marker_weight\": 100", "\"marker_weight\": 1e308");
        QVERIFY(huge != good);
        wrongType.replace("\"max_iterations\": 10", "\"max_iterations\": \"many\"");
        QVERIFY(wrongType != good);
        badAlignment.replace("\"alignment\": null",
                             "\"alignment\": {\"scale\": 1e300, \"rotation\": [[1,0,0],[0,1,0],"
                             "[0,0,1]], \"translation\": [0,0,0]}");
        QVERIFY(badAlignment != good);
        const std::pair<const char*, QByteArray> cases[] = {
            {"truncated", good.left(good.size() / 2)},
            {"garbage", QByteArray(4096, '\xfe')},
            {"empty", QByteArray()},
            {"huge-number", huge},
            {"wrong-type", wrongType},
            {"array", "[1, 2, 3]"},
            {"deep", QByteArray(100000, '[')},
            {"huge-version", "{\"format\": \"boneless-project\", \"version\": 1e300}"},
            {"bad-alignment", badAlignment}};

        MainWindow window;
        QVERIFY(window.openProject(project_));
        QVERIFY(test::showAndWait(window));
        window.autosave()->setDelay(10);
        QVERIFY(window.document()->clearMapping(2));
        QVERIFY(window.autosave()->saveNow());  // the last good autosave
        const int mapped = window.document()->mappedCount();
        QSignalSpy errors(&window, &MainWindow::errorShown);

        for (const auto& [name, bytes] : cases) {
            // Beside the project, so that its relative paths resolve and only the damage can fail
            // it.
            const QString path = folder_ + "/mine/" + name + ".boneless";
            writeAll(path, bytes);
            QVERIFY2(!window.openProject(path), name);
            QVERIFY2(errors.last().at(0).toString().startsWith(name + QString(".boneless")),
                     qPrintable(errors.last().at(0).toString()));
            auto* box = window.findChild<QMessageBox*>("projectErrorMessage");
            QVERIFY(box && box->isVisible());
            QVERIFY(!box->detailedText().isEmpty());
            // The last autosave is the window's own project's: opened, it would pass for this one.
            QVERIFY(!box->findChild<QPushButton*>("openRecoveryButton"));
            // The window keeps its project, which stays the one autosaved; the bad file stays.
            QVERIFY2(window.projectPath() == project_, name);
            QCOMPARE(window.document()->mappedCount(), mapped);
            QVERIFY(window.document()->clearMapping(5));
            window.document()->undoStack()->undo();
            QTest::qWait(50);
            QCOMPARE(readAll(path), bytes);
            // What is wrong, not only that something is.
            if (QByteArray(name) == "bad-alignment")
                QVERIFY2(errors.last().at(0).toString().contains("the alignment's scale"),
                         qPrintable(errors.last().at(0).toString()));
            box->close();
            QTest::qWait(0);
        }
        QCOMPARE(readAll(project_).size() > 0, true);
    }

    // A project damaged after its last autosave (a failing disk, a bad copy) is offered that
    // autosave, and taking it opens the edits untitled.
    void aDamagedProjectOffersTheLastAutosaveMadeFromIt() {
        const QString path = folder_ + "/mine/own.boneless";
        QFile::remove(path);
        QVERIFY(QFile::copy(project_, path));
        int mapped = 0;
        {
            MainWindow window;
            window.setMessageBoxesEnabled(false);
            QVERIFY(window.openProject(path));
            Document* document = window.document();
            int marker = 0;
            while (document->mappedVertex(marker) < 0) ++marker;  // an earlier test cleared some
            QVERIFY(document->clearMapping(marker));
            QVERIFY(window.autosave()->saveNow());
            mapped = window.document()->mappedCount();
        }
        const QByteArray good = readAll(path);
        writeAll(path, good.left(good.size() / 2));

        MainWindow window;
        QVERIFY(!window.openProject(path));
        auto* box = window.findChild<QMessageBox*>("projectErrorMessage");
        QVERIFY(box && box->isVisible());
        auto* open = box->findChild<QPushButton*>("openRecoveryButton");
        QVERIFY(open);
        open->click();
        QVERIFY(window.projectPath().isEmpty());
        QCOMPARE(window.document()->mappedCount(), mapped);
        QVERIFY(test::showAndWait(window));
    }

    // The document's own report of why a project did not open is the project message's details:
    // said twice, the user gets two boxes for one failure.
    void aProjectThatDoesNotOpenGivesOneMessage() {
        QJsonObject root = QJsonDocument::fromJson(readAll(project_)).object();
        QJsonObject correspondence = root["correspondence"].toObject();
        QJsonObject map = correspondence["map"].toObject();
        QJsonArray markers = map["markers"].toArray();
        QJsonObject first = markers[0].toObject();
        first["vertex"] = 999999;
        markers[0] = first;
        map["markers"] = markers;
        correspondence["map"] = map;
        root["correspondence"] = correspondence;
        const QString path = folder_ + "/mine/far-vertex.boneless";
        writeAll(path, QJsonDocument(root).toJson());

        MainWindow window;
        window.setMessageBoxesEnabled(false);
        QSignalSpy errors(&window, &MainWindow::errorShown);
        QVERIFY(!window.openFiles({path}));  // as the command line opens it
        QCOMPARE(errors.size(), 1);
        const QString said = errors.last().at(0).toString();
        QVERIFY2(said.startsWith("The map in far-vertex.boneless points past "), qPrintable(said));
        QVERIFY2(said.contains("999999"), qPrintable(said));
        QVERIFY(!window.openProject(path));
        QCOMPARE(errors.size(), 2);
    }

    // A project whose mesh or take was moved says which file is missing, not only that the
    // project would not open.
    void aProjectWhoseMeshOrTakeIsMissingNamesIt() {
        const QString moved = folder_ + "/moved";
        QDir(moved).removeRecursively();
        QVERIFY(QDir().mkpath(moved));
        const QString lost = moved + "/lost.boneless";
        QVERIFY(QFile::copy(project_, lost));
        MainWindow window;
        QSignalSpy errors(&window, &MainWindow::errorShown);
        QVERIFY(!window.openProject(lost));
        QString said = errors.last().at(0).toString();
        QVERIFY2(
            said.startsWith(
                QString("The mesh %1/walker.obj named by lost.boneless is missing.").arg(moved)),
            qPrintable(said));
        auto* box = window.findChild<QMessageBox*>("projectErrorMessage");
        QVERIFY(box && box->isVisible());
        QVERIFY2(box->text().contains(moved + "/walker.obj"), qPrintable(box->text()));
        box->close();

        QVERIFY(QFile::copy(folder_ + "/mine/walker.obj", moved + "/walker.obj"));
        QVERIFY(!window.openProject(lost));
        said = errors.last().at(0).toString();
        QVERIFY2(
            said.startsWith(
                QString("The take %1/walker.c3d named by lost.boneless is missing.").arg(moved)),
            qPrintable(said));
    }

    // A folder or a FIFO named as a project is refused as the core's loaders refuse them, by
    // name: the project was read with QFile, which gave Qt's words for a folder ("file to open
    // is a directory") and for a FIFO waited for a writer for ever (`--project` hung). The
    // command line's files said that either "does not exist".
    void aFolderOrAFifoGivenAsAProjectIsRefusedByName() {
        const QString folder = folder_ + "/folder.boneless", fifo = folder_ + "/fifo.boneless",
                      fifoTake = folder_ + "/fifo.c3d";
        QDir(folder).removeRecursively();
        QVERIFY(QDir().mkpath(folder));
        for (const QString& path : {fifo, fifoTake}) {
            QFile::remove(path);
            QCOMPARE(::mkfifo(qPrintable(path), 0600), 0);
        }
        Document document;
        QString error;
        QVERIFY(!Project::load(document, folder, &error));
        QCOMPARE(error, folder + ": is a directory, not a Boneless project file");

        MainWindow window;
        window.setMessageBoxesEnabled(false);
        QSignalSpy errors(&window, &MainWindow::errorShown);
        auto said = [&] { return errors.last().at(0).toString(); };
        QVERIFY(!window.openProject(folder));  // as --project opens it
        QVERIFY2(said().startsWith("folder.boneless is a directory, not a Boneless project file."),
                 qPrintable(said()));
        QVERIFY(!window.openFiles({folder}));  // as the command line's files open
        QVERIFY2(said().startsWith("folder.boneless is a directory, not a Boneless project file."),
                 qPrintable(said()));

        QVERIFY(!Project::load(document, fifo, &error));
        QCOMPARE(error, fifo + ": is not a regular file");
        QVERIFY(!window.openProject(fifo));
        QVERIFY2(said().startsWith("fifo.boneless is not a regular file."), qPrintable(said()));
        QVERIFY(!window.openFiles({fifo}));
        QVERIFY2(said().startsWith("fifo.boneless is not a regular file."), qPrintable(said()));
        // A take's message reads its first bytes: not a FIFO's.
        QVERIFY(!window.openFiles({fifoTake}));
        QVERIFY2(said().startsWith("fifo.c3d is not a regular file."), qPrintable(said()));
        QVERIFY(!window.document()->hasMesh());
    }

    // A take cut short opens with what the reader let through, where the user sees it, and a
    // calibration frame past its end goes back to automatic instead of failing every frame.
    void aTakeCutShortOpensWithItsNotesAndDropsACalibrationFrameItLacks() {
        MainWindow window;
        window.setMessageBoxesEnabled(false);
        QVERIFY(window.openFile(folder_ + "/mine/walker.obj"));
        QVERIFY(window.openFile(folder_ + "/mine/walker.c3d"));
        QVERIFY(window.openFile(folder_ + "/mine/walker.map.json"));
        Document* d = window.document();
        QVERIFY(d->takeNotes().isEmpty());
        const int frames = d->frameCount();
        boneless::TakeSolveOptions settings = d->settings();
        settings.calibrationFrame = frames - 1;
        d->setSettings(settings);
        QFile whole(folder_ + "/mine/walker.c3d");
        QVERIFY(whole.open(QIODevice::ReadOnly));
        const QByteArray bytes = whole.readAll();
        QFile cut(folder_ + "/cut.c3d");
        QVERIFY(cut.open(QIODevice::WriteOnly));
        cut.write(bytes.left(bytes.size() * 6 / 10));
        cut.close();

        QVERIFY(window.openFile(cut.fileName()));
        QVERIFY(d->frameCount() < frames);
        const QStringList notes = d->takeNotes();
        QCOMPARE(notes.size(), 2);
        QVERIFY2(notes[0].contains("truncated"), qPrintable(notes[0]));
        QVERIFY2(notes[1].contains("calibrated automatically"), qPrintable(notes[1]));
        QCOMPARE(d->settings().calibrationFrame, -1);
        QVERIFY2(window.statusBar()->currentMessage().contains("with 2 notes"),
                 qPrintable(window.statusBar()->currentMessage()));
        QVERIFY(test::showAndWait(window));
        QVERIFY(test::waitForFrame(window));
        QVERIFY2(window.frameSummary().contains("solved"), qPrintable(window.frameSummary()));
    }

    // The title marks edits that no project file holds (Qt's [*]): an untitled or demo
    // session's until Save As, a project's until the autosave has written them. It marked none.
    void theTitleMarksEditsThatNoProjectFileHolds() {
        MainWindow window;
        window.setMessageBoxesEnabled(false);
        window.autosave()->setDelay(60000);  // saved when the test says
        QVERIFY(window.openFiles({folder_ + "/mine/walker.obj", folder_ + "/mine/walker.c3d",
                                  folder_ + "/mine/walker.map.json"}));
        QCOMPARE(window.windowTitle(), QString("untitled[*] — walker.obj — Boneless"));
        QVERIFY(!window.isWindowModified());  // opening files is no edit
        QVERIFY(window.document()->clearMapping(0));
        QVERIFY(window.isWindowModified());
        (void)window.autosave()->saveNow();  // the recovery file is no project file
        QVERIFY(window.isWindowModified());
        QVERIFY(window.saveProjectAs(folder_ + "/marked.boneless"));
        QVERIFY(!window.isWindowModified());

        QVERIFY(window.document()->clearMapping(1));
        QVERIFY(window.isWindowModified());
        QVERIFY(window.autosave()->saveNow());
        QVERIFY(!window.isWindowModified());
        // Undo goes past what the file holds, redo back to it.
        QUndoStack* undo = window.document()->undoStack();
        undo->undo();
        QVERIFY(window.isWindowModified());
        undo->redo();
        QVERIFY(!window.isWindowModified());

        QVERIFY(window.openDemo());
        QVERIFY(!window.isWindowModified());
        QVERIFY(window.document()->clearMapping(2));
        (void)window.autosave()->saveNow();
        QVERIFY(window.isWindowModified());
        // Undone back to the demo as opened, there is nothing to keep (Ctrl+Q asked to save it).
        undo->undo();
        QVERIFY(!window.isWindowModified());
        window.autosave()->discardPending();
    }

    // Opening the map is an undo step ("Open Correspondence"): the files as opened were past the
    // stack's clean state, so undoing an edit back to them still counted as an edit.
    void undoingBackToTheFilesAsOpenedIsNoEdit() {
        MainWindow window;
        window.setMessageBoxesEnabled(false);
        window.autosave()->setDelay(60000);  // saved when the test says
        const QString map = folder_ + "/mine/walker.map.json";
        QVERIFY(
            window.openFiles({folder_ + "/mine/walker.obj", folder_ + "/mine/walker.c3d", map}));
        Document* d = window.document();
        const int all = d->mappedCount();
        QVERIFY(!window.isWindowModified());
        QVERIFY(d->clearMapping(0));
        QVERIFY(window.isWindowModified());
        d->undoStack()->undo();
        QCOMPARE(d->mappedCount(), all);
        QVERIFY(!window.isWindowModified());

        // A map opened over hand edits is still undone back to them, which are still edits.
        QVERIFY(d->clearMapping(0));
        QVERIFY(window.openFile(map));  // without message boxes: Replace
        QCOMPARE(d->mappedCount(), all);
        QVERIFY(window.isWindowModified());
        QCOMPARE(d->undoStack()->undoText(), QString("Open Correspondence"));
        d->undoStack()->undo();
        QCOMPARE(d->mappedCount(), all - 1);
        QVERIFY(window.isWindowModified());
        d->undoStack()->undo();
        QCOMPARE(d->mappedCount(), all);
        QVERIFY(!window.isWindowModified());
        window.autosave()->discardPending();
    }

    // "The take …/walker.c3d named by walk.boneless is missing." and nothing opened: the map
    // kept only in the project was out of reach but by editing its JSON. Locate… asks where the
    // file is now and opens the project with it, as an edit that the project saves.
    void aProjectWhoseTakeWasRenamedOpensOnceTheTakeIsLocated() {
        const QString project = test::writeDemoProject(folder_ + "/renamed");
        const QString take = folder_ + "/renamed/walker.c3d";
        const QString renamed = folder_ + "/renamed/walker-take2.c3d";
        QVERIFY(QFile::rename(take, renamed));
        MainWindow window;
        window.autosave()->setDelay(60000);  // saved when the test says
        QVERIFY(!window.openProject(project));
        auto* box = window.findChild<QMessageBox*>("projectErrorMessage");
        QVERIFY(box);
        QVERIFY2(box->text().contains(take), qPrintable(box->text()));
        auto* locate = box->findChild<QPushButton*>("locateButton");
        QVERIFY(locate);
        bool asked = false;
        QTimer::singleShot(0, [&] {
            QVERIFY(QTest::qWaitFor(
                [] { return qobject_cast<QFileDialog*>(QApplication::activeModalWidget()); },
                5000));
            auto* dialog = qobject_cast<QFileDialog*>(QApplication::activeModalWidget());
            QCOMPARE(dialog->objectName(), QString("locateDialog"));
            asked = true;
            dialog->selectFile(renamed);
            QMetaObject::invokeMethod(dialog, "accept");
        });
        locate->click();
        QVERIFY(asked);
        QCOMPARE(window.projectPath(), QFileInfo(project).absoluteFilePath());
        QCOMPARE(window.document()->takePath(), renamed);
        QVERIFY(window.document()->mappedCount() > 0);
        QVERIFY(window.isWindowModified());
        QVERIFY(window.autosave()->isPending());
        QVERIFY(window.autosave()->saveNow());
        const QJsonObject saved = QJsonDocument::fromJson(readAll(project)).object();
        QCOMPARE(saved["take"].toObject()["file"].toString(), QString("walker-take2.c3d"));
        for (auto* shown : window.findChildren<QMessageBox*>()) shown->close();
    }

    // A mesh re-exported with other vertices: "p1.boneless could not be opened as a Boneless
    // project.", the cause under Show Details and nothing offered. The message names the map
    // and the mesh, and Locate… opens the project with the mesh the map was made for.
    void aProjectWhoseMeshNoLongerFitsItsMapSaysSoAndTheMeshCanBeLocated() {
        const QString project = test::writeDemoProject(folder_ + "/reexported");
        const QString mesh = folder_ + "/reexported/walker.obj";
        const QString old = folder_ + "/reexported/walker-old.obj";
        QVERIFY(QFile::rename(mesh, old));
        writeAll(mesh, "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n");
        MainWindow window;
        window.autosave()->setDelay(60000);
        QVERIFY(!window.openProject(project));
        auto* box = window.findChild<QMessageBox*>("projectErrorMessage");
        QVERIFY(box);
        QCOMPARE(box->text(), "The map in demo.boneless was made for another mesh than " + mesh +
                                  ", which has 4 vertices now.");
        QVERIFY2(box->detailedText().contains("has 4"), qPrintable(box->detailedText()));
        auto* locate = box->findChild<QPushButton*>("locateButton");
        QVERIFY(locate);
        QTimer::singleShot(0, [&] {
            QVERIFY(QTest::qWaitFor(
                [] { return qobject_cast<QFileDialog*>(QApplication::activeModalWidget()); },
                5000));
            auto* dialog = qobject_cast<QFileDialog*>(QApplication::activeModalWidget());
            dialog->selectFile(old);
            QMetaObject::invokeMethod(dialog, "accept");
        });
        locate->click();
        QCOMPARE(window.projectPath(), QFileInfo(project).absoluteFilePath());
        QCOMPARE(window.document()->meshPath(), old);
        QVERIFY(window.document()->mappedCount() > 0);
        QVERIFY(window.autosave()->saveNow());
        const QJsonObject saved = QJsonDocument::fromJson(readAll(project)).object();
        QCOMPARE(saved["mesh"].toObject()["file"].toString(), QString("walker-old.obj"));
        for (auto* shown : window.findChildren<QMessageBox*>()) shown->close();
    }

    // A map made for another mesh could only be located with that mesh: the project could not
    // be opened to map the mesh it names anew. Open Without the Map opens it unmapped, says so,
    // and keeps the map (only the project held it) in a file beside it; the project is untouched.
    void aProjectWhoseMapDoesNotFitItsMeshOpensWithTheMapSetAside() {
        const QString project = test::writeDemoProject(folder_ + "/setAside");
        const QString mesh = folder_ + "/setAside/walker.obj";
        const int mapped =
            boneless::Correspondence::read((folder_ + "/setAside/walker.map.json").toStdString())
                .markers.size();
        QVERIFY(QFile::remove(mesh));
        writeAll(mesh, "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n");
        const QByteArray before = readAll(project);
        MainWindow window;
        window.autosave()->setDelay(60000);
        QVERIFY(!window.openProject(project));
        auto* box = window.findChild<QMessageBox*>("projectErrorMessage");
        QVERIFY(box);
        QVERIFY2(box->informativeText().contains("Open Without the Map opens it unmapped"),
                 qPrintable(box->informativeText()));
        auto* aside = box->findChild<QPushButton*>("openWithoutMapButton");
        QVERIFY(aside);
        aside->click();
        QCOMPARE(window.projectPath(), QFileInfo(project).absoluteFilePath());
        QCOMPARE(window.document()->meshPath(), mesh);
        QVERIFY(window.document()->hasTake());
        QCOMPARE(window.document()->mappedCount(), 0);
        const QString kept = folder_ + "/setAside/demo.set-aside.map.json";
        const QString said = window.statusBar()->currentMessage();
        QVERIFY2(said.contains("made for another mesh") && said.contains(kept), qPrintable(said));
        QCOMPARE(readAll(project), before);
        const boneless::Correspondence map = boneless::Correspondence::read(kept.toStdString());
        QCOMPARE(int(map.markers.size()), mapped);
        for (auto* shown : window.findChildren<QMessageBox*>()) shown->close();
    }

    // A map file with no vertex count whose entry points past the mesh: "demo.boneless could not
    // be opened as a Boneless project." The headline names the map, the entry and the mesh.
    void aMapPointingPastTheMeshIsNamedWithItsEntryAndTheMeshsVertexCount() {
        const QString project = test::writeDemoProject(folder_ + "/pastMesh");
        const QString mesh = folder_ + "/pastMesh/walker.obj";
        boneless::Correspondence map =
            boneless::Correspondence::read((folder_ + "/pastMesh/walker.map.json").toStdString());
        map.meshVertices = 0;
        map.markers[5].vertex = 4000;
        map.markers[9].vertex = 4100;
        map.write((folder_ + "/pastMesh/past.map.json").toStdString());
        QJsonObject root = QJsonDocument::fromJson(readAll(project)).object();
        root["correspondence"] = QJsonObject{{"file", "past.map.json"}, {"modified", false}};
        writeAll(project, QJsonDocument(root).toJson());
        MainWindow window;
        window.autosave()->setDelay(60000);
        QVERIFY(!window.openProject(project));
        auto* box = window.findChild<QMessageBox*>("projectErrorMessage");
        QVERIFY(box);
        Document d;
        QVERIFY(Project::load(d, test::writeDemoProject(folder_ + "/pastMeshCount")));
        QCOMPARE(box->text(),
                 QString("The map past.map.json named by demo.boneless points past %1: "
                         "marker %2 is on vertex 4000, and it has %3 vertices.")
                     .arg(mesh, QString::fromStdString(map.markers[5].label))
                     .arg(d.mesh().vertexCount()));
        QVERIFY(box->findChild<QPushButton*>("openWithoutMapButton"));
        for (auto* shown : window.findChildren<QMessageBox*>()) shown->close();
    }

    // A map opened into a saved project went in as a load: the title was not marked and its
    // autosave was dropped, so closing without another change left the project with its old map,
    // unasked. It is an edit like any other: marked, autosaved into the project.
    void aMapOpenedIntoASavedProjectIsSavedWithIt() {
        const QString project = test::writeDemoProject(folder_ + "/mapInto");
        const QString other = folder_ + "/mapInto/fewer.map.json";
        boneless::Correspondence fewer =
            boneless::Correspondence::read((folder_ + "/mapInto/walker.map.json").toStdString());
        const int all = int(fewer.markers.size());
        fewer.markers.pop_back();
        fewer.write(other.toStdString());
        {
            MainWindow window;
            window.setMessageBoxesEnabled(false);
            window.autosave()->setDelay(60000);  // saved when the test says
            QVERIFY(window.openProject(project));
            QCOMPARE(window.document()->mappedCount(), all);
            QVERIFY(!window.isWindowModified());
            QVERIFY(window.openFile(other));  // without message boxes: Replace
            QCOMPARE(window.document()->mappedCount(), all - 1);
            QVERIFY(window.isWindowModified());
            QVERIFY(window.autosave()->isPending());
            QVERIFY(window.autosave()->saveNow());
            QVERIFY(!window.isWindowModified());
        }
        MainWindow again;
        again.setMessageBoxesEnabled(false);
        QVERIFY(again.openProject(project));
        QCOMPARE(again.document()->mappedCount(), all - 1);
    }

    void closingAsksBeforeUntitledEditsAreLeftToTheAutosave() {
        MainWindow window;
        QVERIFY(window.openFile(folder_ + "/mine/walker.obj"));
        QVERIFY(window.openFile(folder_ + "/mine/walker.c3d"));
        QVERIFY(window.openFile(folder_ + "/mine/walker.map.json"));
        QVERIFY(test::showAndWait(window));
        window.close();  // files opened, nothing edited: no question
        QVERIFY(!window.isVisible());

        window.show();
        QVERIFY(window.document()->clearMapping(0));
        answerClose("cancelButton");
        window.close();
        QVERIFY(window.isVisible());
        // Opening another take asks too; cancelled, the edit stays.
        answerClose("cancelButton");
        QVERIFY(!window.openFile(folder_ + "/mine/walker.c3d"));
        QCOMPARE(window.document()->mappedCount(), window.document()->markerCount() - 1);
        // A take and a mesh opened together (dropped, or named on the command line): one
        // question for both, and the mesh first.
        int asked = 0;
        QTimer answering;
        connect(&answering, &QTimer::timeout, [&asked] {
            if (auto* box = qobject_cast<QMessageBox*>(QApplication::activeModalWidget())) {
                ++asked;
                box->findChild<QPushButton*>("discardButton")->click();
            }
        });
        answering.start(100);
        QVERIFY(window.openFiles({folder_ + "/mine/walker.c3d", folder_ + "/mine/walker.obj"}));
        answering.stop();
        QCOMPARE(asked, 1);
        QVERIFY(window.document()->hasMesh() && window.document()->hasTake());
        // Going on dropped the edit: closing has nothing to ask.
        QCOMPARE(window.document()->mappedCount(), window.document()->markerCount());
        window.close();
        QVERIFY(!window.isVisible());

        // Close Without Saving closes.
        window.show();
        QVERIFY(window.document()->clearMapping(0));
        answerClose("discardButton");
        window.close();
        QVERIFY(!window.isVisible());

        // Save As names a project, and the edits are in it.
        window.show();
        const QString path = folder_ + "/kept.boneless";
        answerClose("saveAsButton", [path] { answerFileDialog(path); });
        window.close();
        QVERIFY(!window.isVisible());
        QCOMPARE(window.projectPath(), path);
        Document kept;
        QVERIFY(Project::load(kept, path));
        QCOMPARE(kept.mappedCount(), window.document()->markerCount() - 1);
    }

    // "Open Without Saving" kept the edited map with the take opened, and closing asked again
    // about the edits it had said would not be saved. Going on drops them, for a take as for a
    // mesh: the map is back as it was opened, and there is nothing left to ask about.
    void openingATakeOrMeshWithoutSavingDropsTheEdits() {
        {
            MainWindow window;
            QVERIFY(window.openFiles({folder_ + "/mine/walker.obj", folder_ + "/mine/walker.c3d",
                                      folder_ + "/mine/walker.map.json"}));
            QVERIFY(test::showAndWait(window));
            Document* d = window.document();
            const int all = d->mappedCount();
            for (const char* file : {"walker.c3d", "walker.obj"}) {
                QVERIFY(d->clearMapping(0));
                QVERIFY(d->clearMapping(1));
                QVERIFY(window.isWindowModified());
                answerClose("discardButton");
                QVERIFY(window.openFile(folder_ + "/mine/" + file));
                QCOMPARE(d->mappedCount(), all);
                QVERIFY(!window.isWindowModified());
            }
            window.close();  // no question: nothing is left unsaved
            QVERIFY(!window.isVisible());
        }
        // Work reopened from an autosave is all unsaved: none of its map goes on.
        QVERIFY(leaveWorkAsACrashDoes() >= 0);
        MainWindow window;
        QVERIFY(window.openRecovery());
        QVERIFY(window.document()->mappedCount() > 0);
        QVERIFY(window.isWindowModified());
        answerClose("discardButton");
        QVERIFY(window.openFile(folder_ + "/mine/walker.c3d"));
        QCOMPARE(window.document()->mappedCount(), 0);
        QVERIFY(!window.isWindowModified());
    }

    void afterACrashTheLastAutosaveOpensFromTheRecentFilesMenu() {
        QFile::remove(ProjectAutosave::recoveryPath());
        const int mapped = leaveWorkAsACrashDoes();
        QVERIFY(mapped >= 0);
        MainWindow window;
        window.setMessageBoxesEnabled(false);
        QVERIFY(window.openDemo());
        auto* menu = window.findChild<QMenu*>("recentMenu");
        QVERIFY(menu);
        emit menu->aboutToShow();
        auto* last = menu->findChild<QAction*>("openLastAutosave");
        QVERIFY(last && last->isEnabled());
        last->trigger();
        QVERIFY(window.projectPath().isEmpty());
        QVERIFY(!window.isDemoOpen());
        QCOMPARE(window.document()->mappedCount(), mapped);
    }

    // Two p1.boneless of different folders read alike in Recent Files, and the tooltip with
    // the path never showed. A name two entries share also names its folder; tooltips show.
    void recentFilesOfOneNameInDifferentFoldersCanBeToldApart() {
        const QString a = folder_ + "/recentA/proj", b = folder_ + "/recentB/proj";
        QVERIFY(QDir().mkpath(a) && QDir().mkpath(b));
        for (const QString& path : {a + "/p1.boneless", b + "/p1.boneless", a + "/p2.boneless"}) {
            QFile file(path);
            QVERIFY(file.open(QIODevice::WriteOnly));
        }
        RecentFiles::clear();
        RecentFiles::add(a + "/p1.boneless");
        RecentFiles::add(a + "/p2.boneless");
        RecentFiles::add(b + "/p1.boneless");
        MainWindow window;
        window.setMessageBoxesEnabled(false);
        auto* menu = window.findChild<QMenu*>("recentMenu");
        QVERIFY(menu);
        emit menu->aboutToShow();
        QVERIFY(menu->toolTipsVisible());
        QStringList texts, tips;
        for (QAction* action : menu->actions().mid(0, 3)) {
            texts << action->text();
            tips << action->toolTip();
        }
        QCOMPARE(texts, (QStringList{"p1.boneless — " + QDir::toNativeSeparators(b), "p2.boneless",
                                     "p1.boneless — " + QDir::toNativeSeparators(a)}));
        QCOMPARE(tips[1], QDir::toNativeSeparators(a + "/p2.boneless"));
        RecentFiles::clear();
    }

    // "walk & run.boneless" read "walk  run.boneless" in Recent Files with the space after it
    // underlined: the & became the entry's Alt key. Names (and the folders two share) are
    // escaped, so they read as they are and give no Alt key.
    void aRecentFileNamedWithAnAmpersandReadsAsItIsNamed() {
        const QString a = folder_ + "/R&D one", b = folder_ + "/R&D two";
        QVERIFY(QDir().mkpath(a) && QDir().mkpath(b));
        const QStringList paths{a + "/walk & run.boneless", b + "/walk & run.boneless",
                                a + "/Q&A.boneless"};
        for (const QString& path : paths) {
            QFile file(path);
            QVERIFY(file.open(QIODevice::WriteOnly));
        }
        RecentFiles::clear();
        for (const QString& path : paths) RecentFiles::add(path);
        MainWindow window;
        window.setMessageBoxesEnabled(false);
        auto* menu = window.findChild<QMenu*>("recentMenu");
        QVERIFY(menu);
        emit menu->aboutToShow();
        QStringList shown;
        for (QAction* action : menu->actions().mid(0, 3)) {
            shown << action->iconText();  // the text as the menu draws it, mnemonics taken out
            QVERIFY2(QKeySequence::mnemonic(action->text()).isEmpty(), qPrintable(action->text()));
        }
        QCOMPARE(shown, (QStringList{"Q&A.boneless",
                                     "walk & run.boneless — " + QDir::toNativeSeparators(b),
                                     "walk & run.boneless — " + QDir::toNativeSeparators(a)}));
        RecentFiles::clear();
    }

    // kill -9 after untitled edits, then `boneless` with no file: the demo's edits leave that
    // work alone, and the next start asks to reopen it, once.
    void workLeftByACrashIsOfferedAtStartAndNotOverwrittenByTheDemo() {
        QFile::remove(ProjectAutosave::recoveryPath());
        const int mapped = leaveWorkAsACrashDoes();
        QVERIFY(mapped >= 0);
        const QByteArray crashed = readAll(ProjectAutosave::recoveryPath());
        QVERIFY(!crashed.isEmpty());
        {
            MainWindow demo;
            demo.setMessageBoxesEnabled(false);
            QVERIFY(!demo.offerRecovery());  // batch use asks nothing and keeps it
            QVERIFY(demo.openDemo());
            QVERIFY(demo.document()->clearMapping(5));
            (void)demo.autosave()->saveNow();
            QCOMPARE(readAll(ProjectAutosave::recoveryPath()), crashed);
        }
        MainWindow window;
        answerRecovery("reopenButton");
        QVERIFY(window.offerRecovery());
        QVERIFY(window.projectPath().isEmpty());
        QCOMPARE(window.document()->mappedCount(), mapped);
        // The work is the autosave's alone: an edit undone leaves it so.
        QVERIFY(window.isWindowModified());
        int mappedMarker = 0;
        while (window.document()->mappedVertex(mappedMarker) < 0) ++mappedMarker;
        QVERIFY(window.document()->clearMapping(mappedMarker));
        window.document()->undoStack()->undo();
        QVERIFY(window.isWindowModified());
        // Reopened, it is this session's; closed cleanly, there is nothing to offer.
        QVERIFY(!window.autosave()->hasUnfinishedRecovery());
        window.setMessageBoxesEnabled(false);
        window.close();
        MainWindow next;
        QVERIFY(!next.autosave()->hasUnfinishedRecovery());
        QVERIFY(!next.offerRecovery());
    }

    // `boneless --project walk.boneless --frame 40` after a crash, answered Reopen: the crash's
    // work got frame 40, the window asked at once to save it, and walk then opened at its own
    // frame. The question says what Reopen does with the files named; reopened, the work opens
    // where it was left, alone; discarded, the files open as asked.
    void reopeningACrashsWorkAtStartOpensItInsteadOfTheFilesNamed() {
        const QString walk = folder_ + "/walk.boneless";
        {
            MainWindow window;
            window.setMessageBoxesEnabled(false);
            QVERIFY(window.openProject(project_));
            window.timeline()->setFrame(7);
            QVERIFY(window.saveProjectAs(walk));
            window.close();
        }
        QFile::remove(ProjectAutosave::recoveryPath());
        const int mapped = leaveWorkAsACrashDoes(12);
        QVERIFY(mapped >= 0);

        // Every question is counted; the recovery's is answered `recovery`, any other to go on.
        QStringList asked;
        QString recovery = "reopenButton";
        QTimer answering;
        connect(&answering, &QTimer::timeout, [&] {
            auto* box = qobject_cast<QMessageBox*>(QApplication::activeModalWidget());
            if (!box) return;
            asked << box->objectName() + ": " + box->informativeText();
            box->findChild<QPushButton*>(box->objectName() == "recoveryQuestion" ? recovery
                                                                                 : "discardButton")
                ->click();
        });
        answering.start(100);
        {
            MainWindow window;
            window.setStartFrame(40);
            QVERIFY(window.openAtStart(walk, {}));
            QCOMPARE(asked.size(), 1);
            QVERIFY2(asked[0].startsWith("recoveryQuestion") &&
                         asked[0].contains("it opens instead of walk.boneless"),
                     qPrintable(asked[0]));
            QVERIFY(window.projectPath().isEmpty());
            QCOMPARE(window.document()->mappedCount(), mapped);
            QCOMPARE(window.timeline()->frame(), 12);
            QVERIFY2(window.statusBar()->currentMessage().contains("instead of walk.boneless"),
                     qPrintable(window.statusBar()->currentMessage()));
        }  // a crash again, with the work reopened

        asked.clear();
        recovery = "discardButton";
        MainWindow window;
        window.setStartFrame(40);
        QVERIFY(window.openAtStart(walk, {}));
        answering.stop();
        QCOMPARE(asked.size(), 1);
        QCOMPARE(window.projectPath(), walk);
        QCOMPARE(window.timeline()->frame(), 40);
        window.setMessageBoxesEnabled(false);
        window.close();
    }

    // Discarded at start, a crash's work stays in the recovery file until an edit replaces it, as
    // the question says: the files named on the command line, loaded, were autosaved over it.
    void filesOpenedAfterACrashsWorkIsDiscardedDoNotReplaceIt() {
        const QStringList files = {folder_ + "/mine/walker.obj", folder_ + "/mine/walker.c3d",
                                   folder_ + "/mine/walker.map.json"};
        const int mapped = leaveWorkAsACrashDoes();
        QVERIFY(mapped >= 0);
        QTimer answering;
        connect(&answering, &QTimer::timeout, [] {
            if (auto* box = qobject_cast<QMessageBox*>(QApplication::activeModalWidget()))
                box->findChild<QPushButton*>("discardButton")->click();
        });
        answering.start(100);
        MainWindow window;
        QVERIFY(window.openAtStart({}, files));
        answering.stop();
        QVERIFY(window.document()->hasTake());
        QVERIFY(window.document()->mappedCount() > mapped);
        QTest::qWait(1500);  // past the autosave's delay
        Document recovered;
        QVERIFY(Project::load(recovered, ProjectAutosave::recoveryPath()));
        QCOMPARE(recovered.mappedCount(), mapped);
        // An edit does replace it.
        QVERIFY(window.document()->clearMapping(3));
        QVERIFY(window.autosave()->saveNow());
        QVERIFY(Project::load(recovered, ProjectAutosave::recoveryPath()));
        QCOMPARE(recovered.mappedCount(), window.document()->mappedCount());
        window.setMessageBoxesEnabled(false);
        window.close();
    }

    // Two Boneless at once, each editing an untitled project, then both gone without closing (kill
    // -9): the work of each is offered at the next start. They shared one recovery file, so the
    // one that saved last had written over the other's work; a crash then lost it. While the other
    // runs, its work is live, not a crash's, and is not offered.
    void twoBonelessRunningAtOnceEachKeepTheirOwnWork() {
        QProcess other;  // another Boneless: its window opens the walker and unmaps two markers
        QProcessEnvironment env = QProcessEnvironment::systemEnvironment();
        env.insert("BONELESS_TEST_ANOTHER_BONELESS", folder_);
        other.setProcessEnvironment(env);
        other.start(QCoreApplication::applicationFilePath(), {});
        QVERIFY(other.waitForStarted());
        QByteArray said;
        while (!said.contains('\n') && other.waitForReadyRead(60000)) said += other.readAll();
        QVERIFY2(said.startsWith("saved "), said.constData());
        const int othersMapped = said.mid(6).trimmed().toInt();
        int mine = -1;
        {
            MainWindow window;
            QVERIFY(!window.autosave()->hasUnfinishedRecovery());
            QVERIFY(!window.offerRecovery());  // no question box: it would wait for an answer
            window.setMessageBoxesEnabled(false);
            QVERIFY(window.openFiles({folder_ + "/mine/walker.obj", folder_ + "/mine/walker.c3d",
                                      folder_ + "/mine/walker.map.json"}));
            QVERIFY(window.document()->clearMapping(5));
            QVERIFY(window.autosave()->saveNow());
            mine = window.document()->mappedCount();
            QVERIFY(mine != othersMapped);
        }  // gone without closing
        other.kill();
        QVERIFY(other.waitForFinished());

        // Both are offered, the last saved first: this one's is discarded, the other's reopened.
        QStringList asked;
        QTimer answering;
        connect(&answering, &QTimer::timeout, [&] {
            auto* box = qobject_cast<QMessageBox*>(QApplication::activeModalWidget());
            if (!box) return;
            asked << box->objectName();
            box->findChild<QPushButton*>(asked.size() == 1 ? "discardButton" : "reopenButton")
                ->click();
        });
        answering.start(100);
        MainWindow next;
        const bool reopened = next.offerRecovery();
        answering.stop();
        QCOMPARE(asked, QStringList({"recoveryQuestion", "recoveryQuestion"}));
        QVERIFY(reopened);
        QCOMPARE(next.document()->mappedCount(), othersMapped);
        Document discarded;  // still the last autosave of this Boneless
        QVERIFY(Project::load(discarded, ProjectAutosave::recoveryPath()));
        QCOMPARE(discarded.mappedCount(), mine);
        next.setMessageBoxesEnabled(false);
        next.close();
    }

    // Started again within a second of kill -9, the killed Boneless can still be a zombie (its
    // parent has not reaped it yet): its work counted as live, the question was not asked, and
    // the new session said "Edits are not autosaved".
    void theWorkOfABonelessKilledAMomentAgoIsOffered() {
        const int mapped = leaveWorkAsACrashDoes();
        QVERIFY(mapped >= 0);
        const pid_t killed = ::fork();  // ended and not waited for: a zombie
        QVERIFY(killed >= 0);
        if (killed == 0) ::_exit(0);
        const auto reap = qScopeGuard([killed] { ::waitpid(killed, nullptr, 0); });
        QTest::qWait(200);
        // The work is the killed Boneless's: in its file, under its record.
        const QString instance =
            QString("%1-%2").arg(killed).arg(boneless::processStartTime(killed));
        const QString file = QFileInfo(ProjectAutosave::recoveryPath()).absolutePath() + "/" +
                             instance + ".boneless";
        QVERIFY(QFile::rename(ProjectAutosave::recoveryPath(), file));
        QSettings().setValue("autosave/" + instance + "/session", "{killed} " + instance);
        QSettings().setValue("autosave/" + instance + "/project", QString());
        MainWindow window;
        QVERIFY(window.autosave()->hasUnfinishedRecovery());
        answerRecovery("reopenButton");
        QVERIFY(window.offerRecovery());
        QCOMPARE(window.document()->mappedCount(), mapped);
        window.setMessageBoxesEnabled(false);
        window.close();
    }

    // An earlier Boneless kept every session in one recovery.boneless: a crash's work there is
    // still offered after the update, once.
    void aCrashsWorkInTheOneRecoveryFileOfEarlierVersionsIsStillOffered() {
        const int mapped = leaveWorkAsACrashDoes();
        QVERIFY(mapped >= 0);
        const QString shared = QStandardPaths::writableLocation(QStandardPaths::AppDataLocation) +
                               "/recovery.boneless";
        QFile::remove(shared);
        QVERIFY(QFile::rename(ProjectAutosave::recoveryPath(), shared));
        // Its record: the session's process id is above any Linux's pid_max, so it is not running.
        QSettings().setValue("autosave/unfinishedSession", "{an-earlier-boneless} 999999999");
        QSettings().setValue("autosave/recoveredProject", QString());
        MainWindow window;
        answerRecovery("reopenButton");
        QVERIFY(window.offerRecovery());
        QCOMPARE(window.document()->mappedCount(), mapped);
        QVERIFY(!QFileInfo::exists(shared));
        window.setMessageBoxesEnabled(false);
        window.close();
        MainWindow next;
        QVERIFY(!next.autosave()->hasUnfinishedRecovery());
    }

    // While a crash's work holds the recovery file, an untitled session has nowhere to autosave:
    // it is told so once, not left to believe its edits are kept.
    void anUntitledSessionThatCannotAutosaveIsToldSoOnce() {
        QFile::remove(ProjectAutosave::recoveryPath());
        QVERIFY(leaveWorkAsACrashDoes() >= 0);
        MainWindow window;
        window.setMessageBoxesEnabled(false);
        QVERIFY(window.autosave()->hasUnfinishedRecovery());
        QSignalSpy failed(window.autosave(), &ProjectAutosave::failed);
        QVERIFY(window.openFiles({folder_ + "/mine/walker.obj", folder_ + "/mine/walker.c3d",
                                  folder_ + "/mine/walker.map.json"}));
        QVERIFY(window.document()->clearMapping(0));
        QVERIFY(!window.autosave()->saveNow());
        QCOMPARE(failed.count(), 1);
        QVERIFY(failed.at(0).at(0).toString().contains("not autosaved"));
        QVERIFY(window.document()->clearMapping(1));
        QVERIFY(!window.autosave()->saveNow());
        QCOMPARE(failed.count(), 1);
        window.autosave()->discardRecovery();
    }

    void discardingACrashsWorkLetsTheNextSessionAutosave() {
        QFile::remove(ProjectAutosave::recoveryPath());
        QVERIFY(leaveWorkAsACrashDoes() >= 0);
        MainWindow window;
        answerRecovery("discardButton");
        QVERIFY(!window.offerRecovery());
        QVERIFY(!window.document()->hasMesh());
        window.setMessageBoxesEnabled(false);
        QVERIFY(window.openDemo());
        QVERIFY(window.document()->clearMapping(5));
        QVERIFY(window.autosave()->saveNow());
        Document recovered;
        QVERIFY(Project::load(recovered, ProjectAutosave::recoveryPath()));
        QCOMPARE(recovered.mappedCount(), recovered.markerCount() - 1);
    }

    void anEditJustMadeReachesItsProjectWhenAnotherFileIsOpened() {
        const QString a = folder_ + "/mine/a.boneless", b = folder_ + "/mine/b.boneless";
        for (const QString& path : {a, b}) {
            QFile::remove(path);
            QVERIFY(QFile::copy(project_, path));
        }
        MainWindow window;
        window.setMessageBoxesEnabled(false);
        window.autosave()->setDelay(60000);  // the edit is still pending when the next opens
        QVERIFY(window.openProject(a));
        QVERIFY(window.document()->clearMapping(0));
        const int mapped = window.document()->mappedCount();
        QVERIFY(window.openProject(b));
        QVERIFY(window.document()->clearMapping(0));
        QVERIFY(window.openFile(folder_ + "/mine/walker.obj"));
        for (const QString& path : {a, b}) {
            Document reopened;
            QVERIFY(Project::load(reopened, path));
            QCOMPARE(reopened.mappedCount(), mapped);
        }
    }

    void aProjectThatCannotBeSavedStillReachesTheAutosaveAndClosingAsks() {
        const QString path = folder_ + "/mine/vanishing.boneless";
        QVERIFY(QFile::copy(project_, path));
        MainWindow window;
        QVERIFY(window.openProject(path));
        QVERIFY(test::showAndWait(window));
        // The project's name taken by a folder: its saves fail, whoever the user is.
        QVERIFY(QFile::remove(path));
        QVERIFY(QDir().mkdir(path));
        QSignalSpy failed(window.autosave(), &ProjectAutosave::failed);
        QVERIFY(window.document()->clearMapping(4));
        QVERIFY(!window.autosave()->saveNow());
        QCOMPARE(failed.count(), 1);
        QVERIFY2(failed.last().at(0).toString().contains(ProjectAutosave::recoveryPath()),
                 qPrintable(failed.last().at(0).toString()));
        Document recovered;
        QVERIFY(Project::load(recovered, ProjectAutosave::recoveryPath()));
        QCOMPARE(recovered.mappedCount(), window.document()->mappedCount());
        for (auto* box : window.findChildren<QMessageBox*>("errorMessage")) box->close();
        answerClose("cancelButton");
        window.close();
        QVERIFY(window.isVisible());
        answerClose("discardButton");
        window.close();
        QVERIFY(!window.isVisible());
    }

    // A full disk made every edit bring up another error box. Said once while it stays full; the
    // edits wait in memory and reach the project once space returns, with no edit needed.
    void aFullDiskIsSaidOnceAndTheEditsReachTheProjectWhenSpaceReturns() {
        const QString path = folder_ + "/mine/full.boneless";
        QFile::remove(path);
        QVERIFY(QFile::copy(project_, path));
        MainWindow window;
        QVERIFY(window.openProject(path));
        QVERIFY(test::showAndWait(window));
        window.autosave()->setRetryDelay(0);
        QSignalSpy failed(window.autosave(), &ProjectAutosave::failed);
        QSignalSpy saved(window.autosave(), &ProjectAutosave::saved);
        // A full disk as this process sees it: no file grows past 64 bytes (EFBIG).
        rlimit normal{};
        QVERIFY(boneless::test::limitFileSize(normal, 64));
        for (int marker = 0; marker < 3; ++marker) {
            QVERIFY(window.document()->clearMapping(marker));
            QVERIFY(!window.autosave()->saveNow());
        }
        const int boxes = window.findChildren<QMessageBox*>("errorMessage").size();
        QVERIFY(boneless::test::restoreFileSize(normal));
        QCOMPARE(failed.count(), 1);
        QCOMPARE(boxes, 1);
        QVERIFY(window.autosave()->isPending());
        // Space again: the retry saves what was made meanwhile.
        QVERIFY(saved.wait(5000));
        Document reopened;
        QVERIFY(Project::load(reopened, path));
        QCOMPARE(reopened.mappedCount(), window.document()->mappedCount());
        QVERIFY2(window.statusBar()->currentMessage().contains("Saved again"),
                 qPrintable(window.statusBar()->currentMessage()));
        // Full again: said again.
        QVERIFY(boneless::test::limitFileSize(normal, 64));
        QVERIFY(window.document()->clearMapping(3));
        const bool savedFull = window.autosave()->saveNow();
        QVERIFY(boneless::test::restoreFileSize(normal));
        QVERIFY(!savedFull);
        QCOMPARE(failed.count(), 2);
        for (auto* box : window.findChildren<QMessageBox*>("errorMessage")) box->close();
        window.autosave()->setRetryDelay(60000);
        QVERIFY(window.autosave()->saveNow());
        window.setMessageBoxesEnabled(false);
        window.close();
    }

    // A frame that fails to solve while the close question is up: its message waits for the
    // answer, so no box covers the question; cancelled, the window shows it then.
    void aSolverErrorDuringTheCloseQuestionWaitsForTheAnswer() {
        MainWindow window;
        QVERIFY(window.openFile(folder_ + "/mine/walker.obj"));
        QVERIFY(window.openFile(folder_ + "/mine/walker.c3d"));
        QVERIFY(window.openFile(folder_ + "/mine/walker.map.json"));
        QVERIFY(test::showAndWait(window));
        Document* d = window.document();
        // A head marker mapped onto a foot: the take cannot be solved with this map.
        const int head = d->markerByLabel("LFHD");
        const int foot = test::farthestFreeVertex(*d, head);
        QSignalSpy failed(window.frameSolver(), &FrameSolver::failed);
        QVERIFY(d->assign(head, foot));
        auto errorShown = [&] {
            for (QMessageBox* box : window.findChildren<QMessageBox*>("errorMessage"))
                if (box->isVisible()) return true;
            return false;
        };
        bool shownDuringQuestion = true;
        QTimer::singleShot(100, [&] {
            auto* box = qobject_cast<QMessageBox*>(QApplication::activeModalWidget());
            QVERIFY(box && box->objectName() == "unsavedQuestion");
            QVERIFY(QTest::qWaitFor([&] { return failed.count() > 0; }, 60000));
            QTest::qWait(200);  // the failure's message, had it been shown, is up by now
            shownDuringQuestion = errorShown();
            box->findChild<QPushButton*>("cancelButton")->click();
        });
        window.close();  // before the failure arrives: the solver is still being built
        QVERIFY(window.isVisible());
        QCOMPARE(failed.count(), 1);
        QVERIFY(!shownDuringQuestion);
        QVERIFY(errorShown());
        answerClose("discardButton");
        window.close();
        QVERIFY(!window.isVisible());
    }

  private:
    QString folder_, project_;
};

int main(int argc, char** argv) {
    ProjectSessionTest::initMain();
    QApplication app(argc, argv);
    if (qEnvironmentVariableIsSet("BONELESS_TEST_ANOTHER_BONELESS"))
        return ProjectSessionTest::runAnotherBoneless(
            qEnvironmentVariable("BONELESS_TEST_ANOTHER_BONELESS"));
    app.setAttribute(Qt::AA_Use96Dpi, true);
    ProjectSessionTest test;
    QTEST_SET_MAIN_SOURCE_PATH
    return QTest::qExec(&test, argc, argv);
}
#include "ProjectSessionTest.moc"
