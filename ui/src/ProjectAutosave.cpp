#include <algorithm>

#include <QCoreApplication>
#include <QCryptographicHash>
#include <QDir>
#include <QFile>
#include <QFileInfo>
#include <QLockFile>
#include <QSettings>
#include <QStandardPaths>
#include <QTimer>
#include <QUuid>

#include "boneless/Process.h"
#include "boneless/ui/Document.h"
#include "boneless/ui/Project.h"

namespace boneless::ui {

namespace {

// This Boneless among those running: "PID-START", its process id and start time (processStartTime),
// which tells it from a later process given the same id. Names its autosave and its sessions.
QString thisInstance() {
    static const QString instance = QString("%1-%2")
                                        .arg(QCoreApplication::applicationPid())
                                        .arg(processStartTime(QCoreApplication::applicationPid()));
    return instance;
}

QString recoveryFolder() {
    return QStandardPaths::writableLocation(QStandardPaths::AppDataLocation) + "/recovery";
}

// The Boneless that wrote the autosave `path`, and whose record it keeps in the settings.
QString instanceOf(const QString& path) {
    return QFileInfo(path).completeBaseName();
}

// An autosave's record: "autosave/PID-START/project", the project it was saved from (empty for an
// untitled session), and ".../session", the session whose work it holds and no project file holds;
// removed when that session ends cleanly or its work is reopened elsewhere or discarded.
QString recordKey(const QString& path, const char* name) {
    return QString("autosave/%1/%2").arg(instanceOf(path), name);
}

QString sessionOf(const QString& path) {
    return QFileInfo::exists(path) ? QSettings().value(recordKey(path, "session")).toString()
                                   : QString();
}

bool instanceIsGone(const QString& instance) {
    // A zombie (killed a moment ago), or another process given its id since, is gone too.
    const long pid = instance.section('-', 0, 0).toLong();
    return instance != thisInstance() &&
           (pid <= 0 || processIsGone(pid, instance.section('-', 1).toULongLong()));
}

// Before each Boneless had its own, all shared one recovery file, "recovery.boneless", whose record
// was "autosave/recoveredProject" and "autosave/unfinishedSession" ("{UUID} PID"): moved into the
// folder as that session's Boneless's, so that a crash's work from then is still offered.
void moveSharedRecoveryFile() {
    const QString shared =
        QStandardPaths::writableLocation(QStandardPaths::AppDataLocation) + "/recovery.boneless";
    if (!QFileInfo::exists(shared)) return;
    QSettings settings;
    const QString session = settings.value("autosave/unfinishedSession").toString();
    const QString instance = QString("%1-0").arg(session.section(' ', 1).toLong());
    const QString moved = recoveryFolder() + "/" + instance + ".boneless";
    if (!QDir().mkpath(recoveryFolder()) || QFileInfo::exists(moved) ||
        !QFile::rename(shared, moved))
        return;
    settings.setValue("autosave/" + instance + "/project",
                      settings.value("autosave/recoveredProject"));
    if (!session.isEmpty())
        settings.setValue("autosave/" + instance + "/session",
                          session.section(' ', 0, 0) + " " + instance);
    settings.remove("autosave/recoveredProject");
    settings.remove("autosave/unfinishedSession");
}

// Another running Boneless's: its own autosave, or one whose work it reopened. Live work, which
// that Boneless keeps saving: neither offered nor written over here.
bool isAnotherRunningBonelesss(const QString& path) {
    const QString owner = instanceOf(path);
    const QString session = sessionOf(path).section(' ', 1);
    return (owner != thisInstance() && !instanceIsGone(owner)) ||
           (!session.isEmpty() && session != thisInstance() && !instanceIsGone(session));
}

// The lock file that says which session holds the recovery file `path`: "PID-START.boneless.lock".
// Its age alone never makes it stale: a Boneless may ask about a file, or hold it, for days.
std::unique_ptr<QLockFile> lockOf(const QString& path) {
    auto lock = std::make_unique<QLockFile>(path + ".lock");
    lock->setStaleLockTime(0);
    return lock;
}

// Takes `lock`, and one left by a process no longer running (a zombie too, which QLockFile counts
// as running) once its owner is gone.
bool take(QLockFile& lock) {
    if (lock.tryLock(0)) return true;
    qint64 pid = 0;
    QString host, app;
    if (lock.error() == QLockFile::LockFailedError && lock.getLockInfo(&pid, &host, &app) &&
        pid != QCoreApplication::applicationPid() && processIsGone(long(pid)) &&
        lock.removeStaleLockFile())
        return lock.tryLock(0);
    return false;
}

// A hash of what the file `path` holds; empty when it cannot be read (or is not there).
QByteArray contentHash(const QString& path) {
    QFile file(path);
    if (!file.open(QIODevice::ReadOnly)) return {};
    QCryptographicHash hash(QCryptographicHash::Sha1);
    hash.addData(&file);
    return hash.result();
}

void removeAutosave(const QString& path) {
    QFile::remove(path);
    QSettings().remove("autosave/" + instanceOf(path));
}

}  // namespace

ProjectAutosave::ProjectAutosave(Document* document, QObject* parent)
    : QObject(parent),
      document_(document),
      // The instance too: a session whose Boneless still runs (a second window) has not crashed.
      session_(QUuid::createUuid().toString() + " " + thisInstance()),
      timer_(new QTimer(this)),
      retry_(new QTimer(this)),
      markTimer_(new QTimer(this)) {
    retry_->setSingleShot(true);
    retry_->setInterval(10000);
    connect(retry_, &QTimer::timeout, this, &ProjectAutosave::saveNow);
    markTimer_->setSingleShot(true);
    markTimer_->setInterval(0);
    connect(markTimer_, &QTimer::timeout, this, &ProjectAutosave::markUnfinished);
    timer_->setSingleShot(true);
    timer_->setInterval(1000);
    connect(timer_, &QTimer::timeout, this, &ProjectAutosave::saveNow);
    connect(document, &Document::changed, this, &ProjectAutosave::schedule);
}

void ProjectAutosave::schedule() {
    if (!enabled_) return;
    pending_ = true;
    timer_->start();  // restarts: a burst of edits is one save
    if (!path_.isEmpty() && !markedUnfinished_) markTimer_->start();
}

void ProjectAutosave::markUnfinished() {
    // A load's change is dropped (discardPending) before this runs: only an edit gets here.
    if (!pending_ || path_.isEmpty() || !document_ || markedUnfinished_) return;
    const QString own = recoveryPath();
    const QString session = sessionOf(own);
    // Offered already (a save that failed), or another session's work, not written over.
    if (session == session_ || sessionIsGone(session)) return;
    // The recovery file holds this project's last autosave, or now this edit.
    if (!QFileInfo::exists(own) || recoveredProject(own) != path_) {
        QDir().mkpath(recoveryFolder());
        if (!Project::save(*document_, own)) return;
        QSettings().setValue(recordKey(own, "project"), path_);
    }
    QSettings().setValue(recordKey(own, "session"), session_);
    markedUnfinished_ = true;
}

ProjectAutosave::~ProjectAutosave() {
    saveNow();
}

bool ProjectAutosave::hold(const QString& path) {
    if (held_.count(path)) return true;
    std::unique_ptr<QLockFile> lock = lockOf(path);
    // A folder that takes no lock file (read-only) leaves the file to whoever asks, as before.
    if (!take(*lock)) return lock->error() != QLockFile::LockFailedError;
    held_[path] = std::move(lock);
    return true;
}

void ProjectAutosave::release(const QString& path) {
    held_.erase(path);  // the lock file goes with its QLockFile
}

bool ProjectAutosave::isHeldElsewhere(const QString& path) const {
    if (held_.count(path)) return false;
    std::unique_ptr<QLockFile> lock = lockOf(path);
    if (!take(*lock)) return lock->error() == QLockFile::LockFailedError;
    lock->unlock();
    return false;
}

void ProjectAutosave::setProjectPath(const QString& path) {
    path_ = path;
    known_ = path.isEmpty() ? QByteArray() : contentHash(path);
    changedOnDiskSaid_ = false;
}

bool ProjectAutosave::projectChangedOnDisk() const {
    // A file gone since (or a folder in its place, or one that cannot be read) is no other
    // work: saving it says what is wrong, or writes it back and loses nothing.
    if (path_.isEmpty() || !QFileInfo(path_).isFile()) return false;
    const QByteArray now = contentHash(path_);
    return !now.isEmpty() && now != known_;
}

bool ProjectAutosave::overwriteProject() {
    known_ = path_.isEmpty() ? QByteArray() : contentHash(path_);
    changedOnDiskSaid_ = false;
    pending_ = true;
    return saveNow();
}

void ProjectAutosave::setDelay(int ms) {
    timer_->setInterval(std::max(0, ms));
}

void ProjectAutosave::setRetryDelay(int ms) {
    retry_->setInterval(std::max(0, ms));
}

void ProjectAutosave::fail(const QString& message) {
    // A box on every edit while the disk stays full said nothing new and buried the window.
    if (message != failureSaid_) emit failed(message);
    failureSaid_ = message;
    if (pending_) retry_->start();
}

bool ProjectAutosave::isPending() const {
    return pending_;
}

void ProjectAutosave::discardPending() {
    timer_->stop();
    retry_->stop();
    markTimer_->stop();
    pending_ = false;
    // The project file holds the state kept: nothing to offer after a crash.
    if (markedUnfinished_) endSession();
    markedUnfinished_ = false;
}

QString ProjectAutosave::recoveryPath() {
    return recoveryFolder() + "/" + thisInstance() + ".boneless";
}

QStringList ProjectAutosave::recoveries() {
    moveSharedRecoveryFile();
    QStringList paths;
    const QFileInfoList files =
        QDir(recoveryFolder()).entryInfoList({"*.boneless"}, QDir::Files, QDir::Time);
    for (const QFileInfo& file : files)
        if (!isAnotherRunningBonelesss(file.absoluteFilePath())) paths << file.absoluteFilePath();
    return paths;
}

QString ProjectAutosave::lastAutosave() {
    const QStringList all = recoveries();
    return all.isEmpty() ? QString() : all.front();
}

QString ProjectAutosave::autosaveOf(const QString& project) {
    const QString absolute = QFileInfo(project).absoluteFilePath();
    for (const QString& path : recoveries())
        if (path != absolute && recoveredProject(path) == absolute) return path;
    return {};
}

QString ProjectAutosave::recoveredProject(const QString& path) {
    return QSettings().value(recordKey(path, "project")).toString();
}

bool ProjectAutosave::sessionIsGone(const QString& session) const {
    if (session.isEmpty() || session == session_) return false;
    // Another of this process's sessions is a window that is gone (the app has one at a time);
    // another running Boneless's is live work, which it keeps saving in its own autosave.
    const QString instance = session.section(' ', 1);
    return instance == thisInstance() || instanceIsGone(instance);
}

QStringList ProjectAutosave::unfinishedRecoveries() const {
    QStringList paths = recoveries();
    paths.erase(std::remove_if(paths.begin(), paths.end(),
                               [this](const QString& p) {
                                   return !sessionIsGone(sessionOf(p)) || isHeldElsewhere(p);
                               }),
                paths.end());
    return paths;
}

bool ProjectAutosave::hasUnfinishedRecovery() const {
    return !unfinishedRecoveries().isEmpty();
}

void ProjectAutosave::claimRecovery(const QString& path) {
    QSettings().setValue(recordKey(path, "session"), session_);
    // Another Boneless's: it goes once this session's own autosave holds it, and is held till
    // then, so that no other Boneless offers, gives up or removes the work reopened here.
    if (QFileInfo(path).absoluteFilePath() != QFileInfo(recoveryPath()).absoluteFilePath()) {
        adopted_ = path;
        hold(path);
    } else {
        release(path);  // held while asked about: this Boneless's own file needs no lock
    }
}

void ProjectAutosave::discardRecovery(const QString& path) {
    // Held by another session: it asks about it, or reopened it and keeps it until it saves.
    const bool heldHere = held_.count(path) > 0;
    if (!hold(path)) return;
    QSettings().remove(recordKey(path, "session"));
    if (!heldHere) release(path);
}

void ProjectAutosave::endSession() {
    for (const QString& path : {recoveryPath(), adopted_})
        if (!path.isEmpty() && QSettings().value(recordKey(path, "session")).toString() == session_)
            QSettings().remove(recordKey(path, "session"));
    if (!adopted_.isEmpty()) release(adopted_);
}

void ProjectAutosave::replaceFinishedAutosaves() {
    // Reopened here, and now in this session's own autosave.
    if (!adopted_.isEmpty() && sessionOf(adopted_) == session_) removeAutosave(adopted_);
    if (!adopted_.isEmpty()) release(adopted_);
    adopted_.clear();
    // Discarded, or left by a Boneless that closed: the last autosave until a change replaces it,
    // which this one was. One another session holds (asks about, or reopened) is its own.
    for (const QString& path : recoveries())
        if (instanceOf(path) != thisInstance() && sessionOf(path).isEmpty() &&
            !isHeldElsewhere(path))
            removeAutosave(path);
}

bool ProjectAutosave::saveNow() {
    timer_->stop();
    retry_->stop();
    if (!enabled_) return true;
    if (!pending_ || !document_) return true;
    pending_ = false;
    // An empty untitled session has nothing worth recovering.
    if (path_.isEmpty() && !document_->hasMesh() && !document_->hasTake()) return true;
    emit aboutToSave();  // the window stores its session; that change is this save's
    timer_->stop();
    pending_ = false;
    // This Boneless's autosave holds its last session saved, titled or not: it is what the window
    // offers when a project file will not open, or at start after a crash. Another session's
    // work there (a window of this process that is gone), not yet reopened or discarded, is not
    // written over. Another running Boneless has an autosave of its own.
    // Every target is tried: a project that cannot be written (a read-only folder, a full
    // disk) must not keep the edits out of the recovery file too.
    QStringList targets;
    if (!sessionIsGone(sessionOf(recoveryPath()))) targets << recoveryPath();
    // Changed on disk since read or written here (another Boneless's autosave, another program):
    // written over, that work was lost unsaid. The edits stay in the recovery file.
    const bool changedElsewhere = projectChangedOnDisk();
    if (!path_.isEmpty() && !changedElsewhere) targets.prepend(path_);
    if (changedElsewhere && !changedOnDiskSaid_) emit changedOnDisk(path_);
    changedOnDiskSaid_ = changedOnDiskSaid_ || changedElsewhere;
    if (targets.isEmpty()) {
        pending_ = true;  // kept for a save once that work is reopened or discarded
        // Said once: an untitled session left unsaved must know (a crash's work that would not
        // reopen).
        if (!heldBackSaid_)
            emit failed(
                tr("Edits are not autosaved: the recovery file holds the work of a "
                   "Boneless that did not close (File → Recent Files → Last Autosave). "
                   "Save this project to keep them."));
        heldBackSaid_ = true;
        return false;
    }
    QStringList errors;
    bool kept = !changedElsewhere, recovered = targets.contains(recoveryPath());
    for (const QString& target : targets) {
        QDir().mkpath(QFileInfo(target).absolutePath());
        QString error;
        const bool ok = Project::save(*document_, target, &error);
        if (!ok) errors << error;
        if (ok && target == path_) known_ = contentHash(path_);
        (target == path_ ? kept : recovered) = ok;
    }
    // Which project the recovery file holds: offered for another one, it would pass for it.
    if (path_.isEmpty()) kept = recovered;
    if (recovered) {
        QSettings().setValue(recordKey(recoveryPath(), "project"), path_);
        // Only work that no project file holds is offered after a crash.
        if (kept && !path_.isEmpty())
            endSession();
        else
            claimRecovery();
        replaceFinishedAutosaves();
    }
    // Held in the project file now (the recovery file could not be written): nothing to offer.
    if (markedUnfinished_ && kept && !path_.isEmpty() && !recovered) endSession();
    markedUnfinished_ = false;
    if (changedElsewhere) {
        pending_ = true;  // saved once the user chose (overwriteProject, or another path)
        if (!errors.isEmpty()) fail(errors.join("\n"));
        return false;
    }
    if (!errors.isEmpty()) {
        pending_ = true;  // try again after the next change
        if (!kept && recovered)
            errors << tr("The changes are kept in the last autosave, %1.").arg(recoveryPath());
        fail(errors.join("\n"));
        return kept;
    }
    if (!failureSaid_.isEmpty()) emit savedAgain(targets.front());
    failureSaid_.clear();
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
