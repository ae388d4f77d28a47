// The .boneless project: save, reload, compare; relative paths; autosave; recent files; demo.
#include <sys/resource.h>
#include <csignal>

#include <QDir>
#include <QFile>
#include <QFileInfo>
#include <QJsonArray>
#include <QJsonDocument>
#include <QJsonObject>
#include <QSignalSpy>
#include <QUndoStack>
#include <QtTest>

#include "ModelTestFixtures.h"
#include "boneless/C3dWriter.h"

using namespace boneless;
using namespace boneless::ui;

namespace {

QJsonObject readJson(const QString& path) {
    QFile f(path);
    if (!f.open(QIODevice::ReadOnly)) return {};
    return QJsonDocument::fromJson(f.readAll()).object();
}

QByteArray readAll(const QString& path) {
    QFile f(path);
    return f.open(QIODevice::ReadOnly) ? f.readAll() : QByteArray();
}

void copyFolder(const QString& from, const QString& to) {
    QDir().mkpath(to);
    for (const QFileInfo& f : QDir(from).entryInfoList(QDir::Files))
        QFile::copy(f.absoluteFilePath(), to + "/" + f.fileName());
}

}  // namespace

class ProjectTest : public QObject {
    Q_OBJECT
    QString work_, demo_;

  private slots:
    void initTestCase() {
        test::isolate("ProjectTest");
        work_ = test::freshFolder("ProjectTest");
        demo_ = work_ + "/demo";
        test::writeDemoProject(demo_);
    }

    void saveReloadCompare() {
        Document d;
        QVERIFY(test::loadDemo(d, demo_));
        // Edit everything the project stores.
        int free = 0;
        while (d.markerForVertex(free) >= 0) ++free;
        QVERIFY(d.clearMapping(2));
        QVERIFY(d.assign(2, free));
        // And one marker on a point of a face, as a click maps it (version 2).
        SurfacePoint clicked;
        for (int f = 0; f < d.mesh().faceCount() && clicked.face < 0; ++f)
            if (d.markerForVertex(d.mesh().F(f, 0)) < 0)
                clicked = SurfacePoint{d.mesh().F(f, 0), f, Vec3(0.5, 0.3, 0.2)};
        QVERIFY(d.clearMapping(3));
        QVERIFY(d.assign(3, clicked));
        QVERIFY(d.align(12));
        TakeSolveOptions settings = d.settings();
        settings.markerWeight = 42;
        settings.lowPassHz = 6;
        settings.solver.method = SolverOptions::Method::Exact;
        settings.solver.foldGuard = 0.02;
        settings.solver.orientationGuard = 50;
        settings.calibrate = CalibrateMode::None;
        d.setSettings(settings);
        d.setViewSetting("labels", true);
        d.setViewSetting("trailFrames", 8);

        const QString path = work_ + "/session/edited.boneless";
        QDir().mkpath(work_ + "/session");
        QString error;
        QVERIFY2(Project::save(d, path, &error), qPrintable(error));

        Document e;
        QVERIFY2(Project::load(e, path, &error), qPrintable(error));
        QCOMPARE(Project::toJson(e, path), Project::toJson(d, path));
        QCOMPARE(e.mappedVertex(2), free);
        QCOMPARE(e.mappedPoint(3).face, clicked.face);
        QCOMPARE(e.mappedPoint(3).barycentric, clicked.barycentric);  // exact doubles
        QCOMPARE(e.mappedVertex(3), clicked.vertex);
        QVERIFY(e.correspondenceModified());
        QVERIFY(e.alignment());
        QCOMPARE(e.alignment()->frame, 12);
        QCOMPARE(e.alignment()->takeToMesh.R, d.alignment()->takeToMesh.R);  // exact doubles
        QCOMPARE(e.alignment()->takeToMesh.t, d.alignment()->takeToMesh.t);
        QCOMPARE(e.settings().markerWeight, 42.0);
        QCOMPARE(e.settings().lowPassHz, 6.0);
        QCOMPARE(e.settings().solver.method, SolverOptions::Method::Exact);
        QCOMPARE(readJson(path)["settings"].toObject()["solver"].toString(), QString("exact"));
        QCOMPARE(e.settings().calibrate, CalibrateMode::None);
        QCOMPARE(readJson(path)["settings"].toObject()["calibrate"].toString(), QString("none"));
        QCOMPARE(e.settings().solver.foldGuard, 0.02);
        QCOMPARE(e.settings().solver.orientationGuard, 50.0);
        QCOMPARE(e.viewSettings().value("trailFrames").toInt(), 8);
        QCOMPARE(e.undoStack()->count(), 0);
        QCOMPARE(e.meshPath(), QFileInfo(demo_ + "/walker.obj").absoluteFilePath());
    }

    void pathsAreRelativeSoTheFolderCanMove() {
        const QString moved = work_ + "/moved/elsewhere";
        copyFolder(demo_, moved);
        const QJsonObject json = readJson(moved + "/demo.boneless");
        QCOMPARE(json["mesh"].toObject()["file"].toString(), QString("walker.obj"));
        QCOMPARE(json["take"].toObject()["file"].toString(), QString("walker.c3d"));
        Document d;
        QString error;
        QVERIFY2(Project::load(d, moved + "/demo.boneless", &error), qPrintable(error));
        QCOMPARE(d.takePath(), moved + "/walker.c3d");
        QVERIFY(!d.correspondenceModified());
    }

    void theDefaultMethodIsSavedAsLocalGlobal() {
        Document d;
        QVERIFY(test::loadDemo(d, demo_));
        QCOMPARE(d.settings().solver.method, SolverOptions::Method::LocalGlobal);
        const QString path = work_ + "/default-method.boneless";
        QVERIFY(Project::save(d, path));
        const QJsonObject settings = readJson(path)["settings"].toObject();
        QCOMPARE(settings["solver"].toString(), QString("local-global"));
        QVERIFY(!settings.contains("coarsest_leads"));
        QVERIFY(!settings.contains("continuation_steps"));
    }

    // Projects written before the local/global engine name a method that is gone: "direct" (the
    // default then, never chosen on purpose) or "iterative". Both open as local/global, with the
    // keys of those methods ignored; "exact" opens as exact. They name it "method", and the fold
    // guard "rigidity_weight". A method nobody wrote is refused, naming the key.
    // A project whose take was cut short since (a truncated copy) opened without a word of it,
    // and its calibration frame, now past the take's end, failed every frame. It says what the
    // take says, and calibrates automatically, as opening the take alone does.
    void aProjectWhoseTakeWasCutShortSaysSoAndCalibratesAutomatically() {
        const QString folder = work_ + "/cut-short";
        copyFolder(demo_, folder);
        const QString path = folder + "/demo.boneless";
        QJsonObject root = readJson(path);
        QJsonObject settings = root["settings"].toObject();
        settings["calibration_frame"] = 50;
        root["settings"] = settings;
        QFile project(path);
        QVERIFY(project.open(QIODevice::WriteOnly | QIODevice::Truncate));
        project.write(QJsonDocument(root).toJson());
        project.close();
        QFile take(folder + "/walker.c3d");
        QVERIFY(take.resize(take.size() / 2));
        Document d;
        QString error;
        QVERIFY2(Project::load(d, path, &error), qPrintable(error));
        QVERIFY(d.frameCount() > 0 && d.frameCount() < 50);
        QCOMPARE(d.settings().calibrationFrame, -1);
        const QString notes = d.takeNotes().join("\n");
        QVERIFY2(d.takeNotes().size() >= 2 &&
                     notes.contains(QString("The calibration frame 50 (capture frame %1) is "
                                            "past this take's")
                                        .arg(d.take().firstFrame + 50)),
                 qPrintable(notes));
    }

    // A take in metres under POINT:UNITS "mm" says how to read it right, naming the menu first;
    // read in metres (take_units), the project keeps them and reopens the take in them.
    void aTakesUnitsAreKeptInTheProjectAndItsTakeIsReadInThem() {
        Document d;
        QVERIFY(test::loadDemo(d, demo_));
        C3dTake metres = d.take();
        for (std::size_t f = 0; f < metres.samples.frames(); ++f)
            for (std::size_t k = 0; k < metres.samples.points(); ++k)
                if (const auto p = metres.samples.position(f, k)) {
                    const Eigen::Vector3d m = *p / 1000.0;
                    metres.samples.set(f, k, m.x(), m.y(), m.z());
                }
        const QString take = work_ + "/metres.c3d";
        writeC3d(metres, take.toStdString());
        QVERIFY(d.loadTake(take));
        QVERIFY2(d.takeNotes().join("\n").contains("are they in metres (") &&
                     d.takeNotes().join("\n").contains(
                         "A body spans 0.3 to 3 m: choose Edit → Take "
                         "Units → Metres (m), or set the file's POINT:UNITS to m."),
                 qPrintable(d.takeNotes().join("\n")));
        TakeSolveOptions settings = d.settings();
        settings.takeUnits = "m";
        d.setSettings(settings);
        QCOMPARE(d.take().unitToMm, 1000.0);
        QVERIFY(!d.takeNotes().join("\n").contains("its markers span"));

        const QString path = work_ + "/metres.boneless";
        QString error;
        QVERIFY2(Project::save(d, path, &error), qPrintable(error));
        QCOMPARE(readJson(path)["settings"].toObject()["take_units"].toString(), QString("m"));
        Document e;
        QVERIFY2(Project::load(e, path, &error), qPrintable(error));
        QCOMPARE(e.settings().takeUnits, std::string("m"));
        QCOMPARE(e.take().units, std::string("m"));
        QCOMPARE(e.take().unitToMm, 1000.0);
        QCOMPARE(e.take().unitsFrom, std::string(Document::kTakeUnitsFrom));
        QVERIFY2(!e.takeNotes().join("\n").contains("its markers span"),
                 qPrintable(e.takeNotes().join("\n")));
    }

    void anOldProjectOpensWithLocalGlobalUnlessItAsksForExact() {
        const QString folder = work_ + "/old-methods";
        copyFolder(demo_, folder);
        const QString path = folder + "/demo.boneless";
        const QJsonObject original = readJson(path);
        const std::pair<const char*, SolverOptions::Method> cases[] = {
            {"direct", SolverOptions::Method::LocalGlobal},
            {"iterative", SolverOptions::Method::LocalGlobal},
            {"exact", SolverOptions::Method::Exact}};
        // The demo project with these settings, loaded into d (false also when it cannot be
        // written, which the messages checked below then show).
        auto load = [&](const QJsonObject& settings, Document& d, QString& error) {
            QJsonObject root = original;
            root["settings"] = settings;
            QFile f(path);
            if (!f.open(QIODevice::WriteOnly | QIODevice::Truncate)) return false;
            f.write(QJsonDocument(root).toJson());
            f.close();
            return Project::load(d, path, &error);
        };
        for (const auto& [name, method] : cases) {
            QJsonObject settings = original["settings"].toObject();
            settings.remove("solver");
            settings.remove("fold_guard");
            settings["method"] = name;
            settings["rigidity_weight"] = 0.04;
            settings["coarsest_leads"] = true;
            settings["continuation_steps"] = 3;
            settings["marker_weight"] = 77.0;
            settings.remove("calibrate");  // from before calibration
            Document d;
            QString error;
            QVERIFY2(load(settings, d, error), qPrintable(error));
            QCOMPARE(d.settings().solver.method, method);
            QCOMPARE(d.settings().markerWeight, 77.0);  // the keys around it still read
            QCOMPARE(d.settings().solver.foldGuard, 0.04);
            QCOMPARE(d.settings().calibrate, CalibrateMode::Shape);
            // Saved again, it names its method the new way.
            QVERIFY(Project::save(d, path));
            const QJsonObject saved = readJson(path)["settings"].toObject();
            QCOMPARE(saved["solver"].toString(), QString(methodName(method)));
            QVERIFY(!saved.contains("method"));
            QCOMPARE(saved["fold_guard"].toDouble(), 0.04);
        }
        QJsonObject settings = original["settings"].toObject();
        settings["solver"] = "no-such-method";
        Document d;
        QString error;
        QVERIFY(!load(settings, d, error));
        QVERIFY2(error.contains("\"solver\" must be one of local-global, exact"),
                 qPrintable(error));
    }

    void aBrokenProjectLeavesTheDocumentAlone() {
        Document d;
        QVERIFY(test::loadDemo(d, demo_));
        QString error;

        const QString notJson = work_ + "/broken.boneless";
        QFile f(notJson);
        QVERIFY(f.open(QIODevice::WriteOnly));
        f.write("{\"format\": \"boneless-project\", ");
        f.close();
        QVERIFY(!Project::load(d, notJson, &error));
        QVERIFY(error.contains("broken.boneless"));

        // A project whose take is corrupt.
        const QString folder = work_ + "/corrupt-take";
        copyFolder(demo_, folder);
        QFile take(folder + "/walker.c3d");
        QVERIFY(take.resize(600));
        QVERIFY(!Project::load(d, folder + "/demo.boneless", &error));
        QVERIFY2(error.contains("walker.c3d"), qPrintable(error));

        QVERIFY(!Project::load(d, work_ + "/missing.boneless", &error));
        QVERIFY(!Project::save(d, work_ + "/no/such/folder/p.boneless", &error));
        QVERIFY(!error.isEmpty());

        QCOMPARE(d.takePath(), QFileInfo(demo_ + "/walker.c3d").absoluteFilePath());
        QCOMPARE(d.frameCount(), 60);
        QVERIFY(d.canSolve());
    }

    // A project edited by hand: "mesh": "walker.obj" opened without the mesh, a map pasted as
    // an array opened with the map file's markers in place of the project's, and the next save
    // wrote the project without them. A key of the wrong type is now refused by name.
    void aKeyOfTheWrongTypeIsRefusedByNameNotReadAsAbsent() {
        const QString folder = work_ + "/hand-edited";
        copyFolder(demo_, folder);
        const QString path = folder + "/demo.boneless";
        const QJsonObject original = readJson(path);
        auto with = [&](const QString& key, const QString& inner, const QJsonValue& value) {
            QJsonObject root = original;
            if (inner.isEmpty()) {
                root[key] = value;
            } else {
                QJsonObject o = root[key].toObject();
                o[inner] = value;
                root[key] = o;
            }
            return root;
        };
        QJsonObject noMeshFile = original;
        noMeshFile["mesh"] = QJsonObject{{"fiel", "walker.obj"}};
        const QJsonArray markers =
            original["correspondence"].toObject()["map"].toObject()["markers"].toArray();
        const std::pair<QJsonObject, const char*> cases[] = {
            {with("mesh", {}, "walker.obj"), "\"mesh\" is a string, not an object"},
            {with("take", {}, "walker.c3d"), "\"take\" is a string, not an object"},
            {with("mesh", "file", 5), "\"mesh\"'s \"file\" is a number, not a string"},
            {with("mesh", "group", 5), "\"mesh\"'s \"group\" is a number, not a string"},
            {noMeshFile, "\"mesh\" has no \"file\""},
            {with("correspondence", "map", markers),
             "\"correspondence\"'s \"map\" is an array, not an object"},
            {with("correspondence", {}, "walker.map.json"),
             "\"correspondence\" is a string, not an object"},
            {with("alignment", {}, "none"), "\"alignment\" is a string, not an object or null"},
            {with("settings", {}, QJsonArray()), "\"settings\" is an array, not an object"},
            {with("view", {}, 3), "\"view\" is a number, not an object"},
            {with("version", {}, "1"), "\"version\" is a string, not a number"}};
        Document d;
        QVERIFY(test::loadDemo(d, demo_));
        const int mapped = d.mappedCount();
        QVERIFY(d.clearMapping(0));
        for (const auto& [root, why] : cases) {
            QFile f(path);
            QVERIFY(f.open(QIODevice::WriteOnly | QIODevice::Truncate));
            f.write(QJsonDocument(root).toJson());
            f.close();
            QString error;
            QVERIFY2(!Project::load(d, path, &error), why);
            QVERIFY2(error.startsWith(path + ": ") && error.contains(why), qPrintable(error));
            QCOMPARE(d.mappedCount(), mapped - 1);  // the document is left as it was
        }
        // Absent keys still read as nothing there: a project of an empty session.
        QJsonObject bare{{"format", "boneless-project"}, {"version", 1}};
        QFile f(path);
        QVERIFY(f.open(QIODevice::WriteOnly | QIODevice::Truncate));
        f.write(QJsonDocument(bare).toJson());
        f.close();
        QString error;
        QVERIFY2(Project::load(d, path, &error), qPrintable(error));
        QVERIFY(!d.hasMesh() && !d.hasTake());
    }

    // A trailing comma left by a hand edit was "not JSON (object is missing after a comma at
    // byte 6322)": a text editor counts lines. It says the line and column, as a map file's does.
    void aProjectThatIsNotJsonSaysTheLineAndColumn() {
        const QString path = work_ + "/trailing-comma.boneless";
        QFile f(path);
        QVERIFY(f.open(QIODevice::WriteOnly));
        f.write("{\n  \"format\": \"boneless-project\",\n  \"version\": 1,\n}\n");
        f.close();
        Document d;
        QString error;
        QVERIFY(!Project::load(d, path, &error));
        QVERIFY2(error.startsWith(path + ": not JSON (") && error.contains("at line 4, column 2)"),
                 qPrintable(error));
    }

    void aSaveThatCannotBeWrittenLeavesTheProjectAsItWasAndSaysSo() {
        const QString folder = work_ + "/full";
        copyFolder(demo_, folder);
        const QString path = folder + "/demo.boneless";
        const QByteArray before = readAll(path);
        QVERIFY(!before.isEmpty());
        Document d;
        QVERIFY(Project::load(d, path));
        QVERIFY(d.clearMapping(0));
        // A full disk as this process sees it: a file cannot grow past 64 bytes (EFBIG).
        std::signal(SIGXFSZ, SIG_IGN);
        rlimit normal{};
        QCOMPARE(getrlimit(RLIMIT_FSIZE, &normal), 0);
        rlimit small = normal;
        small.rlim_cur = 64;
        QCOMPARE(setrlimit(RLIMIT_FSIZE, &small), 0);
        QString error;
        const bool saved = Project::save(d, path, &error);
        QCOMPARE(setrlimit(RLIMIT_FSIZE, &normal), 0);
        QVERIFY(!saved);
        QVERIFY2(error.contains("demo.boneless"), qPrintable(error));
        QCOMPARE(readAll(path), before);
        QCOMPARE(QDir(folder).entryList({"demo.boneless*"}), QStringList{"demo.boneless"});
    }

    void autosaveKeepsTheProjectCurrent() {
        const QString folder = work_ + "/autosave";
        copyFolder(demo_, folder);
        const QString path = folder + "/demo.boneless";
        Document d;
        QVERIFY(Project::load(d, path));
        ProjectAutosave autosave(&d);
        autosave.setProjectPath(path);
        autosave.setDelay(50);
        QSignalSpy saved(&autosave, &ProjectAutosave::saved);
        QVERIFY(d.clearMapping(0));
        QVERIFY(d.clearMapping(1));
        QVERIFY(autosave.isPending());
        QVERIFY(saved.wait(5000));
        QCOMPARE(saved.count(), 1);  // two edits, one save
        QVERIFY(!autosave.isPending());

        // What a crash right now would leave on disk.
        Document reopened;
        QVERIFY(Project::load(reopened, path));
        QCOMPARE(reopened.mappedCount(), 37);

        // Undo is an edit like any other.
        d.undoStack()->undo();
        QVERIFY(autosave.saveNow());
        Document again;
        QVERIFY(Project::load(again, path));
        QCOMPARE(again.mappedCount(), 38);

        // Loading is a change of the document too, but the file already holds it.
        QVERIFY(Project::load(d, path));
        QVERIFY(autosave.isPending());
        autosave.discardPending();
        QVERIFY(!autosave.isPending());
    }

    void untitledSessionsGoToTheRecoveryFile() {
        QFile::remove(ProjectAutosave::recoveryPath());
        Document d;
        ProjectAutosave autosave(&d);
        QVERIFY(d.loadMesh(demo_ + "/walker.obj"));
        QVERIFY(autosave.saveNow());
        QVERIFY(QFileInfo::exists(ProjectAutosave::recoveryPath()));
        Document recovered;
        QVERIFY(Project::load(recovered, ProjectAutosave::recoveryPath()));
        QVERIFY(recovered.hasMesh());
        QVERIFY(!recovered.hasTake());
    }

    void recentFiles() {
        RecentFiles::clear();
        QStringList files;
        for (int i = 0; i < 12; ++i) {
            files << work_ + QString("/recent%1.boneless").arg(i);
            QFile f(files.last());
            QVERIFY(f.open(QIODevice::WriteOnly));
        }
        for (const QString& f : files) RecentFiles::add(f);
        RecentFiles::add(files[5]);
        const QStringList recent = RecentFiles::list();
        QCOMPARE(recent.size(), 10);
        QCOMPARE(recent[0], files[5]);
        QCOMPARE(recent[1], files[11]);
        QVERIFY(!recent.contains(files[0]));
        QFile::remove(files[11]);
        QVERIFY(!RecentFiles::list().contains(files[11]));
        RecentFiles::remove(files[5]);
        QCOMPARE(RecentFiles::list().first(), files[10]);
    }

    void theDemoIsWrittenAsGeneratedOverAnyEdits() {
        const QString folder = work_ + "/demo-again";
        QString error;
        const QString path = DemoProject::write(folder, &error);
        QVERIFY2(!path.isEmpty(), qPrintable(error));
        // Someone's work saved over it, and its map edited.
        QFile project(path);
        QVERIFY(project.open(QIODevice::WriteOnly));
        project.write("{\"format\": \"boneless-project\", \"version\": 1}");
        project.close();
        QFile map(folder + "/walker.map.json");
        QVERIFY(map.open(QIODevice::WriteOnly));
        map.write("{}");
        map.close();
        QCOMPARE(DemoProject::write(folder), path);
        Document d;
        QVERIFY(Project::load(d, path));
        QCOMPARE(d.mappedCount(), 39);
        QVERIFY(!d.alignment());
        QVERIFY(DemoProject::defaultFolder().endsWith("/demo"));
        QVERIFY(DemoProject::isDemo(DemoProject::defaultFolder() + "/demo.boneless"));
        QVERIFY(!DemoProject::isDemo(path));
    }
};

QTEST_MAIN(ProjectTest)
#include "ProjectTest.moc"
