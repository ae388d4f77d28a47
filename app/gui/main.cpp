// boneless: the desktop application.
//   boneless                                   opens the generated demo project
//   boneless FILE...                           opens projects, meshes, takes, maps by extension
//   boneless --project P --frame N --screenshot OUT.png   renders frame N to a PNG and exits
#include <QApplication>
#include <QCommandLineParser>
#include <QFileInfo>
#include <QSettings>
#include <QStatusBar>
#include <QTimer>
#include <cstdio>

#include "BonelessVersion.h"
#include "boneless/ui/Document.h"
#include "boneless/ui/MainWindow.h"
#include "boneless/ui/MeshView.h"
#include "boneless/ui/NumberFormat.h"
#include "boneless/ui/SurfaceFormat.h"
#include "boneless/ui/Timeline.h"

namespace {

constexpr int kMinSide = 16, kMaxSide = 16384;  // a screenshot's side, in pixels

void fail(const QString& message) {
    std::fprintf(stderr, "boneless: %s\n", qPrintable(message));
}

// Waits until the requested frame is solved and on screen, then writes the view's picture.
// The window stays on screen meanwhile: a QOpenGLWidget only renders when exposed.
int runScreenshot(QApplication& app, boneless::ui::MainWindow& window, const QString& out,
                  int timeoutMs) {
    int status = -1;
    QString firstError;
    QObject::connect(&window, &boneless::ui::MainWindow::errorShown, [&](const QString& message) {
        if (firstError.isEmpty()) firstError = message;
    });
    QTimer poll;
    QObject::connect(&poll, &QTimer::timeout, [&] {
        if (!firstError.isEmpty()) {
            fail(firstError);
            status = 1;
        } else if (QString why, detail; window.frameUpToDate() && window.document()->hasTake() &&
                                        !window.document()->canSolve(&why, &detail)) {
            // A picture of the take unsolved is not the frame asked for.
            const QString file = window.projectPath().isEmpty() ? window.document()->takePath()
                                                                : window.projectPath();
            fail(QString("%1: not solving: %2%3")
                     .arg(file, why, detail.isEmpty() ? "" : " " + detail));
            status = 1;
        } else if (window.frameUpToDate()) {
            const QImage image = window.meshView()->grabImage();
            if (image.isNull() || !image.save(out)) {
                fail(QString("cannot write the screenshot %1").arg(out));
                status = 1;
            } else {
                std::printf("%s: %s\n", qPrintable(QFileInfo(out).absoluteFilePath()),
                            qPrintable(window.frameSummary()));
                status = 0;
            }
        }
        if (status >= 0) app.exit(status);
    });
    QTimer::singleShot(timeoutMs, &app, [&] {
        fail(QString("frame not ready after %1 s").arg(timeoutMs / 1000));
        app.exit(1);
    });
    poll.start(50);
    return app.exec();
}

}  // namespace

int main(int argc, char** argv) {
    QCoreApplication::setApplicationName("Boneless");
    QCoreApplication::setOrganizationName("Boneless");
    // A Wayland desktop matches the window to its menu entry by this name (X11 by WM_CLASS).
    QGuiApplication::setDesktopFileName("org.boneless.Boneless");
    QCoreApplication::setApplicationVersion(BONELESS_VERSION);

    QCommandLineParser parser;
    parser.setApplicationDescription(
        "Skeleton-free mesh animation from motion-capture markers.\n\n"
        "With no file it opens a generated demo. Files open by extension: meshes (.obj .ply .off\n"
        ".stl), takes (.c3d), correspondence files (.json) and projects (.boneless).\n\n"
        "Examples:\n"
        "  boneless body.obj take.c3d map.json\n"
        "  boneless --project walk.boneless --frame 40 --screenshot walk.png --size 640x480\n\n"
        "boneless-cli solves, inspects and maps takes from scripts.");
    const QCommandLineOption help = parser.addHelpOption();
    const QCommandLineOption version = parser.addVersionOption();
    const QCommandLineOption project("project", "Open the project file P.", "P");
    const QCommandLineOption frame("frame", "Show frame N (0-based) of the take.", "N");
    const QCommandLineOption screenshot("screenshot",
                                        "Render the frame into the PNG file OUT and exit.", "OUT");
    const QCommandLineOption noMsaa("no-msaa", "Render without multisampling.");
    const QCommandLineOption size(
        "size", "With --screenshot: the view's size WxH, 16 to 16384 pixels a side (800x600).",
        "WxH", "800x600");
    const QCommandLineOption group(
        "group", "Open group G of an OBJ among the files, without asking which.", "G");
    parser.addOptions({project, frame, group, screenshot, noMsaa, size});
    parser.addPositionalArgument("files", "Projects, meshes, takes or maps to open.", "[FILE...]");

    // --help and --version are answered before the QApplication, which aborts without a display
    // (ssh, a headless machine). The rest waits for it: Qt's own options (-platform) are its, and
    // --help-all lists them, from an application on the offscreen platform, which needs no display.
    {
        QStringList arguments;
        for (int i = 0; i < argc; ++i) arguments << QString::fromLocal8Bit(argv[i]);
        (void)parser.parse(arguments);  // process() below reports the errors
        if (parser.isSet(version) || parser.isSet(help)) {
            const QCoreApplication core(argc, argv);  // for the program's name in the usage
            if (parser.isSet(version)) parser.showVersion();
            parser.showHelp(0);
        }
        if (parser.isSet("help-all")) qputenv("QT_QPA_PLATFORM", "offscreen");
    }

    boneless::ui::setDefaultSurfaceFormat();
    QApplication app(argc, argv);
    boneless::ui::useOneNumberFormat();  // "12.5" as the CLI and project files write it
    parser.process(app);

    const bool batch = parser.isSet(screenshot);
    int startFrame = -1;
    if (parser.isSet(frame)) {
        bool ok = false;
        startFrame = parser.value(frame).toInt(&ok);
        if (!ok || startFrame < 0) {
            fail(QString("--frame wants a frame number >= 0, not '%1'").arg(parser.value(frame)));
            return 2;
        }
    }
    QSize viewSize(800, 600);
    if (batch) {
        const QStringList wh = parser.value(size).split('x');
        bool okW = false, okH = false;
        const int w = wh.size() == 2 ? wh[0].toInt(&okW) : 0;
        const int h = wh.size() == 2 ? wh[1].toInt(&okH) : 0;
        if (!okW || !okH) {
            fail(QString("--size wants WxH, not '%1'").arg(parser.value(size)));
            return 2;
        }
        // Past 16384 a side, Mesa's frame buffer fails: a blank picture, or a crash.
        if (w < kMinSide || h < kMinSide || w > kMaxSide || h > kMaxSide) {
            fail(QString("--size: each side must be %1 to %2 pixels, not '%3'")
                     .arg(kMinSide)
                     .arg(kMaxSide)
                     .arg(parser.value(size)));
            return 2;
        }
        viewSize = QSize(w, h);
    }

    boneless::ui::MainWindow window;
    // Multisampling is cheap on a GPU but triples the cost on software GL; batch renders
    // skip it so that their pictures compare across machines.
    const int samples = QSettings().value("view/multiSamples", 4).toInt();
    window.meshView()->setMultiSampling(parser.isSet(noMsaa) || batch ? 0 : samples);
    window.setMessageBoxesEnabled(!batch);
    window.setRecordsSession(!batch);  // a render script leaves the user's recent files alone
    // Logout, shutdown and kill save the last second's edits and quit, asking nothing.
    if (!batch) window.quitOnTerminationSignals();
    window.setStartFrame(startFrame);
    window.setStartGroup(parser.value(group));
    if (batch) window.meshView()->setFixedSize(viewSize);

    // What the error box's details would show: the status bar has only the first line.
    QString openError;
    const auto openErrors = QObject::connect(&window, &boneless::ui::MainWindow::errorShown,
                                             [&](const QString& message) { openError = message; });
    const bool opened = window.openAtStart(parser.value(project), parser.positionalArguments());
    if (window.endedBySignal()) return 0;  // during a question at start: app.exec() would stay
    if (batch && !opened) {
        fail(openError.isEmpty() ? window.statusBar()->currentMessage() : openError);
        return 1;
    }

    window.show();
    if (batch) {
        if (startFrame >= 0 && window.timeline()->frameCount() > 0 &&
            startFrame >= window.timeline()->frameCount()) {
            fail(QString("--frame %1: the take has frames 0 to %2")
                     .arg(startFrame)
                     .arg(window.timeline()->frameCount() - 1));
            return 1;
        }
        QObject::disconnect(openErrors);
        return runScreenshot(app, window, parser.value(screenshot), 300000);
    }
    return app.exec();
}
