// `boneless` run from a shell: what it answers before it needs a window.
#include <QRegularExpression>
#include <QtTest>

#include "AppRun.h"
#include "ModelTestFixtures.h"

namespace {

using boneless::ui::test::AppRun;

// Runs boneless with `arguments`, without a display when `headless` (no DISPLAY, no Xvfb, no
// QT_QPA_PLATFORM): a user on a headless machine or over ssh.
AppRun runFromShell(const QStringList& arguments, bool headless) {
    QProcessEnvironment env = QProcessEnvironment::systemEnvironment();
    if (headless)
        for (const char* name : {"DISPLAY", "WAYLAND_DISPLAY", "QT_QPA_PLATFORM"}) env.remove(name);
    return boneless::ui::test::runBoneless(
        arguments, boneless::ui::test::freshFolder("CommandLineTest"), env, 60000);
}

// Why a run that should have exited 0 did not, for the test's message.
QString exitText(const QStringList& arguments, const AppRun& run) {
    return QString("%1: exit %2%3\n%4")
        .arg(arguments.join(' '))
        .arg(run.exitCode)
        .arg(run.crashed ? " (crashed)" : "")
        .arg(run.output);
}

}  // namespace

class CommandLineTest : public QObject {
    Q_OBJECT
  private slots:
    void helpIsPrintedWithoutADisplay() {
        for (const QStringList& arguments :
             {QStringList{"--help"}, QStringList{"-h"}, QStringList{"--frame", "3", "--help"}}) {
            const AppRun run = runFromShell(arguments, true);
            QVERIFY2(!run.crashed && run.exitCode == 0, qPrintable(exitText(arguments, run)));
            QVERIFY2(run.output.contains("Usage: ") && run.output.contains("boneless"),
                     qPrintable(run.output));
            for (const char* option : {"--project", "--frame", "--group", "--screenshot", "--size",
                                       "--no-msaa", "--version"})
                QVERIFY2(run.output.contains(option), qPrintable(option + ("\n" + run.output)));
        }
    }

    // --help-all adds Qt's own options, which exist only once the application does.
    void helpWithQtsOptionsIsPrintedWithoutADisplay() {
        const AppRun run = runFromShell({"--help-all"}, true);
        QVERIFY2(!run.crashed && run.exitCode == 0, qPrintable(exitText({"--help-all"}, run)));
        for (const char* option : {"--project", "--screenshot", "-platform"})
            QVERIFY2(run.output.contains(option), qPrintable(option + ("\n" + run.output)));
    }

    void versionIsPrintedWithoutADisplay() {
        const AppRun run = runFromShell({"--version"}, true);
        QVERIFY2(!run.crashed && run.exitCode == 0, qPrintable(exitText({"--version"}, run)));
        QVERIFY2(QRegularExpression("^Boneless \\d+\\.\\d+").match(run.output).hasMatch(),
                 qPrintable(run.output));
    }

    // A screenshot past 16384 pixels a side came out blank (exit 0) or crashed the app; one under
    // 16 was refused as not "WxH".
    void aScreenshotSizeOutOfRangeIsRefusedNamingTheRange() {
        for (const QString& size : {"20000x100", "100x16385", "10x10"}) {
            const QStringList arguments{"--screenshot", "x.png", "--size", size};
            const AppRun run = runFromShell(arguments, false);
            QVERIFY2(!run.crashed && run.exitCode == 2, qPrintable(exitText(arguments, run)));
            QVERIFY2(run.output.contains("--size: each side must be 16 to 16384 pixels, not '" +
                                         size + "'"),
                     qPrintable(run.output));
        }
        const AppRun run = runFromShell({"--screenshot", "x.png", "--size", "800by600"}, false);
        QVERIFY2(run.exitCode == 2 && run.output.contains("--size wants WxH, not '800by600'"),
                 qPrintable(run.output));
    }

    // Answering --help early must not let a wrong option through to the window.
    void anUnknownOptionIsStillRefusedWithTheParsersMessage() {
        const AppRun run = runFromShell({"--no-such-option"}, false);
        QVERIFY2(!run.crashed && run.exitCode == 1, qPrintable(run.output));
        QVERIFY2(run.output.contains("Unknown option 'no-such-option'"), qPrintable(run.output));
    }
};

QTEST_GUILESS_MAIN(CommandLineTest)
#include "CommandLineTest.moc"
