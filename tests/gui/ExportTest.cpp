// Export from the application writes what `boneless-cli solve` writes, byte for byte.
#include <QDir>
#include <QFile>
#include <QJsonArray>
#include <QJsonDocument>
#include <QJsonObject>
#include <QProcess>
#include <QSignalSpy>
#include <QtTest>

#include "ModelTestFixtures.h"
#include "boneless/C3dReader.h"
#include "boneless/C3dWriter.h"
#include "boneless/ui/ExportRunner.h"

using namespace boneless;
using namespace boneless::ui;

namespace {

QByteArray readAll(const QString& path) {
    QFile f(path);
    return f.open(QIODevice::ReadOnly) ? f.readAll() : QByteArray();
}

// The sidecar records solve times ("ms", "ms_per_frame_median", ...), which no two runs share;
// everything else must match.
QJsonValue withoutTimes(const QJsonValue& value) {
    if (value.isArray()) {
        QJsonArray out;
        for (const QJsonValue& v : value.toArray()) out.append(withoutTimes(v));
        return out;
    }
    if (!value.isObject()) return value;
    QJsonObject out;
    const QJsonObject in = value.toObject();
    for (auto it = in.begin(); it != in.end(); ++it) {
        const QString key = it.key();
        if (key == "ms" || key.startsWith("ms_") || key.endsWith("_ms")) continue;
        out.insert(key, withoutTimes(it.value()));
    }
    return out;
}

QJsonObject sidecarWithoutTimes(const QString& path) {
    return withoutTimes(QJsonDocument::fromJson(readAll(path)).object()).toObject();
}

void runCli(const Document& d, const QString& out, const QString& format) {
    QProcess cli;
    cli.start(BONELESS_CLI, {"solve", "--mesh", d.meshPath(), "--c3d", d.takePath(), "--map",
                             d.correspondencePath(), "--out", out, "--format", format, "--frames",
                             "0:10", "--quiet"});
    QVERIFY(cli.waitForFinished(120000));
    QVERIFY2(cli.exitCode() == 0, cli.readAllStandardError().constData());
}

void compareFolders(const QString& app, const QString& cli, int expectedFiles) {
    const QStringList names = QDir(cli).entryList(QDir::Files, QDir::Name);
    QCOMPARE(QDir(app).entryList(QDir::Files, QDir::Name), names);
    QCOMPARE(names.size(), expectedFiles);
    for (const QString& name : names) {
        if (name.endsWith(".json")) {
            QCOMPARE(sidecarWithoutTimes(app + "/" + name), sidecarWithoutTimes(cli + "/" + name));
            continue;
        }
        const QByteArray bytes = readAll(app + "/" + name);
        QVERIFY2(!bytes.isEmpty(), qPrintable(name));
        QVERIFY2(bytes == readAll(cli + "/" + name), qPrintable(name));
    }
}

}  // namespace

class ExportTest : public QObject {
    Q_OBJECT
    QString work_, demo_;

    void exportAndCompare(ExportFormat format, const QString& name, int files) {
        Document d;
        QVERIFY(test::loadDemo(d, demo_));
        ExportRequest request = d.exportRequest(work_ + "/app-" + name, format);
        request.first = 0;
        request.end = 10;
        ExportRunner runner;
        QSignalSpy finished(&runner, &ExportRunner::finished);
        QSignalSpy progress(&runner, &ExportRunner::progress);
        QString error;
        QVERIFY2(runner.start(d, request, &error), qPrintable(error));
        QVERIFY(runner.isRunning());
        QVERIFY(finished.wait(120000));
        QVERIFY2(finished.first().at(0).toBool(), qPrintable(finished.first().at(1).toString()));
        QCOMPARE(runner.result().framesWritten, 10);
        QCOMPARE(progress.count(), 10);
        runCli(d, work_ + "/cli-" + name, name);
        compareFolders(work_ + "/app-" + name, work_ + "/cli-" + name, files);
    }

  private slots:
    void initTestCase() {
        test::isolate("ExportTest");
        work_ = test::freshFolder("ExportTest");
        demo_ = work_ + "/demo";
        test::writeDemoProject(demo_);
    }

    void objFramesMatchTheCli() { exportAndCompare(ExportFormat::Obj, "obj", 11); }
    void pointCacheMatchesTheCli() { exportAndCompare(ExportFormat::Pc2, "pc2", 2); }

    void refusedWithAMessageWhenNothingCanBeSolved() {
        Document d;
        QVERIFY(d.loadMesh(demo_ + "/walker.obj"));
        ExportRunner runner;
        QString error;
        QVERIFY(!runner.start(d, d.exportRequest(work_ + "/none", ExportFormat::Obj), &error));
        QVERIFY2(error.contains("take"), qPrintable(error));
        QVERIFY(!runner.isRunning());
        QVERIFY(!QDir(work_ + "/none").exists());
    }

    void aBadFrameRangeIsAMessage() {
        Document d;
        QVERIFY(test::loadDemo(d, demo_));
        ExportRunner runner;
        ExportRequest request = d.exportRequest(work_ + "/bad-range", ExportFormat::Obj);
        request.first = 500;
        QSignalSpy finished(&runner, &ExportRunner::finished);
        QVERIFY(runner.start(d, request));
        QVERIFY(finished.wait(60000));
        QVERIFY(!finished.first().at(0).toBool());
        QVERIFY2(finished.first().at(1).toString().contains("500"),
                 qPrintable(finished.first().at(1).toString()));
    }

    // The app exports through the same core: a glb of a take without a frame rate is refused
    // with solve's message, not written with every key at time 0.
    void aGlbOfATakeWithoutAFrameRateIsRefusedNamingTheTake() {
        const QString folder = test::freshFolder("ExportTest/no-rate");
        test::writeDemoProject(folder);
        const QString take = folder + "/walker.c3d";
        C3dTake t = readC3d(take.toStdString());
        t.rate = 0;
        writeC3d(t, take.toStdString());
        Document d;
        QVERIFY(d.loadMesh(folder + "/walker.obj"));
        QVERIFY(d.loadTake(take));
        QVERIFY(d.loadCorrespondence(folder + "/walker.map.json"));
        ExportRunner runner;
        QSignalSpy finished(&runner, &ExportRunner::finished);
        QVERIFY(runner.start(d, d.exportRequest(work_ + "/no-rate", ExportFormat::Glb)));
        QVERIFY(finished.wait(60000));
        QVERIFY(!finished.first().at(0).toBool());
        const QString message = finished.first().at(1).toString();
        QVERIFY2(message.contains(take + ": its frame rate is 0"), qPrintable(message));
        QVERIFY(!QFile::exists(work_ + "/no-rate/walker.glb"));
    }
};

QTEST_MAIN(ExportTest)
#include "ExportTest.moc"
