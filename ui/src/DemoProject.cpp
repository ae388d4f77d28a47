#include "boneless/ui/DemoProject.h"

#include <QDir>
#include <QFileInfo>
#include <QStandardPaths>

#include "boneless/DemoFiles.h"
#include "boneless/ui/Document.h"
#include "boneless/ui/Project.h"

namespace boneless::ui::DemoProject {

QString defaultFolder() {
    return QStandardPaths::writableLocation(QStandardPaths::AppDataLocation) + "/demo";
}

bool isDemo(const QString& path) {
    return !path.isEmpty() && QFileInfo(path).absoluteFilePath() ==
                                  QDir(defaultFolder()).absoluteFilePath("demo.boneless");
}

QString write(const QString& folder, QString* error) {
    const QDir dir(folder.isEmpty() ? defaultFolder() : folder);
    const QString project = dir.absoluteFilePath("demo.boneless");
    const QString mesh = dir.absoluteFilePath("walker.obj");
    const QString take = dir.absoluteFilePath("walker.c3d");
    const QString map = dir.absoluteFilePath("walker.map.json");
    try {
        // No true motion: the application has no use for it, and it is the bulk of the files.
        writeDemoFiles(dir.absolutePath().toStdString(), 60, 10.0, /*withTruth=*/false, 1,
                       DemoSubject::Walker);
    } catch (const std::exception& e) {
        if (error) *error = QString::fromStdString(e.what());
        return {};
    }
    Document document;
    if (!document.loadMesh(mesh) || !document.loadTake(take) || !document.loadCorrespondence(map)) {
        if (error) *error = document.lastError();
        return {};
    }
    if (!Project::save(document, project, error)) return {};
    return project;
}

}  // namespace boneless::ui::DemoProject
