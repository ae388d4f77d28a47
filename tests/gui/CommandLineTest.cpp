// `boneless` run from a shell: what it answers before it needs a window.
#include <QProcess>
#include <QRegularExpression>
#include <QtTest>

#include "ModelTestFixtures.h"

namespace {

struct Run {
    bool crashed = true;
    int exitCode = -1;
    QString output;
};

// Runs boneless with `arguments`, without a display when `headless` (no DISPLAY, no Xvfb, no
// QT_QPA_PLATFORM): a user on a headless machine or over ssh.
Run runBoneless(const QStringList& arguments, bool headless) {
    QProcessEnvironment env = QProcessEnvironment::systemEnvironment();
    if (headless)
        for (const char* name : {"DISPLAY", "WAYLAND_DISPLAY", "QT_QPA_PLATFORM"}) env.remove(name);
    // Any settings it would write stay in the test's folder, not the user's.
    const QString home = boneless::ui::test::freshFolder("CommandLineTest");
    env.insert("XDG_CONFIG_HOME", home + "/config");
    env.insert("XDG_DATA_HOME", home + "/data");
    env.insert("XDG_CACHE_HOME", home + "/cache");
    QProcess process;
    process.setProcessEnvironment(env);
    process.setProcessChannelMode(QProcess::MergedChannels);
    process.start(QStringLiteral(BONELESS_GUI), arguments);
    Run run;
    if (!process.waitForFinished(60000)) {
        process.kill();
        process.waitForFinished();
        run.output = "timed out\n";
    }
    run.output += QString::fromLocal8Bit(process.readAll());
    run.crashed = process.exitStatus() != QProcess::NormalExit;
    run.exitCode = process.exitCode();
    return run;
}

}  // namespace

class CommandLineTest : public QObject {
    Q_OBJECT
  private slots:
    void helpIsPrintedWithoutADisplay() {
        for (const QStringList& arguments :
             {QStringList{"--help"}, QStringList{"-h"}, QStringList{"--frame", "3", "--help"}}) {
            const Run run = runBoneless(arguments, true);
            QVERIFY2(!run.crashed && run.exitCode == 0,
                     qPrintable(QString("%1: exit %2%3\n%4")
                                    .arg(arguments.join(' '))
                                    .arg(run.exitCode)
                                    .arg(run.crashed ? " (crashed)" : "")
                                    .arg(run.output)));
            QVERIFY2(run.output.contains("Usage: ") && run.output.contains("boneless"),
                     qPrintable(run.output));
            for (const char* option :
                 {"--project", "--frame", "--screenshot", "--size", "--no-msaa", "--version"})
                QVERIFY2(run.output.contains(option), qPrintable(option + ("\n" + run.output)));
        }
    }

    void versionIsPrintedWithoutADisplay() {
        const Run run = runBoneless({"--version"}, true);
        QVERIFY2(!run.crashed && run.exitCode == 0,
                 qPrintable(QString("exit %1%2\n%3")
                                .arg(run.exitCode)
                                .arg(run.crashed ? " (crashed)" : "")
                                .arg(run.output)));
        QVERIFY2(QRegularExpression("^Boneless \\d+\\.\\d+").match(run.output).hasMatch(),
                 qPrintable(run.output));
    }

    // Answering --help early must not let a wrong option through to the window.
    void anUnknownOptionIsStillRefusedWithTheParsersMessage() {
        const Run run = runBoneless({"--no-such-option"}, false);
        QVERIFY2(!run.crashed && run.exitCode == 1, qPrintable(run.output));
        QVERIFY2(run.output.contains("Unknown option 'no-such-option'"), qPrintable(run.output));
    }
};

QTEST_GUILESS_MAIN(CommandLineTest)
#include "CommandLineTest.moc"
