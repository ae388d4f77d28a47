#include <QCoreApplication>
#include <QDir>
#include <QFileInfo>
#include <QSettings>
#include <QStandardPaths>
#include <QTimer>
#include <QUuid>

#include "boneless/Process.h"
#include "boneless/ui/Document.h"
#include "boneless/ui/Project.h"

namespace boneless::ui {

ProjectAutosave::ProjectAutosave(Document* document, QObject* parent)
    : QObject(parent),
      document_(document),
      // The process too: a session whose process still runs (a second window) has not crashed.
      session_(QUuid::createUuid().toString() + " " +
               QString::number(QCoreApplication::applicationPid())),
      timer_(new QTimer(this)) {
    timer_->setSingleShot(true);
    timer_->setInterval(1000);
    connect(timer_, &QTimer::timeout, this, &ProjectAutosave::saveNow);
    connect(document, &Document::changed, this, [this] {
        pending_ = true;
        timer_->start();  // restarts: a burst of edits is one save
    });
}

ProjectAutosave::~ProjectAutosave() {
    saveNow();
}

void ProjectAutosave::setProjectPath(const QString& path) {
    path_ = path;
}

void ProjectAutosave::setDelay(int ms) {
    timer_->setInterval(std::max(0, ms));
}

bool ProjectAutosave::isPending() const {
    return pending_;
}

void ProjectAutosave::discardPending() {
    timer_->stop();
    pending_ = false;
}

QString ProjectAutosave::recoveryPath() {
    return QStandardPaths::writableLocation(QStandardPaths::AppDataLocation) + "/recovery.boneless";
}

namespace {
const char* kRecoveredProjectKey = "autosave/recoveredProject";
// The session whose work the recovery file holds and no project file does; removed when that
// session ends cleanly or its work is reopened elsewhere or discarded.
const char* kSessionKey = "autosave/unfinishedSession";

QString recoverySession() {
    return QFileInfo::exists(ProjectAutosave::recoveryPath())
               ? QSettings().value(kSessionKey).toString()
               : QString();
}
}  // namespace

QString ProjectAutosave::recoveredProject() {
    return QSettings().value(kRecoveredProjectKey).toString();
}

bool ProjectAutosave::hasUnfinishedRecovery() const {
    const QString session = recoverySession();
    if (session.isEmpty() || session == session_) return false;
    // Another of this process's sessions is a window that is gone (the app has one at a time);
    // another running Boneless's is live work, which it keeps saving: the recovery file then holds
    // whichever saved last, as it always did.
    const qint64 pid = session.section(' ', 1).toLongLong();
    return pid == QCoreApplication::applicationPid() || processIsGone(pid);
}

void ProjectAutosave::claimRecovery() {
    QSettings().setValue(kSessionKey, session_);
}

void ProjectAutosave::discardRecovery() {
    QSettings().remove(kSessionKey);
}

void ProjectAutosave::endSession() {
    if (QSettings().value(kSessionKey).toString() == session_) QSettings().remove(kSessionKey);
}

bool ProjectAutosave::saveNow() {
    timer_->stop();
    if (!pending_ || !document_) return true;
    pending_ = false;
    // An empty untitled session has nothing worth recovering.
    if (path_.isEmpty() && !document_->hasMesh() && !document_->hasTake()) return true;
    emit aboutToSave();  // the window stores its session; that change is this save's
    timer_->stop();
    pending_ = false;
    // The recovery file holds the last session saved, titled or not: it is what the window
    // offers when a project file will not open, or at start after a crash. Another session's
    // work there, not yet reopened or discarded, is not written over (the demo opened after a
    // crash did, at its first edit).
    // Every target is tried: a project that cannot be written (a read-only folder, a full
    // disk) must not keep the edits out of the recovery file too.
    QStringList targets;
    if (!hasUnfinishedRecovery()) targets << recoveryPath();
    if (!path_.isEmpty()) targets.prepend(path_);
    if (targets.isEmpty()) {
        pending_ = true;  // kept for a save once that work is reopened or discarded
        // Said once: an untitled session left unsaved must know (a second Boneless running
        // when the first crashed, or a crash's work that would not reopen).
        if (!heldBackSaid_)
            emit failed(
                tr("Edits are not autosaved: the recovery file holds the work of a "
                   "Boneless that did not close (File → Recent Files → Last Autosave). "
                   "Save this project to keep them."));
        heldBackSaid_ = true;
        return false;
    }
    QStringList errors;
    bool kept = true, recovered = targets.contains(recoveryPath());
    for (const QString& target : targets) {
        QDir().mkpath(QFileInfo(target).absolutePath());
        QString error;
        const bool ok = Project::save(*document_, target, &error);
        if (!ok) errors << error;
        (target == path_ ? kept : recovered) = ok;
    }
    // Which project the recovery file holds: offered for another one, it would pass for it.
    if (path_.isEmpty()) kept = recovered;
    if (recovered) {
        QSettings().setValue(kRecoveredProjectKey, path_);
        // Only work that no project file holds is offered after a crash.
        if (kept && !path_.isEmpty())
            endSession();
        else
            claimRecovery();
    }
    if (!errors.isEmpty()) {
        pending_ = true;  // try again after the next change
        if (!kept && recovered)
            errors << tr("The changes are kept in the last autosave, %1.").arg(recoveryPath());
        emit failed(errors.join("\n"));
        return kept;
    }
    emit saved(targets.front());
    return true;
}

namespace RecentFiles {

namespace {
constexpr int kMax = 10;
const char* kKey = "recentFiles";
}  // namespace

QStringList list() {
    QStringList files = QSettings().value(kKey).toStringList();
    files.erase(std::remove_if(files.begin(), files.end(),
                               [](const QString& f) { return !QFileInfo::exists(f); }),
                files.end());
    return files;
}

void add(const QString& path) {
    const QString absolute = QFileInfo(path).absoluteFilePath();
    QStringList files = list();
    files.removeAll(absolute);
    files.prepend(absolute);
    while (files.size() > kMax) files.removeLast();
    QSettings().setValue(kKey, files);
}

void remove(const QString& path) {
    QStringList files = list();
    files.removeAll(QFileInfo(path).absoluteFilePath());
    QSettings().setValue(kKey, files);
}

void clear() {
    QSettings().remove(kKey);
}

}  // namespace RecentFiles

}  // namespace boneless::ui
