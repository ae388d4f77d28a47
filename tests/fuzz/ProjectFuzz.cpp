// libFuzzer target for the app's `.boneless` project loader (Project::load). Any bytes must load
// or fail with a message; what loads must save and load back as the same project.
//
// The inputs are project files in a folder that also holds the demo's files and a few more, so
// that the paths a seed names resolve and the loader goes on to the mesh, take and map.

#include <QCoreApplication>
#include <QDir>
#include <QFile>
#include <cstdlib>
#include <string>

#include "FuzzFile.h"
#include "FuzzSeeds.h"
#include "boneless/DemoFiles.h"
#include "boneless/ui/DemoProject.h"
#include "boneless/ui/Document.h"
#include "boneless/ui/Project.h"

namespace {

using namespace boneless;
using namespace boneless::ui;

void require(bool ok) {
    if (!ok) std::abort();  // the harness, not the loader, failed
}

// Writes the files the seeds name into `folder`, and when `seeds` is set, the seeds themselves:
// projects saved by Project::save in `folder` from real sessions (the demo's, an edited one, a
// mesh with its map but no take, an empty session), then copied to `seeds`.
void writeProjects(const QString& folder, const QString& seeds) {
    const QString demo = DemoProject::write(folder);
    require(!demo.isEmpty());
    writeDemoFiles((folder + "/creature").toStdString(), 10, 10.0, false, 1, DemoSubject::Creature);
    if (seeds.isEmpty()) return;
    QDir().mkpath(seeds);
    const auto keep = [&](const Document& document, const QString& name) {
        require(Project::save(document, folder + "/" + name));
        QFile::remove(seeds + "/" + name);
        require(QFile::copy(folder + "/" + name, seeds + "/" + name));
    };
    QFile::remove(seeds + "/demo.boneless");
    require(QFile::copy(demo, seeds + "/demo.boneless"));

    Document edited;
    require(edited.loadMesh(folder + "/walker.obj") && edited.loadTake(folder + "/walker.c3d") &&
            edited.loadCorrespondence(folder + "/walker.map.json"));
    require(edited.align(5) && edited.clearMapping(0));
    TakeSolveOptions settings = edited.settings();
    settings.markerWeight = 3.5;
    settings.lowPassHz = 6;
    settings.fillGapSeconds = 0.25;
    settings.solver.method = SolverOptions::Method::Exact;
    settings.solver.maxIterations = 7;
    edited.setSettings(settings);
    edited.setViewSetting("labels", true);
    edited.setViewSetting("frame", 12);
    keep(edited, "edited.boneless");

    Document creature;
    require(creature.loadMesh(folder + "/creature/creature.obj") &&
            creature.loadCorrespondence(folder + "/creature/creature.map.json"));
    keep(creature, "creature.boneless");

    Document empty;
    keep(empty, "empty.boneless");
}

QString inputFolder() {
    static const QString folder = [] {
        const std::uint8_t none = 0;
        return QString::fromStdString(
            std::filesystem::path(fuzzInputFile(&none, 0, "boneless")).parent_path().string());
    }();
    return folder;
}

}  // namespace

extern "C" int LLVMFuzzerInitialize(int* argc, char*** argv) {
    static QCoreApplication app(*argc, *argv);  // Qt's file and text functions expect one
    const std::string seeds = fuzzseeds::seedDir(argc, argv);
    writeProjects(inputFolder(), QString::fromStdString(seeds));
    if (!seeds.empty()) fuzzseeds::done(seeds);
    return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const QString path = QString::fromStdString(fuzzInputFile(data, size, "boneless"));
    Document document;
    QString error;
    if (!Project::load(document, path, &error)) {
        if (!error.startsWith(path)) std::abort();  // a message naming the project file
        return 0;
    }
    const QString again = inputFolder() + "/again.boneless";
    require(Project::save(document, again));
    Document reloaded;
    if (!Project::load(reloaded, again, &error)) std::abort();
    if (Project::toJson(reloaded, again) != Project::toJson(document, again)) std::abort();
    return 0;
}
