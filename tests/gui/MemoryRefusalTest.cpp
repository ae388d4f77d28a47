// Issue 29, large inputs, in the app: a mesh whose solve would not fit the memory the process may
// use is shown but never solved, with the CLI's message (file, size, estimate, limit), once; the
// project's work stays, and the window goes on working. The limit is set through take's test
// hook: a window cannot run under a small ulimit -v as the CLI test does.
#include <QLocale>
#include <QtTest>

#include "SolveMemory.h"
#include "ViewTestSupport.h"
#include "boneless/ui/ExportDialog.h"
#include "boneless/ui/FrameSolver.h"
#include "boneless/ui/Timeline.h"

using namespace boneless::ui;
using boneless::estimateSolveMemory;
using boneless::limitSolveMemoryForTests;
using boneless::SolverOptions;

namespace {

// A window without message boxes showing `project`, its errors collected in `errors`.
std::unique_ptr<MainWindow> open(const QString& project, QStringList* errors) {
    auto window = std::make_unique<MainWindow>();
    window->setMessageBoxesEnabled(false);
    QObject::connect(window.get(), &MainWindow::errorShown,
                     [errors](const QString& m) { *errors << m; });
    if (!window->openProject(project) || !test::showAndWait(*window)) return nullptr;
    return window;
}

}  // namespace

class MemoryRefusalTest : public QObject {
    Q_OBJECT
  public:
    static void initMain() { setDefaultSurfaceFormat(); }

  private slots:
    void cleanup() { limitSolveMemoryForTests(0); }

    void aMeshTooLargeForTheLimitIsShownUnsolvedNamingItsSizeAndTheWindowKeepsWorking() {
        const QString project = test::demoProjectFor("MemoryRefusalTest-limit");
        limitSolveMemoryForTests(1 << 20);
        QStringList errors;
        const auto shown = open(project, &errors);
        QVERIFY(shown);
        MainWindow& window = *shown;

        // The CLI's message under one plain sentence.
        QTRY_COMPARE(errors.size(), 1);
        const Document& document = *window.document();
        const QLocale english(QLocale::English);
        const QString size = document.meshPath() + ": " +
                             english.toString(document.mesh().faceCount()) + " faces (" +
                             english.toString(document.mesh().vertexCount()) + " vertices)";
        QVERIFY2(errors[0].startsWith("walker.obj is too large to solve in the memory available"),
                 qPrintable(errors[0]));
        QVERIFY2(errors[0].contains(size), qPrintable(errors[0]));
        QVERIFY2(errors[0].contains("would need about"), qPrintable(errors[0]));
        QVERIFY2(errors[0].contains("the limit set for tests is 1 MB"), qPrintable(errors[0]));

        // No solver was prepared; the mesh and the project's map are there, unsolved.
        QVERIFY(!window.isSolving());
        QVERIFY(!window.frameSolver()->hasProblem());
        QVERIFY(window.meshView()->hasMesh());
        QVERIFY(document.mappedCount() >= 3);
        QVERIFY(window.frameSummary().contains("would need about"));

        // The timeline still moves, and edits do not repeat the message.
        window.timeline()->setFrame(10);
        QVERIFY(test::waitForFrame(window));
        QCOMPARE(window.displayedFrame(), 10);
        boneless::TakeSolveOptions settings = document.settings();
        settings.markerWeight += 1;  // any edit: an unchanged setting is none
        window.document()->setSettings(settings);
        QVERIFY(test::waitForFrame(window));
        QCOMPARE(errors.size(), 1);

        // The export is refused with the same message.
        window.showExportDialog();
        QCOMPARE(errors.size(), 2);
        QVERIFY2(errors[1].startsWith("Nothing to export: ") && errors[1].contains(size),
                 qPrintable(errors[1]));
        QVERIFY(!window.exportDialog()->isVisible());

        // Once the memory is there, the same window solves.
        limitSolveMemoryForTests(0);
        settings.markerWeight += 1;
        window.document()->setSettings(settings);
        QTRY_VERIFY(window.isSolving());
        QVERIFY(test::waitForFrame(window));
        QVERIFY(window.frameSolver()->hasProblem());
        QCOMPARE(errors.size(), 2);
    }

    // The exact method needs several times the local/global method's memory: switching to it
    // under a limit only local/global fits refuses it, and switching back solves again.
    void theRefusalFollowsTheSolveMethod() {
        const QString project = test::demoProjectFor("MemoryRefusalTest-method");
        QStringList errors;
        const auto shown = open(project, &errors);
        QVERIFY(shown);
        MainWindow& window = *shown;
        QVERIFY(window.isSolving());
        Document& document = *window.document();
        // A limit between the two methods' estimates: only local/global fits.
        const int vertices = document.mesh().vertexCount(), faces = document.mesh().faceCount();
        const std::uint64_t localGlobal =
            estimateSolveMemory(vertices, faces, SolverOptions::Method::LocalGlobal).firstRun;
        const std::uint64_t exact =
            estimateSolveMemory(vertices, faces, SolverOptions::Method::Exact).firstRun;
        QVERIFY(localGlobal < exact);
        limitSolveMemoryForTests((localGlobal + exact) / 2);

        auto settings = document.settings();
        settings.solver.method = SolverOptions::Method::Exact;
        document.setSettings(settings);
        QTRY_COMPARE(errors.size(), 1);
        QVERIFY2(errors[0].contains(document.meshPath() + ": "), qPrintable(errors[0]));
        QVERIFY(test::waitForFrame(window));
        QVERIFY(!window.isSolving());

        settings.solver.method = SolverOptions::Method::LocalGlobal;
        document.setSettings(settings);
        QTRY_VERIFY(window.isSolving());
        QVERIFY(test::waitForFrame(window));
        QCOMPARE(errors.size(), 1);
    }
};

QTEST_MAIN(MemoryRefusalTest)
#include "MemoryRefusalTest.moc"
