// `boneless --project P --frame N --screenshot OUT.png` against a committed baseline picture.
// The view's own elements have baselines of their own in ViewBaselineTest.
#include <QDir>
#include <QFileInfo>
#include <QImage>
#include <QJsonArray>
#include <QJsonDocument>
#include <QJsonObject>
#include <QSet>
#include <QSettings>
#include <QtTest>

#include "AppRun.h"
#include "BaselineImage.h"
#include "ViewTestSupport.h"

namespace {

namespace test = boneless::ui::test;

constexpr double kMaxMismatchShare = 0.01;  // of all pixels

// A copy of the demo project at `path` whose first map entry `edit` changed.
template <typename Edit>
QString editedDemoMap(const QString& demo, const QString& path, Edit edit) {
    QFile in(demo);
    if (!in.open(QIODevice::ReadOnly)) return {};
    QJsonObject root = QJsonDocument::fromJson(in.readAll()).object();
    QJsonObject correspondence = root["correspondence"].toObject();
    QJsonObject map = correspondence["map"].toObject();
    QJsonArray markers = map["markers"].toArray();
    QJsonObject first = markers[0].toObject();
    edit(first);
    markers[0] = first;
    map["markers"] = markers;
    correspondence["map"] = map;
    correspondence["modified"] = true;
    root["correspondence"] = correspondence;
    QFile out(path);
    if (!out.open(QIODevice::WriteOnly)) return {};
    out.write(QJsonDocument(root).toJson());
    return path;
}

}  // namespace

class ScreenshotTest : public QObject {
    Q_OBJECT
  private slots:
    void initTestCase() {
        boneless::ui::test::isolate("ScreenshotTest");
        folder_ = boneless::ui::test::freshFolder("ScreenshotTest");
        project_ = boneless::ui::test::writeDemoProject(folder_ + "/demo");
    }

    void demoFrameMatchesBaseline() {
        const QString out = folder_ + "/demo-frame10.png";
        const test::AppRun run = test::runBoneless(
            {"--project", project_, "--frame", "10", "--screenshot", out}, folder_);
        QVERIFY2(run.exitCode == 0, qPrintable(run.output));
        qInfo("boneless: %s", qPrintable(run.output.trimmed()));
        const QImage actual = QImage(out).convertToFormat(QImage::Format_RGB32);
        QVERIFY2(!actual.isNull(), qPrintable(out));
        QCOMPARE(actual.size(), QSize(800, 600));

        // Not blank: a mesh covers a good part of the background, shaded in many tones.
        const QRgb background = actual.pixel(0, 0);
        int covered = 0;
        QSet<QRgb> colours;
        for (int y = 0; y < actual.height(); ++y)
            for (int x = 0; x < actual.width(); ++x) {
                const QRgb p = actual.pixel(x, y);
                colours.insert(p);
                if (test::channelDistance(p, background) > test::kChannelTolerance) ++covered;
            }
        const double coveredShare = double(covered) / (actual.width() * actual.height());
        QVERIFY2(coveredShare > 0.05, qPrintable(QString("only %1 % of the picture differs from "
                                                         "the background")
                                                     .arg(100 * coveredShare)));
        QVERIFY2(colours.size() > 200, qPrintable(QString("%1 colours").arg(colours.size())));

        const QString failure =
            test::differenceFromBaseline(actual, "demo-frame10", folder_, kMaxMismatchShare);
        QVERIFY2(failure.isEmpty(), qPrintable(failure));
    }

    // An OBJ with groups asked which to open in a modal dialog that no one can answer in a
    // screenshot run: it hung for ever. It now says to name the group, and --group opens it.
    void aMeshWithGroupsIsOpenedByGroupOrRefusedNamingThem() {
        const QString dir = QFileInfo(project_).absolutePath();
        QFile walker(dir + "/walker.obj"), grouped(folder_ + "/grouped.obj");
        QVERIFY(walker.open(QIODevice::ReadOnly) && grouped.open(QIODevice::WriteOnly));
        grouped.write("g body\n" + walker.readAll() +
                      "g prop\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf -3 -2 -1\n");
        grouped.close();
        const QStringList files{grouped.fileName(), dir + "/walker.c3d", dir + "/walker.map.json"};
        const QString out = folder_ + "/grouped.png";
        auto screenshot = [&](const QStringList& options) {
            return test::runBoneless(files + options + QStringList{"--screenshot", out}, folder_,
                                     QProcessEnvironment::systemEnvironment(), 60000);
        };
        test::AppRun run = screenshot({});
        QVERIFY2(run.exitCode == 1, qPrintable(run.output));
        QVERIFY2(run.output.contains("grouped.obj has 2 groups: name one with --group") &&
                     run.output.contains("body, prop"),
                 qPrintable(run.output));
        QVERIFY(!QFileInfo::exists(out));
        run = screenshot({"--group", "lid"});
        QVERIFY2(run.exitCode == 1 && run.output.contains("grouped.obj has no group named lid"),
                 qPrintable(run.output));
        run = screenshot({"--group", "body", "--frame", "5"});
        QVERIFY2(run.exitCode == 0, qPrintable(run.output));
        QVERIFY(!QImage(out).isNull());
    }

    // A render script over a library replaced the user's File → Recent Files with what it
    // rendered: a screenshot run records nothing of the user's session, recent files and autosave
    // records (the settings file) and autosaves (the recovery folder) alike.
    void aScreenshotRunLeavesTheUsersRecentFilesAndAutosavesAlone() {
        const QString home = boneless::ui::test::freshFolder("ScreenshotTest/session");
        const QString settingsFile = home + "/config/Boneless/Boneless.conf";
        {
            QSettings settings(settingsFile, QSettings::IniFormat);
            settings.setValue("recentFiles", QStringList{project_});
        }
        const QString recovery = home + "/data/Boneless/Boneless/recovery";
        QVERIFY(QDir().mkpath(recovery));
        QFile autosave(recovery + "/1-1.boneless");
        QVERIFY(autosave.open(QIODevice::WriteOnly) && autosave.write("{}") == 2);
        autosave.close();
        auto contents = [](const QString& path) {
            QFile file(path);
            return file.open(QIODevice::ReadOnly) ? file.readAll() : QByteArray("(none)");
        };
        const QByteArray settingsBefore = contents(settingsFile);
        const QStringList recoveryBefore = QDir(recovery).entryList(QDir::Files);

        const QString dir = QFileInfo(project_).absolutePath();
        const QStringList runs[] = {
            {"--project", project_},
            {dir + "/walker.obj", dir + "/walker.c3d", dir + "/walker.map.json"}};
        for (const QStringList& files : runs) {
            const test::AppRun run = test::runBoneless(
                files + QStringList{"--frame", "2", "--screenshot", home + "/shot.png"}, home);
            QVERIFY2(run.exitCode == 0, qPrintable(run.output));
            QCOMPARE(contents(settingsFile), settingsBefore);
            QCOMPARE(QDir(recovery).entryList(QDir::Files), recoveryBefore);
        }
    }

    void badProjectFailsWithMessage() {
        const QString out = folder_ + "/never.png";
        const test::AppRun run = test::runBoneless(
            {"--project", folder_ + "/missing.boneless", "--screenshot", out}, folder_);
        QVERIFY2(run.exitCode != 0, qPrintable(run.output));
        QVERIFY2(run.output.contains("missing.boneless"), qPrintable(run.output));
        QVERIFY(!QFileInfo::exists(out));
    }

    // A script has no error box to read: the reason must reach its output.
    void aProjectThatDoesNotOpenPrintsWhy() {
        const QString project =
            editedDemoMap(project_, QFileInfo(project_).absolutePath() + "/far-vertex.boneless",
                          [](QJsonObject& marker) { marker["vertex"] = 999999; });
        QVERIFY(!project.isEmpty());
        const QString out = folder_ + "/never.png";
        const test::AppRun run =
            test::runBoneless({"--project", project, "--screenshot", out}, folder_);
        QVERIFY2(run.exitCode != 0, qPrintable(run.output));
        QVERIFY2(run.output.contains("far-vertex.boneless"), qPrintable(run.output));
        QVERIFY2(run.output.contains("999999"), qPrintable(run.output));
        QVERIFY(!QFileInfo::exists(out));
    }

    // The picture of an unsolved take is not the frame asked for.
    void aProjectThatCannotSolveFailsWithTheReason() {
        const QString project =
            editedDemoMap(project_, QFileInfo(project_).absolutePath() + "/no-label.boneless",
                          [](QJsonObject& marker) { marker["label"] = "NOSUCHLABEL"; });
        QVERIFY(!project.isEmpty());
        const QString out = folder_ + "/never.png";
        const test::AppRun run =
            test::runBoneless({"--project", project, "--screenshot", out}, folder_);
        QVERIFY2(run.exitCode != 0, qPrintable(run.output));
        QVERIFY2(run.output.contains("no-label.boneless"), qPrintable(run.output));
        QVERIFY2(run.output.contains("NOSUCHLABEL"), qPrintable(run.output));
        QVERIFY(!QFileInfo::exists(out));
    }

    // A take and its map without a mesh (a project whose mesh key was lost) said "preparing
    // the solver for  (calibrating, factorising)…" for ever, and a screenshot run waited its
    // 300 s out. Now it fails at once with the reason the status bar gives.
    void aTakeWithoutAMeshFailsAtOnceSayingSo() {
        const QString demo = QFileInfo(project_).absolutePath();
        const QString out = folder_ + "/never.png";
        const test::AppRun run = test::runBoneless(
            {demo + "/walker.c3d", demo + "/walker.map.json", "--screenshot", out}, folder_,
            QProcessEnvironment::systemEnvironment(), 60000);
        QVERIFY2(run.exitCode != 0, qPrintable(run.output));
        QVERIFY2(run.output.contains("walker.c3d: not solving: No mesh is loaded."),
                 qPrintable(run.output));
        QVERIFY(!QFileInfo::exists(out));
    }

    void frameOutsideTheTakeFails() {
        const test::AppRun run = test::runBoneless(
            {"--project", project_, "--frame", "600", "--screenshot", folder_ + "/never.png"},
            folder_);
        QVERIFY2(run.exitCode != 0, qPrintable(run.output));
        QVERIFY2(run.output.contains("600"), qPrintable(run.output));
    }

  private:
    QString folder_, project_;
};

QTEST_MAIN(ScreenshotTest)
#include "ScreenshotTest.moc"
