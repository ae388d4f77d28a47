// MainWindow: closing, the termination signals, and the unsaved work both ask about.
#include <utility>

#include <QCloseEvent>
#include <QCoreApplication>
#include <QFileInfo>
#include <QMessageBox>
#include <QPushButton>
#include <QScopedValueRollback>
#include <QSocketNotifier>
#include <cerrno>

#include <fcntl.h>
#include <signal.h>
#include <unistd.h>

#include "boneless/ui/Document.h"
#include "boneless/ui/ExportDialog.h"
#include "boneless/ui/MainWindow.h"
#include "boneless/ui/Project.h"

namespace boneless::ui {
namespace {

// The signal handler's end of a pipe the event loop reads (the self-pipe): a handler may do little
// more than write(), and the saving is done by the window, between events.
int signalPipe[2] = {-1, -1};

void onTerminationSignal(int signal) {
    const int saved = errno;
    const char byte = char(signal);
    (void)!::write(signalPipe[1], &byte, 1);
    errno = saved;
}

}  // namespace

void MainWindow::closeEvent(QCloseEvent* event) {
    // A running export is work as unsaved edits are: asked about first, by how far it got, and
    // stopped only once neither question keeps the window open.
    bool exportAsked = true;
    if (messageBoxes_) {
        const QScopedValueRollback<bool> asking(asking_, true);
        exportAsked = exportDialog_->mayCloseApp(this);
    }
    if (!exportAsked || !keepUnsavedWork(true)) {
        for (const auto& [message, detail] : std::exchange(heldErrors_, {}))
            errorBox(message, detail)->show();
        event->ignore();  // and an export running goes on
        return;
    }
    exportDialog_->cancelExport();
    stopSuggesting();
    autosave_->endSession();  // closed, not crashed: nothing to offer at the next start
    event->accept();
}

void MainWindow::quitOnTerminationSignals() {
    if (signalPipe[0] < 0 && ::pipe2(signalPipe, O_CLOEXEC | O_NONBLOCK) != 0) return;
    delete findChild<QSocketNotifier*>("terminationSignals");
    auto* notifier = new QSocketNotifier(signalPipe[0], QSocketNotifier::Read, this);
    notifier->setObjectName("terminationSignals");
    connect(notifier, &QSocketNotifier::activated, this, [this] {
        char byte = 0;
        bool signalled = false;
        while (::read(signalPipe[0], &byte, 1) > 0) signalled = true;
        if (signalled) endForSignal();
    });
    struct sigaction action = {};
    action.sa_handler = onTerminationSignal;
    sigemptyset(&action.sa_mask);
    action.sa_flags = SA_RESTART;
    for (const int signal : {SIGTERM, SIGHUP, SIGINT}) ::sigaction(signal, &action, nullptr);
}

void MainWindow::endForSignal() {
    messageBoxes_ = false;  // nobody may be there to answer (a logout, a shutdown)
    if (!demo_) storeSession();
    const bool kept = autosave_->saveNow();
    const bool titled = !projectPath_.isEmpty() && !demo_;
    // Kept where it belongs, the session ends as a close ends it; otherwise its work is offered at
    // the next start.
    if (titled ? kept : !unsavedEdits_) autosave_->endSession();
    exportDialog_->cancelExport();
    stopSuggesting();
    endedBySignal_ = true;
    // Not quit(): Qt 6's asks each window to close, and a box without an escape button (the
    // changed-on-disk question) refused, so the app stayed until killed; nor did it end a box
    // exec'd before app.exec() (the recovery question). exit() ends every running event loop.
    QCoreApplication::exit(0);
}

bool MainWindow::keepUnsavedWork(bool closing) {
    if (workAsked_) return true;
    // The frame, speed and camera only count as a change when the project is left, closed or for
    // another file; the demo's never do. Opening another project lost them.
    if (!demo_) storeSession();
    // The edits of the last second go to the project (or recovery file) they were made in.
    const bool kept = autosave_->saveNow();
    const bool titled = !projectPath_.isEmpty() && !demo_;
    if (!messageBoxes_ || (titled ? kept : !unsavedEdits_)) return true;
    const QString question =
        titled && autosave_->projectChangedOnDisk()
            ? tr("%1 changed on disk since it was opened or last saved, and holds none of these "
                 "changes. Save them elsewhere first?")
                  .arg(QFileInfo(projectPath_).fileName())
        : titled ? tr("%1 could not be saved. Save the project elsewhere first?")
                       .arg(QFileInfo(projectPath_).fileName())
        : demo_ ? tr("Save your changes to the demo as a project first?")
                : tr("Save this untitled project first?");
    QMessageBox box(QMessageBox::Question, closing ? tr("Close Boneless") : tr("Open"), question,
                    QMessageBox::NoButton, this);
    box.setObjectName("unsavedQuestion");
    box.setInformativeText(
        tr("Otherwise the changes are kept only in the last autosave, which the next change "
           "replaces."));
    QPushButton* saveAs = box.addButton(tr("Save As…"), QMessageBox::AcceptRole);
    QPushButton* discard =
        box.addButton(closing ? tr("Close Without Saving") : tr("Open Without Saving"),
                      QMessageBox::DestructiveRole);
    QPushButton* cancel = box.addButton(QMessageBox::Cancel);
    saveAs->setObjectName("saveAsButton");
    discard->setObjectName("discardButton");
    cancel->setObjectName("cancelButton");
    box.setDefaultButton(saveAs);
    asking_ = true;
    box.exec();  // nothing closes or opens before this is answered
    const bool goOn =
        box.clickedButton() == discard || (box.clickedButton() == saveAs && chooseSaveProjectAs());
    asking_ = false;
    if (!closing && box.clickedButton() == discard) {
        // Not saved, so not kept: the file opens into the session as it was opened or saved, and
        // nothing is left to ask about. Kept, the edited map went on with a take opened, and
        // closing asked about it again. The last autosave keeps the edits, as the question says.
        document_->discardEdits(tr("Open Without Saving"));
        setUnsavedEdits(false);
        autosave_->discardPending();
    }
    for (const auto& [message, detail] : std::exchange(heldErrors_, {}))
        if (!goOn) errorBox(message, detail)->show();
    return goOn;
}

}  // namespace boneless::ui
