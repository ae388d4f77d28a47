// MainWindow: a crashed session's work offered and reopened, and what opens at start.
#include <optional>

#include <QDateTime>
#include <QLocale>
#include <QMap>
#include <QMessageBox>
#include <QPushButton>
#include <QScopeGuard>
#include <QScopedValueRollback>
#include <QStatusBar>
#include <QUndoStack>

#include "MainWindowFiles.h"
#include "boneless/ui/Document.h"

namespace boneless::ui {

bool MainWindow::openRecovery(const QString& path, const QMap<QString, QString>& located,
                              bool setMapAside) {
    const QString recovery = path.isEmpty() ? ProjectAutosave::lastAutosave() : path;
    std::optional<Loading> loading(std::in_place, this);
    QString error, missing, missingFile, setAside;
    bool loaded = false;
    {
        const QScopedValueRollback<bool> quiet(loadingProject_, true);
        loaded = Project::load(*document_, recovery, &error, &missing, &missingFile, located,
                               setMapAside, &setAside);
    }
    if (!loaded) {
        // The files it names moved after the crash (a folder renamed, a copy elsewhere): the
        // sentence names the file, not the recovery file's PID-START name, and Locate… reads it
        // where it is now. The work is kept either way: offerRecovery does not give it up.
        const QString message = !missing.isEmpty() ? missing.replace(QFileInfo(recovery).fileName(),
                                                                     tr("the last autosave"))
                                                   : tr("The last autosave could not be opened.");
        if (!messageBoxes_ || asking_) {  // no box, or one held until the question is answered
            showError(message, error);
            return false;
        }
        statusBar()->showMessage(message, 15000);
        emit errorShown(message + "\n" + error);
        QMessageBox* box = errorBox(message, error);
        box->setObjectName("recoveryErrorMessage");
        QString kept = tr("The autosave is left as it is.");
        if (!missingFile.isEmpty())
            kept += " " + offerMissingFile(box, missingFile, located,
                                           [this, recovery](const QMap<QString, QString>& next,
                                                            bool setMapAside) {
                                               if (keepUnsavedWork(false))
                                                   openRecovery(recovery, next, setMapAside);
                                           });
        box->setInformativeText(kept);
        box->show();
        return false;
    }
    startUntitled();
    setUnsavedEdits(true);                 // untitled: only the autosave holds it, until Save As
    document_->undoStack()->resetClean();  // so no undo makes it look held elsewhere
    autosave_->discardPending();
    autosave_->claimRecovery(recovery);  // a crash now offers it again
    applyViewSettings();
    startFrame_ = -1;  // --frame is for the files named with it: this opens where it was left
    restoreSession();
    statusBar()->showMessage(tr("Opened the last autosave, untitled: Save As keeps it"), 10000);
    // Named as its message names it, not by the recovery file's PID-START name.
    if (!setAside.isEmpty())
        showOpened(tr("the last autosave"),
                   {setAside.replace(QFileInfo(recovery).fileName(), tr("the last autosave"))});
    if (!located.isEmpty()) {
        loading.reset();
        autosave_->schedule();  // the autosave names the files located from now on
    }
    return true;
}

bool MainWindow::offerRecovery(const QStringList& named) {
    if (!messageBoxes_) return false;
    // One question for each Boneless that did not close, its last work first.
    for (const QString& path : autosave_->unfinishedRecoveries())
        if (offerRecovery(path, named))
            return true;
        else if (endedBySignal_)
            return false;
    return false;
}

bool MainWindow::offerRecovery(const QString& path, const QStringList& named) {
    // Asked by one Boneless at a time: two both asked, and one's Discard took away the other's
    // Reopen (and its next autosave removed the file).
    if (!autosave_->hold(path)) return false;
    const QFileInfo recovery(path);
    const QString from = ProjectAutosave::recoveredProject(path);
    QMessageBox box(QMessageBox::Question, tr("Boneless"),
                    tr("Boneless did not close normally. Reopen the work it autosaved?"),
                    QMessageBox::NoButton, this);
    box.setObjectName("recoveryQuestion");
    QString holds =
        tr("The last autosave, from %1, holds %2.")
            .arg(QLocale::system().toString(recovery.lastModified(), QLocale::ShortFormat),
                 from.isEmpty() ? tr("an untitled project")
                                : tr("unsaved changes to %1").arg(QFileInfo(from).fileName()));
    if (!named.isEmpty())
        holds += " " + (named.size() == 1
                            ? tr("Reopened, it opens instead of %1, which is then not opened.")
                            : tr("Reopened, it opens instead of %1, which are then not opened."))
                           .arg(fileNames(named));
    box.setInformativeText(holds + " " +
                           tr("Discarded, it stays under File → Recent Files → Last Autosave "
                              "until the next change replaces it."));
    QPushButton* reopen = box.addButton(tr("Reopen"), QMessageBox::AcceptRole);
    QPushButton* discard = box.addButton(tr("Discard"), QMessageBox::DestructiveRole);
    reopen->setObjectName("reopenButton");
    discard->setObjectName("discardButton");
    box.setDefaultButton(reopen);
    box.exec();  // answered before anything else opens (and autosaves over it)
    if (endedBySignal_) {
        autosave_->release(path);  // unanswered: offered again at the next start
        return false;
    }
    if (box.clickedButton() == reopen) {
        if (openRecovery(path)) return true;  // held while its own
        // It would not open (openRecovery said why, and offers Locate… for a file moved since):
        // still the crash's work, offered at the next start, which no change here replaces.
        autosave_->release(path);
        return false;
    }
    // Discarded: a change may replace it.
    autosave_->discardRecovery(path);
    autosave_->release(path);
    return false;
}

bool MainWindow::openAtStart(const QString& project, const QStringList& files) {
    const auto once = qScopeGuard([this] { startGroup_.clear(); });  // not for later opens
    QStringList named = files;
    if (!project.isEmpty()) named.prepend(project);
    // A crash's work first: a file opened, or the demo edited, before the question would autosave
    // over it.
    const bool reopened = offerRecovery(named);
    if (endedBySignal_) return false;  // nothing more opens: the app is ending
    if (reopened) {
        if (!named.isEmpty())
            statusBar()->showMessage(
                tr("Opened the last autosave, untitled (Save As keeps it), instead of %1")
                    .arg(fileNames(named)),
                15000);
        return true;
    }
    bool opened = true;
    if (!project.isEmpty()) opened = openProject(project);
    if (!files.isEmpty()) opened = openFiles(files) && opened;
    if (named.isEmpty()) opened = openDemo();
    return opened;
}

}  // namespace boneless::ui
