// MainWindow: opening, saving, exporting, recent files and drag and drop.
#include <QCloseEvent>
#include <QDragEnterEvent>
#include <QDropEvent>
#include <QFileDialog>
#include <QFileInfo>
#include <QInputDialog>
#include <QMenu>
#include <QMimeData>
#include <QStatusBar>
#include <QUrl>

#include "FrameDisplay.h"
#include "boneless/Error.h"
#include "boneless/MeshReader.h"
#include "boneless/ui/DemoProject.h"
#include "boneless/ui/Document.h"
#include "boneless/ui/ExportRunner.h"
#include "boneless/ui/MainWindow.h"
#include "boneless/ui/Project.h"

namespace boneless::ui {
namespace {

const QStringList kMeshSuffixes = {"obj", "ply", "off", "stl"};

enum class FileKind { Project, Mesh, Take, Correspondence, Unknown };

FileKind kindOf(const QString& path) {
    const QString suffix = QFileInfo(path).suffix().toLower();
    if (suffix == "boneless") return FileKind::Project;
    if (kMeshSuffixes.contains(suffix)) return FileKind::Mesh;
    if (suffix == "c3d") return FileKind::Take;
    if (suffix == "json") return FileKind::Correspondence;
    return FileKind::Unknown;
}

}  // namespace

bool MainWindow::openFile(const QString& path) {
    if (!QFileInfo(path).isFile()) {
        showError(tr("Cannot open %1: no such file").arg(path));
        return false;
    }
    bool ok = false;
    switch (kindOf(path)) {
        case FileKind::Project:
            return openProject(path);
        case FileKind::Mesh:
            ok = document_->loadMesh(path);
            break;
        case FileKind::Take:
            ok = document_->loadTake(path);
            break;
        case FileKind::Correspondence:
            ok = document_->loadCorrespondence(path);
            break;
        case FileKind::Unknown:
            showError(tr("Cannot open %1: not a project (.boneless), mesh (.obj, .ply, .off, "
                         ".stl), take (.c3d) or correspondence (.json)")
                          .arg(path));
            return false;
    }
    // The document has already reported a failure through errorOccurred.
    if (ok) {
        RecentFiles::add(QFileInfo(path).absoluteFilePath());
        statusBar()->showMessage(tr("Opened %1").arg(QFileInfo(path).fileName()), 5000);
    }
    return ok;
}

bool MainWindow::openProject(const QString& path) {
    QString error;
    if (!Project::load(*document_, path, &error)) {
        showError(error.isEmpty() ? tr("Cannot open the project %1").arg(path) : error);
        return false;
    }
    projectPath_ = QFileInfo(path).absoluteFilePath();
    autosave_->setProjectPath(projectPath_);
    RecentFiles::add(projectPath_);
    applyViewSettings();
    updateTitle();
    statusBar()->showMessage(tr("Opened %1").arg(QFileInfo(path).fileName()), 5000);
    return true;
}

bool MainWindow::openDemo() {
    QString error;
    const QString path = DemoProject::ensure({}, &error);
    if (path.isEmpty()) {
        showError(error.isEmpty() ? tr("Cannot write the demo project") : error);
        return false;
    }
    return openProject(path);
}

bool MainWindow::saveProject() {
    if (projectPath_.isEmpty()) {
        chooseSaveProjectAs();
        return !projectPath_.isEmpty();
    }
    return saveProjectAs(projectPath_);
}

bool MainWindow::saveProjectAs(const QString& path) {
    QString error;
    if (!Project::save(*document_, path, &error)) {
        showError(error.isEmpty() ? tr("Cannot save the project %1").arg(path) : error);
        return false;
    }
    projectPath_ = QFileInfo(path).absoluteFilePath();
    autosave_->setProjectPath(projectPath_);
    RecentFiles::add(projectPath_);
    updateTitle();
    statusBar()->showMessage(tr("Saved %1").arg(QFileInfo(path).fileName()), 5000);
    return true;
}

bool MainWindow::exportTo(const QString& folder, bool pointCache) {
    QString why;
    if (!document_->canSolve(&why)) {
        showError(tr("Nothing to export: %1").arg(why));
        return false;
    }
    const ExportRequest request = document_->exportRequest(
        folder, pointCache ? ExportFormat::Pc2 : ExportFormat::Obj);
    QString error;
    if (!exporter_->start(*document_, request, &error)) {
        showError(error);
        return false;
    }
    statusBar()->showMessage(tr("Exporting to %1…").arg(folder));
    return true;
}

void MainWindow::chooseMesh() {
    const QString path = QFileDialog::getOpenFileName(
        this, tr("Open Mesh"), {}, tr("Meshes (*.obj *.ply *.off *.stl);;All files (*)"));
    if (path.isEmpty()) return;
    QString group;
    try {
        const std::vector<std::string> groups = objGroups(path.toStdString());
        if (groups.size() > 1) {
            QStringList items{tr("(whole file)")};
            for (const std::string& g : groups) items << QString::fromStdString(g);
            bool ok = false;
            const QString chosen = QInputDialog::getItem(
                this, tr("Open Mesh"), tr("The file has groups. Animate:"), items, 0, false, &ok);
            if (!ok) return;
            if (chosen != items.front()) group = chosen;
        }
    } catch (const Error& e) {
        showError(QString::fromStdString(e.what()));
        return;
    }
    if (document_->loadMesh(path, group)) RecentFiles::add(path);
}

void MainWindow::chooseTake() {
    const QString path = QFileDialog::getOpenFileName(this, tr("Open Take"), {},
                                                      tr("C3D takes (*.c3d);;All files (*)"));
    if (!path.isEmpty()) openFile(path);
}

void MainWindow::chooseCorrespondence() {
    const QString path = QFileDialog::getOpenFileName(
        this, tr("Open Correspondence"), {}, tr("Correspondence files (*.json);;All files (*)"));
    if (!path.isEmpty()) openFile(path);
}

void MainWindow::chooseProject() {
    const QString path = QFileDialog::getOpenFileName(
        this, tr("Open Project"), {}, tr("Boneless projects (*.boneless);;All files (*)"));
    if (!path.isEmpty()) openProject(path);
}

void MainWindow::chooseSaveProjectAs() {
    QString path = QFileDialog::getSaveFileName(this, tr("Save Project As"), projectPath_,
                                                tr("Boneless projects (*.boneless)"));
    if (path.isEmpty()) return;
    if (QFileInfo(path).suffix().isEmpty()) path += ".boneless";
    saveProjectAs(path);
}

void MainWindow::chooseSaveCorrespondence() {
    QString path = QFileDialog::getSaveFileName(this, tr("Save Correspondence As"),
                                                document_->correspondencePath(),
                                                tr("Correspondence files (*.json)"));
    if (path.isEmpty()) return;
    if (QFileInfo(path).suffix().isEmpty()) path += ".json";
    if (document_->saveCorrespondence(path))
        statusBar()->showMessage(tr("Saved %1").arg(QFileInfo(path).fileName()), 5000);
}

void MainWindow::chooseExport(bool pointCache) {
    const QString folder = QFileDialog::getExistingDirectory(
        this, pointCache ? tr("Export PC2 Into") : tr("Export OBJ Sequence Into"));
    if (!folder.isEmpty()) exportTo(folder, pointCache);
}

void MainWindow::rebuildRecentMenu() {
    recentMenu_->clear();
    const QStringList files = RecentFiles::list();
    for (const QString& path : files)
        recentMenu_->addAction(QFileInfo(path).fileName(), this, [this, path] { openFile(path); })
            ->setToolTip(path);
    if (files.isEmpty()) recentMenu_->addAction(tr("(none)"))->setEnabled(false);
    recentMenu_->addSeparator();
    recentMenu_->addAction(tr("Clear"), this, [] { RecentFiles::clear(); });
}

void MainWindow::updateTitle() {
    QString name = projectPath_.isEmpty() ? tr("untitled") : QFileInfo(projectPath_).fileName();
    if (document_->hasMesh()) name += " — " + QFileInfo(document_->meshPath()).fileName();
    setWindowTitle(tr("%1 — Boneless").arg(name));
}

void MainWindow::dragEnterEvent(QDragEnterEvent* event) {
    for (const QUrl& url : event->mimeData()->urls()) {
        if (url.isLocalFile() && kindOf(url.toLocalFile()) != FileKind::Unknown) {
            event->acceptProposedAction();
            return;
        }
    }
}

void MainWindow::dropEvent(QDropEvent* event) {
    QStringList paths;
    for (const QUrl& url : event->mimeData()->urls())
        if (url.isLocalFile()) paths << url.toLocalFile();
    // Mesh before take before map, whatever order they were dropped in: each needs the one
    // before it to be checked against.
    auto rank = [](const QString& p) { return int(kindOf(p)); };
    std::stable_sort(paths.begin(), paths.end(),
                     [&](const QString& a, const QString& b) { return rank(a) < rank(b); });
    for (const QString& path : paths) openFile(path);
    event->acceptProposedAction();
}

void MainWindow::closeEvent(QCloseEvent* event) {
    if (exporter_->isRunning()) exporter_->cancel();
    autosave_->saveNow();
    event->accept();
}

}  // namespace boneless::ui
