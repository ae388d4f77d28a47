#pragma once
// `boneless` run as a user runs it from a shell, for the tests of its command line.
#include <QProcess>
#include <QString>
#include <QStringList>

namespace boneless::ui::test {

struct AppRun {
    bool crashed = true;
    int exitCode = -1;  // -1 when it crashed or was stopped
    QString output;     // stdout and stderr together
};

// `env` for a `boneless` whose settings, recent files and autosaves are kept in `home` (not the
// user's).
inline QProcessEnvironment appEnvironment(
    const QString& home, QProcessEnvironment env = QProcessEnvironment::systemEnvironment()) {
    env.insert("XDG_CONFIG_HOME", home + "/config");
    env.insert("XDG_DATA_HOME", home + "/data");
    env.insert("XDG_CACHE_HOME", home + "/cache");
    env.insert("OPENBLAS_NUM_THREADS", "1");
    return env;
}

// Runs the built `boneless` with `arguments` in `env`, its settings and recent files kept in
// `home` (not the user's); one still running after `timeoutMs` is stopped and says "timed out".
inline AppRun runBoneless(const QStringList& arguments, const QString& home,
                          QProcessEnvironment env = QProcessEnvironment::systemEnvironment(),
                          int timeoutMs = 240000) {
    QProcess process;
    process.setProcessEnvironment(appEnvironment(home, env));
    process.setProcessChannelMode(QProcess::MergedChannels);
    process.start(QStringLiteral(BONELESS_GUI), arguments);
    AppRun run;
    if (!process.waitForFinished(timeoutMs)) {
        process.kill();
        process.waitForFinished();
        run.output = "timed out\n";
    }
    run.output += QString::fromLocal8Bit(process.readAll());
    run.crashed = process.exitStatus() != QProcess::NormalExit;
    run.exitCode = run.crashed ? -1 : process.exitCode();
    return run;
}

}  // namespace boneless::ui::test
