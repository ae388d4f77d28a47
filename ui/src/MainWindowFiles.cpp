// MainWindow: opening, saving, exporting, recent files and drag and drop.
#include <algorithm>
#include <utility>

#include <QDir>
#include <QDragEnterEvent>
#include <QDropEvent>
#include <QFile>
#include <QFileDialog>
#include <QFileInfo>
#include <QLocale>
#include <QMap>
#include <QMenu>
#include <QMessageBox>
#include <QMimeData>
#include <QPushButton>
#include <QScopedValueRollback>
#include <QStatusBar>
#include <QUndoStack>
#include <QUrl>
#include <optional>

#include "Counted.h"
#include "FrameDisplay.h"
#include "MainWindowFiles.h"
#include "boneless/Error.h"
#include "boneless/InputFile.h"
#include "boneless/MeshReader.h"
#include "boneless/ui/DemoProject.h"
#include "boneless/ui/Document.h"
#include "boneless/ui/ExportDialog.h"
#include "boneless/ui/GroupChooser.h"
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

// "walk.boneless is a directory, not a Boneless project file.": a folder, or a FIFO (whose opening
// waits for a writer for ever), refused by name as the core's loaders refuse them. Empty for a
// regular file, and for a path that cannot be looked at (opening it says why).
QString notARegularFileSentence(const QString& path, FileKind kind) {
    const char* name = kind == FileKind::Project ? "Boneless project"
                       : kind == FileKind::Mesh  ? "mesh"
                       : kind == FileKind::Take  ? "C3D"
                                                 : "correspondence";
    const std::string why = notARegularFile(path.toStdString(), name);
    if (why.empty()) return {};
    return QObject::tr("%1 %2.").arg(QFileInfo(path).fileName(), QString::fromStdString(why));
}

}  // namespace

QString MainWindow::plainError(const QString& path) const {
    const QString name = QFileInfo(path).fileName();
    switch (kindOf(path)) {
        case FileKind::Mesh:
            return tr("%1 could not be opened as a mesh.").arg(name);
        case FileKind::Take: {
            // Every C3D file has 0x50 as its second byte: without it, it is something else.
            QFile file(path);
            const QByteArray head = file.open(QIODevice::ReadOnly) ? file.read(2) : QByteArray();
            if (head.size() < 2 || head[1] != '\x50') return tr("%1 is not a C3D file.").arg(name);
            return tr("%1 is a C3D file that Boneless could not read.").arg(name);
        }
        case FileKind::Correspondence:
            return tr("%1 could not be opened as a marker correspondence for this mesh.").arg(name);
        default:
            return tr("%1 could not be opened.").arg(name);
    }
}

bool MainWindow::openFile(const QString& path) {
    if (!QFileInfo::exists(path)) {
        showError(tr("%1 does not exist.").arg(QFileInfo(path).fileName()),
                  tr("No such file: %1").arg(path));
        return false;
    }
    if (kindOf(path) != FileKind::Unknown) {  // else refused below by its extension
        if (const QString why = notARegularFileSentence(path, kindOf(path)); !why.isEmpty()) {
            showError(why, path);
            return false;
        }
    }
    // The document's own message (technical) goes under the plain sentence.
    opening_ = path;
    const auto done = qScopeGuard([this] { opening_.clear(); });
    bool ok = false;
    switch (kindOf(path)) {
        case FileKind::Project:
            return openProject(path);
        case FileKind::Mesh:
            return openMesh(path);
        case FileKind::Take: {
            if (!keepUnsavedWork(false)) return false;
            const Loading loading(this);
            ok = document_->loadTake(path);
            if (ok) startUntitled();
            break;
        }
        case FileKind::Correspondence: {
            // Read and checked first: a map that cannot be used is said so, not asked about.
            if (!document_->checkCorrespondence(path)) return false;
            Document::MapLoad mode = Document::MapLoad::Replace;
            if (!askMapLoad(path, mode)) return false;
            // Into files opened untitled and not edited since, the map is what its file holds:
            // the state opened, which undoing back to is no edit. Over edits it stays an undo
            // step back to them.
            const bool asOpened = mode == Document::MapLoad::Replace && projectPath_.isEmpty() &&
                                  !unsavedEdits_ && document_->undoStack()->isClean();
            // Otherwise it is an edit like any other, marked and autosaved: as a load, a map
            // opened into a saved project was neither, and the project kept its old map.
            std::optional<Loading> loading;
            if (asOpened) loading.emplace(this);
            int added = 0, replaced = 0;
            ok = document_->loadCorrespondence(path, mode, &added, &replaced);
            if (ok && asOpened) document_->undoStack()->setClean();
            // A merge's own message says what it did; what the file said of itself comes first.
            if (ok && mode == Document::MapLoad::Merge &&
                !document_->correspondenceNotes().isEmpty())
                break;
            if (ok && mode == Document::MapLoad::Merge && replaced > 0) {
                addRecentFile(QFileInfo(path).absoluteFilePath());
                statusBar()->showMessage(
                    counted(replaced,
                            tr("Merged %1: %2 added, and %n suggestion still to review "
                               "replaced by its mapping"),
                            tr("Merged %1: %2 added, and %n suggestions still to review "
                               "replaced by its mappings"))
                        .arg(QFileInfo(path).fileName(),
                             counted(added, tr("%n marker"), tr("%n markers"))),
                    10000);
                return true;
            }
            if (ok && mode == Document::MapLoad::Merge && added == 0) {
                addRecentFile(QFileInfo(path).absoluteFilePath());
                statusBar()->showMessage(
                    tr("Nothing merged from %1: each marker it maps is mapped already, or its "
                       "vertex is taken")
                        .arg(QFileInfo(path).fileName()),
                    10000);
                return true;
            }
            break;
        }
        case FileKind::Unknown:
            showError(tr("Boneless does not open %1 files.").arg(QFileInfo(path).suffix()),
                      tr("%1 is not a project (.boneless), mesh (.obj, .ply, .off, .stl), take "
                         "(.c3d) or correspondence (.json).")
                          .arg(path));
            return false;
    }
    // The document has already reported a failure through errorOccurred.
    if (ok) {
        addRecentFile(QFileInfo(path).absoluteFilePath());
        showOpened(path, kindOf(path) == FileKind::Take ? document_->takeNotes()
                         : kindOf(path) == FileKind::Correspondence
                             ? document_->correspondenceNotes()
                             : QStringList());
    }
    return ok;
}

void MainWindow::showOpened(const QString& path, const QStringList& notes) {
    const QString name = QFileInfo(path).fileName();
    if (notes.isEmpty()) {
        statusBar()->showMessage(tr("Opened %1").arg(name), 5000);
        return;
    }
    // A truncated take or a map cleared for another mesh changes what the user sees: said
    // where it cannot be missed, not only in a log.
    const QString message = notes.size() == 1
                                ? tr("Opened %1, with a note:").arg(name)
                                : tr("Opened %1, with %2 notes:").arg(name).arg(notes.size());
    statusBar()->showMessage(message + " " + notes.first(), 15000);
    if (!messageBoxes_) return;
    QMessageBox* box = errorBox(message, notes.join("\n"));
    box->setObjectName("openingNotes");
    box->setIcon(QMessageBox::Information);
    box->setInformativeText(notes.first());
    box->show();
}

bool MainWindow::openProject(const QString& path, const QMap<QString, QString>& located,
                             bool setMapAside) {
    // Refused before asking about the work open now: nothing would replace it.
    if (const QString why = notARegularFileSentence(path, FileKind::Project); !why.isEmpty()) {
        showError(why, path);
        return false;
    }
    if (!keepUnsavedWork(false)) return false;
    std::optional<Loading> loading(std::in_place, this);
    QString error, missing, missingFile, setAside;
    bool loaded = false;
    {
        const QScopedValueRollback<bool> quiet(loadingProject_, true);
        loaded = Project::load(*document_, path, &error, &missing, &missingFile, located,
                               setMapAside, &setAside);
    }
    if (!loaded) {
        const QString message = !missing.isEmpty()
                                    ? missing
                                    : tr("%1 could not be opened as a Boneless project.")
                                          .arg(QFileInfo(path).fileName());
        const QString recovery = ProjectAutosave::autosaveOf(path);
        statusBar()->showMessage(message, 15000);
        emit errorShown(message + "\n" + error);
        if (!messageBoxes_) return false;
        QMessageBox* box = errorBox(message, error);
        box->setObjectName("projectErrorMessage");
        if (!recovery.isEmpty()) {
            box->setInformativeText(
                tr("The file is left as it is. The last autosave, from %1, can be opened "
                   "instead.")
                    .arg(QLocale::system().toString(QFileInfo(recovery).lastModified(),
                                                    QLocale::ShortFormat)));
            QPushButton* open = box->addButton(tr("Open Last Autosave"), QMessageBox::AcceptRole);
            open->setObjectName("openRecoveryButton");
            connect(open, &QPushButton::clicked, this,
                    [this, recovery] { openRecovery(recovery); });
        }
        if (!missingFile.isEmpty()) {
            const QString offered = offerMissingFile(
                box, missingFile, located,
                [this, path](const QMap<QString, QString>& next, bool setMapAside) {
                    openProject(path, next, setMapAside);
                });
            if (recovery.isEmpty())
                box->setInformativeText(tr("The file is left as it is. %1").arg(offered));
        }
        box->show();
        return false;
    }
    projectPath_ = QFileInfo(path).absoluteFilePath();
    demo_ = DemoProject::isDemo(projectPath_);
    setUnsavedEdits(false);
    autosave_->setProjectPath(demo_ ? QString() : projectPath_);
    // The file holds what was just loaded: saving it again now would only overwrite the
    // recovery file with it (or, for the demo, with the demo).
    autosave_->discardPending();
    if (!demo_) addRecentFile(projectPath_);
    applyViewSettings();
    restoreSession();
    updateTitle();
    QStringList notes = document_->takeNotes();  // a take cut short since, as the take says
    if (!setAside.isEmpty()) notes.prepend(setAside);
    showOpened(path, notes);
    if (!located.isEmpty()) {
        // The project names the files located: an edit, marked and saved into it (once the
        // load's own autosave is dropped).
        loading.reset();
        setUnsavedEdits(true);
        autosave_->schedule();
        QStringList names;
        for (const QString& file : located) names << QFileInfo(file).fileName();
        statusBar()->showMessage(tr("Opened %1 with %2 in place of the file it named; the project "
                                    "names it from now on")
                                     .arg(QFileInfo(path).fileName(), names.join(", ")),
                                 10000);
    }
    return true;
}

QString MainWindow::offerMissingFile(
    QMessageBox* box, const QString& missingFile, const QMap<QString, QString>& located,
    const std::function<void(const QMap<QString, QString>&, bool)>& reopen) {
    // A take or mesh renamed or moved: the map that lives only in the project is reached by
    // saying where the file is now.
    QPushButton* locateButton = box->addButton(tr("Locate…"), QMessageBox::ActionRole);
    locateButton->setObjectName("locateButton");
    connect(locateButton, &QPushButton::clicked, this, [this, missingFile, located, reopen] {
        const QString chosen = locate(missingFile);
        if (chosen.isEmpty()) return;
        QMap<QString, QString> next = located;
        next[missingFile] = QFileInfo(chosen).absoluteFilePath();
        reopen(next, false);
    });
    const QString name = QFileInfo(missingFile).fileName();
    if (!QFileInfo::exists(missingFile))
        return tr("Locate… opens it with %1 where it is now.").arg(name);
    // There, but not the mesh the map was made for: the mesh is the one wanted, and the map is
    // to be made anew for it.
    QPushButton* aside = box->addButton(tr("Open Without the Map"), QMessageBox::ActionRole);
    aside->setObjectName("openWithoutMapButton");
    connect(aside, &QPushButton::clicked, this, [located, reopen] { reopen(located, true); });
    return tr("Locate… opens it with the mesh the map was made for, in place of %1; Open Without "
              "the Map opens it unmapped, the map kept.")
        .arg(name);
}

QString MainWindow::locate(const QString& file) {
    const QFileInfo missing(file);
    // Where the project said it was, or the nearest folder still there.
    QDir start = missing.absoluteDir();
    while (!start.exists() && start.cdUp()) {
    }
    QFileDialog dialog(this, tr("Locate %1").arg(missing.fileName()), start.absolutePath());
    dialog.setObjectName("locateDialog");
    dialog.setFileMode(QFileDialog::ExistingFile);
    const QString suffix = missing.suffix();
    if (!suffix.isEmpty())
        dialog.setNameFilters(
            {tr("%1 files (*.%2)").arg(suffix.toUpper(), suffix), tr("All files (*)")});
    if (dialog.exec() != QDialog::Accepted || dialog.selectedFiles().isEmpty()) return {};
    return dialog.selectedFiles().first();
}

bool MainWindow::askMapLoad(const QString& path, Document::MapLoad& mode) {
    const int mapped = document_->mappedCount();
    if (mapped == 0 || !messageBoxes_) return true;
    QMessageBox box(QMessageBox::Question, tr("Open Correspondence"),
                    counted(mapped, tr("%n marker is mapped already. Open %1:"),
                            tr("%n markers are mapped already. Open %1:"))
                        .arg(QFileInfo(path).fileName()),
                    QMessageBox::NoButton, this);
    box.setObjectName("mapLoadQuestion");
    QPushButton* replace = box.addButton(tr("Replace Them"), QMessageBox::DestructiveRole);
    QPushButton* merge = box.addButton(tr("Merge (Keep Mine)"), QMessageBox::AcceptRole);
    QPushButton* cancel = box.addButton(QMessageBox::Cancel);
    replace->setObjectName("replaceButton");
    merge->setObjectName("mergeButton");
    cancel->setObjectName("cancelButton");
    box.setDefaultButton(merge);
    box.setInformativeText(
        tr("Merge adds the file's mappings of the markers not mapped yet. "
           "Either can be undone (Ctrl+Z)."));
    box.exec();  // a question must be answered before anything is loaded
    if (box.clickedButton() == replace)
        mode = Document::MapLoad::Replace;
    else if (box.clickedButton() == merge)
        mode = Document::MapLoad::Merge;
    else
        return false;
    return true;
}

void MainWindow::startUntitled() {
    projectPath_.clear();
    demo_ = false;
    autosave_->setProjectPath({});
    updateTitle();
}

bool MainWindow::openDemo() {
    QString error;
    const QString path = DemoProject::write({}, &error);
    if (path.isEmpty()) {
        showError(tr("The demo could not be written."), error);
        return false;
    }
    return openProject(path);
}

bool MainWindow::saveProject() {
    if (projectPath_.isEmpty() || demo_) {
        chooseSaveProjectAs();
        return !projectPath_.isEmpty() && !demo_;
    }
    return saveProjectAs(projectPath_);
}

bool MainWindow::saveProjectAs(const QString& path) {
    if (DemoProject::isDemo(path)) {
        showError(tr("The demo is written afresh each time it opens: save the project elsewhere."));
        return false;
    }
    // Never over the document's own files: saved as its map, the project replaced the user's
    // correspondence file, and its autosaves went on rewriting it.
    if (const QString what = ownFileAt(path, projectPath_); !what.isEmpty()) {
        showError(tr("%1 is this project's %2 file: a project saved there would replace it. "
                     "Save the project under another name.")
                      .arg(QFileInfo(path).fileName(), what),
                  path);
        return false;
    }
    // Save into the project open: not over what another Boneless or program wrote there since.
    if (QFileInfo(path).absoluteFilePath() == projectPath_ && autosave_->projectChangedOnDisk()) {
        askChangedOnDisk(projectPath_);
        return false;
    }
    storeSession();
    QString error;
    if (!Project::save(*document_, path, &error)) {
        showError(tr("%1 could not be saved.").arg(QFileInfo(path).fileName()), error);
        return false;
    }
    projectPath_ = QFileInfo(path).absoluteFilePath();
    demo_ = false;
    document_->undoStack()->setClean();
    setUnsavedEdits(false);
    autosave_->setProjectPath(projectPath_);
    autosave_->discardPending();
    addRecentFile(projectPath_);
    updateTitle();
    statusBar()->showMessage(tr("Saved %1").arg(QFileInfo(path).fileName()), 5000);
    return true;
}

void MainWindow::askChangedOnDisk(const QString& path) {
    const QString message =
        tr("%1 changed on disk since it was opened or last saved: this window's changes are not "
           "saved into it.")
            .arg(QFileInfo(path).fileName());
    statusBar()->showMessage(message, 15000);
    emit errorShown(message + "\n" + path);
    if (!messageBoxes_) return;
    // Shown, not exec'd: an autosave finds it, in the middle of whatever the user does.
    auto* box =
        new QMessageBox(QMessageBox::Warning, tr("Boneless"), message, QMessageBox::NoButton, this);
    box->setObjectName("changedOnDiskQuestion");
    box->setAttribute(Qt::WA_DeleteOnClose);
    box->setModal(false);
    box->setInformativeText(
        tr("Another Boneless or program wrote it. Reload opens it as it is now and drops this "
           "window's changes; Save As… keeps them in another file; Overwrite replaces what it "
           "holds with them. Until then they are kept in the last autosave only."));
    box->setDetailedText(path);
    QPushButton* reload = box->addButton(tr("Reload"), QMessageBox::DestructiveRole);
    QPushButton* saveAs = box->addButton(tr("Save As…"), QMessageBox::AcceptRole);
    QPushButton* overwrite = box->addButton(tr("Overwrite"), QMessageBox::DestructiveRole);
    reload->setObjectName("reloadButton");
    saveAs->setObjectName("saveAsButton");
    overwrite->setObjectName("overwriteButton");
    box->setDefaultButton(saveAs);
    connect(reload, &QPushButton::clicked, this, [this, path] {
        if (path != projectPath_) return;  // another project opened since
        autosave_->discardPending();
        setUnsavedEdits(false);
        const QScopedValueRollback<bool> asked(workAsked_, true);  // the answer was Reload
        openProject(path);
    });
    connect(saveAs, &QPushButton::clicked, this, [this] { chooseSaveProjectAs(); });
    connect(overwrite, &QPushButton::clicked, this, [this, path] {
        if (path != projectPath_) return;
        storeSession();
        if (autosave_->overwriteProject()) {
            document_->undoStack()->setClean();
            setUnsavedEdits(false);
        }
    });
    box->show();
}

void MainWindow::showExportDialog() {
    QString why, detail;
    if (!document_->canSolve(&why, &detail)) {
        showError(tr("Nothing to export: %1").arg(why), detail);
        return;
    }
    exportDialog_->setProjectPath(demo_ ? QString() : projectPath_);
    exportDialog_->show();
    exportDialog_->raise();
}

void MainWindow::chooseMesh() {
    const QString path = QFileDialog::getOpenFileName(
        this, tr("Open Mesh"), {}, tr("Meshes (*.obj *.ply *.off *.stl);;All files (*)"));
    // A take or project chosen here (All files) opens as what it is, not as a broken mesh.
    if (!path.isEmpty()) kindOf(path) == FileKind::Unknown ? openMesh(path) : openFile(path);
}

// An OBJ with groups asks which to open (the largest preselected), however it was opened, unless
// --group named it. A run without message boxes (--screenshot) cannot ask: it says how to name it.
bool MainWindow::openMesh(const QString& path) {
    if (!keepUnsavedWork(false)) return false;
    QString group;
    try {
        const std::vector<ObjGroup> groups = objGroups(path.toStdString());
        QStringList names;
        for (const ObjGroup& g : groups) names << QString::fromStdString(g.name);
        const QString name = QFileInfo(path).fileName();
        if (!startGroup_.isEmpty()) {
            if (!names.contains(startGroup_)) {
                showError(
                    tr("%1 has no group named %2.").arg(name, startGroup_),
                    tr("Its groups: %1").arg(names.isEmpty() ? tr("none") : names.join(", ")));
                return false;
            }
            group = startGroup_;
        } else if (groups.size() > 1 && !messageBoxes_) {
            showError(tr("%1 has %2 groups: name one with --group.").arg(name).arg(groups.size()),
                      tr("Its groups: %1").arg(names.join(", ")));
            return false;
        } else if (groups.size() > 1) {
            GroupChooser chooser(name, groups, this);
            if (chooser.exec() != QDialog::Accepted) return false;
            group = chooser.group();
        }
    } catch (const Error& e) {
        showError(plainError(path), QString::fromStdString(e.what()));
        return false;
    }
    opening_ = path;
    const auto done = qScopeGuard([this] { opening_.clear(); });
    const Loading loading(this);
    if (!document_->loadMesh(path, group)) return false;
    startUntitled();  // never into the project (or demo) open before
    addRecentFile(QFileInfo(path).absoluteFilePath());
    showOpened(path, document_->meshWarnings());
    return true;
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
    if (!path.isEmpty()) kindOf(path) == FileKind::Unknown ? openProject(path) : openFile(path);
}

bool MainWindow::chooseSaveProjectAs() {
    // A project is a .boneless, whatever was typed: walker.map.json was taken as it was, and the
    // project written over the map. So the name saved to, not the one typed, is asked about.
    QString path = QFileDialog::getSaveFileName(
        this, tr("Save Project As"), demo_ ? QString() : projectPath_,
        tr("Boneless projects (*.boneless)"), nullptr, QFileDialog::DontConfirmOverwrite);
    if (path.isEmpty()) return false;
    if (QFileInfo(path).suffix().compare("boneless", Qt::CaseInsensitive) != 0) path += ".boneless";
    if (QFileInfo(path).absoluteFilePath() != projectPath_ &&
        !askToReplace(tr("Save Project As"), path))
        return false;
    return saveProjectAs(path);
}

bool MainWindow::askToReplace(const QString& title, const QString& path) {
    if (!messageBoxes_ || !QFileInfo::exists(path)) return true;
    QMessageBox box(QMessageBox::Question, title,
                    tr("%1 already exists. Replace it?").arg(QFileInfo(path).fileName()),
                    QMessageBox::Yes | QMessageBox::No, this);
    box.setObjectName("replaceQuestion");
    box.setDefaultButton(QMessageBox::No);
    return box.exec() == QMessageBox::Yes;
}

void MainWindow::chooseSaveCorrespondence() {
    // As a project: the name saved to is the one asked about (walker typed, walker.json replaced
    // unasked), it is a .json that Open Correspondence opens (walker.map was refused), and it is
    // none of the document's other files.
    QString path = QFileDialog::getSaveFileName(
        this, tr("Save Correspondence As"), document_->correspondencePath(),
        tr("Correspondence files (*.json)"), nullptr, QFileDialog::DontConfirmOverwrite);
    if (path.isEmpty()) return;
    if (QFileInfo(path).suffix().compare("json", Qt::CaseInsensitive) != 0) path += ".json";
    if (saveCorrespondenceAs(path))
        statusBar()->showMessage(tr("Saved %1").arg(QFileInfo(path).fileName()), 5000);
}

QString MainWindow::ownFileAt(const QString& path, const QString& except) const {
    const QString target = QFileInfo(path).canonicalFilePath();
    if (target.isEmpty() || (!except.isEmpty() && QFileInfo(except).canonicalFilePath() == target))
        return {};
    const std::pair<QString, QString> own[] = {
        {document_->meshPath(), tr("mesh")},
        {document_->takePath(), tr("take")},
        {document_->correspondencePath(), tr("correspondence")},
        {projectPath_, tr("project")}};
    for (const auto& [file, what] : own)
        if (!file.isEmpty() && QFileInfo(file).canonicalFilePath() == target) return what;
    return {};
}

bool MainWindow::saveCorrespondenceAs(const QString& path) {
    if (const QString what = ownFileAt(path, document_->correspondencePath()); !what.isEmpty()) {
        showError(tr("%1 is this document's %2 file: a correspondence saved there would replace "
                     "it. Save the correspondence under another name.")
                      .arg(QFileInfo(path).fileName(), what),
                  path);
        return false;
    }
    const QString own = document_->correspondencePath();
    if ((own.isEmpty() ||
         QFileInfo(own).absoluteFilePath() != QFileInfo(path).absoluteFilePath()) &&
        !askToReplace(tr("Save Correspondence As"), path))
        return false;
    return document_->saveCorrespondence(path);
}

void MainWindow::setRecordsSession(bool records) {
    recordsSession_ = records;
    autosave_->setEnabled(records);
}

void MainWindow::addRecentFile(const QString& path) {
    if (recordsSession_) RecentFiles::add(path);
}

void MainWindow::rebuildRecentMenu() {
    recentMenu_->clear();
    // Each file's full path is its tooltip; a name two entries share also names its folder, or
    // two p1.boneless of different folders read alike.
    recentMenu_->setToolTipsVisible(true);
    const QStringList files = RecentFiles::list();
    QMap<QString, int> named;
    for (const QString& path : files) ++named[QFileInfo(path).fileName()];
    for (const QString& path : files) {
        const QFileInfo file(path);
        const QString text =
            named[file.fileName()] > 1
                ? tr("%1 — %2").arg(file.fileName(), QDir::toNativeSeparators(file.absolutePath()))
                : file.fileName();
        // An & in a menu item marks its Alt key: "walk & run.boneless" read "walk  run.boneless".
        recentMenu_
            ->addAction(QString(text).replace('&', "&&"), this, [this, path] { openFile(path); })
            ->setToolTip(QDir::toNativeSeparators(path));
    }
    if (files.isEmpty()) recentMenu_->addAction(tr("(none)"))->setEnabled(false);
    recentMenu_->addSeparator();
    // After a crash the last session, titled or not, is here until the next one changes something.
    const QString path = ProjectAutosave::lastAutosave();
    const QFileInfo recovery(path);
    QAction* last = recentMenu_->addAction(tr("Last Autosave"), this, [this, path] {
        // Another Boneless's work replaces this session's: asked first, as any file opened is.
        if (path == ProjectAutosave::recoveryPath() || keepUnsavedWork(false)) openRecovery(path);
    });
    last->setObjectName("openLastAutosave");
    last->setEnabled(!path.isEmpty() && recovery.exists());
    if (last->isEnabled()) {
        last->setText(
            tr("Last Autosave (%1)")
                .arg(QLocale::system().toString(recovery.lastModified(), QLocale::ShortFormat)));
        last->setToolTip(recovery.absoluteFilePath());
    }
    recentMenu_->addAction(tr("Clear"), this, [] { RecentFiles::clear(); });
}

void MainWindow::updateTitle() {
    QString name = projectPath_.isEmpty() ? tr("untitled")
                   : demo_                ? tr("demo (Save As to keep changes)")
                                          : QFileInfo(projectPath_).fileName();
    // The project's mark ([*]), not the mesh's: it shows while the edits are in no project file
    // (setUnsavedEdits).
    name += "[*]";
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
    openFiles(paths);
    event->acceptProposedAction();
}

bool MainWindow::openFiles(QStringList paths) {
    // Mesh before take before map, whatever order they came in: each needs the one before it to
    // be checked against.
    auto rank = [](const QString& p) { return int(kindOf(p)); };
    std::stable_sort(paths.begin(), paths.end(),
                     [&](const QString& a, const QString& b) { return rank(a) < rank(b); });
    // One question for them all, not one for the mesh and another for the take.
    const bool replaces = std::any_of(paths.begin(), paths.end(), [](const QString& p) {
        return kindOf(p) == FileKind::Project || kindOf(p) == FileKind::Mesh ||
               kindOf(p) == FileKind::Take;
    });
    if (replaces && !keepUnsavedWork(false)) return false;
    const QScopedValueRollback<bool> asked(workAsked_, true);
    bool opened = true;
    for (const QString& path : paths) opened = openFile(path) && opened;
    return opened;
}

}  // namespace boneless::ui
