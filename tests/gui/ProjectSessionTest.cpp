// The window and its project files as a user meets them: the demo is never written over, a new
// mesh or take starts an untitled project, the frame, speed and camera come back with the
// project, and a damaged or hostile project file gives a message, offers the last autosave and
// is itself left alone.
#include <QFile>
#include <QLabel>
#include <QMessageBox>
#include <QPushButton>
#include <QUndoStack>
#include <QtTest>

#include "ViewTestSupport.h"
#include "boneless/ui/DemoProject.h"
#include "boneless/ui/Document.h"
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

}  // namespace

class ProjectSessionTest : public QObject {
    Q_OBJECT
  public:
    static void initMain() { setDefaultSurfaceFormat(); }

  private slots:
    void initTestCase() {
        test::isolate("ProjectSessionTest");
        folder_ = test::freshFolder("ProjectSessionTest");
        project_ = test::writeDemoProject(folder_ + "/mine");
        QDir(DemoProject::defaultFolder()).removeRecursively();
        QFile::remove(ProjectAutosave::recoveryPath());
    }

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

    void aDamagedProjectGivesAMessageOffersTheAutosaveAndIsLeftAlone() {
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
            {"bad-alignment", badAlignment}};  // last: it takes the offer

        MainWindow window;
        QVERIFY(window.openProject(project_));
        QVERIFY(test::showAndWait(window));
        window.autosave()->setDelay(10);
        QVERIFY(window.document()->clearMapping(2));
        QVERIFY(window.autosave()->saveNow());  // the last good autosave
        const int mapped = window.document()->mappedCount();
        QSignalSpy errors(&window, &MainWindow::errorShown);

        for (const auto& [name, bytes] : cases) {
            const QString path = folder_ + "/" + name + ".boneless";
            writeAll(path, bytes);
            QVERIFY2(!window.openProject(path), name);
            QVERIFY2(errors.last().at(0).toString().startsWith(name + QString(".boneless")),
                     qPrintable(errors.last().at(0).toString()));
            auto* box = window.findChild<QMessageBox*>("projectErrorMessage");
            QVERIFY(box && box->isVisible());
            QVERIFY(!box->detailedText().isEmpty());
            QVERIFY(box->findChild<QPushButton*>("openRecoveryButton"));
            // The window keeps its project, which stays the one autosaved; the bad file stays.
            QVERIFY2(window.projectPath() == project_, name);
            QCOMPARE(window.document()->mappedCount(), mapped);
            QVERIFY(window.document()->clearMapping(5));
            window.document()->undoStack()->undo();
            QTest::qWait(50);
            QCOMPARE(readAll(path), bytes);
            if (QByteArray(name) != "bad-alignment") {
                box->close();
                QTest::qWait(0);
                continue;
            }
            // Taking the offer: the last autosave, untitled.
            box->findChild<QPushButton*>("openRecoveryButton")->click();
            QVERIFY(window.projectPath().isEmpty());
            QCOMPARE(window.document()->mappedCount(), mapped);
            QVERIFY(test::waitForFrame(window));
        }
        QCOMPARE(readAll(project_).size() > 0, true);
    }

  private:
    QString folder_, project_;
};

QTEST_MAIN(ProjectSessionTest)
#include "ProjectSessionTest.moc"
