#pragma once

#include <QMap>
#include <QObject>
#include <QPointer>
#include <QString>
#include <QStringList>
#include <map>
#include <memory>

class QLockFile;
class QTimer;

namespace boneless::ui {

class Document;

// The `.boneless` project file: JSON with the mesh (and group), take and correspondence file
// paths relative to the project file, the map itself, the fixed alignment, the solver settings
// and the view settings:
//   {"format": "boneless-project", "version": 1,
//    "mesh": {"file": "walker.obj", "group": ""}, "take": {"file": "walker.c3d"},
//    "correspondence": {"file": "walker.map.json", "modified": false, "map": {...}},
//    "alignment": null | {"calibration_frame", "scale", "rotation", "translation", ...},
//    "settings": {"marker_weight", ...}, "view": {...}}
// The map is stored whole, so unsaved edits of a correspondence file are kept by the project.
namespace Project {

// Writes the document's state (atomically, QSaveFile). false with *error on failure.
bool save(const Document& document, const QString& path, QString* error = nullptr);
// Loads the files the project names into the document and restores its state; on failure the
// document is left as it was and *error holds a message naming the project and the cause.
// When it failed because a file the project names is not there, *missing (if given) says which,
// in a plain sentence: "The mesh /data/walker.obj named by walk.boneless is missing."
// A mesh that no longer fits the map (re-exported since) is said so too: "The map in walk.boneless
// was made for another mesh than /data/walker.obj, which has 3083 vertices now."
// So is a map with an entry past the mesh's last vertex: "The map walk.map.json named by
// walk.boneless points past /data/walker.obj: marker LFHD is on vertex 4000, and it has 3426
// vertices."
// *missingFile (if given) is that file's path, the one to locate. `located` gives files found
// elsewhere (Locate…): a path the project names, resolved, to the one read instead (and saved
// next). `setMapAside` opens a project whose map does not fit its mesh without the map (and its
// alignment), to be mapped anew; *setAside (if given) then says where the map is kept: its own
// file, left as it is, or for a map only the project held, a copy written beside the project.
bool load(Document& document, const QString& path, QString* error = nullptr,
          QString* missing = nullptr, QString* missingFile = nullptr,
          const QMap<QString, QString>& located = {}, bool setMapAside = false,
          QString* setAside = nullptr);
// The project's JSON text (what save() writes), for tests and comparisons.
QByteArray toJson(const Document& document, const QString& path);

}  // namespace Project

// Keeps a project file up to date: after each change of the document (Document::changed) it
// saves the project within a short delay, so a crash loses at most that delay's edits. Each save
// also goes to recoveryPath() (the only place it goes without a project path), which the window
// offers to reopen when the project it was saved from will not open; a project that cannot be
// written does not keep the change from it.
// The project file is written only while it holds what this session last read or wrote there:
// changed since (by another Boneless, or another program), it is left alone, the edits go to the
// recovery file only, and changedOnDisk() is emitted once, until overwriteProject() or another
// project path.
// An edit of a titled project marks its session unfinished at once (writing the recovery file
// when it holds no autosave of that project yet): killed before the delayed save, the next start
// offers the edit, or what was last saved.
// Each running Boneless has a recovery file of its own, named by its process (id and start time):
// a second Boneless beside the first neither writes over the first's nor offers it. The work of a
// session that did not end (a crash), in a file that no project file holds, is offered at the next
// start once its Boneless is no longer running: reopened (claimRecovery) it is that session's,
// discarded (discardRecovery) it stays as the last autosave until a change replaces it.
// A recovery file is offered by one Boneless at a time: the one asking about it, and then the one
// that reopened it, holds its lock file (PID-START.boneless.lock); no other asks about it, gives
// it up or removes it. A lock left by a Boneless no longer running is taken over.
class ProjectAutosave : public QObject {
    Q_OBJECT
  public:
    explicit ProjectAutosave(Document* document, QObject* parent = nullptr);
    ~ProjectAutosave() override;  // saves a pending change

    // Empty = untitled. The file as it is now is the one this session knows (just loaded or saved).
    void setProjectPath(const QString& path);
    QString projectPath() const { return path_; }
    void setDelay(int ms);  // default 1000
    // After a failed save (a full disk), the next try comes this long after, edit or not: the
    // edits reach the files once space returns. Default 10000.
    void setRetryDelay(int ms);
    // false: nothing is saved or recorded, the project file, the recovery file and the settings
    // are left as they are (a scripted run).
    void setEnabled(bool enabled) { enabled_ = enabled; }
    bool isPending() const;
    // A change the document did not signal (a file the project names, located elsewhere):
    // saved as an edit is.
    void schedule();
    // Where this Boneless keeps an untitled session (in the per-user data folder's recovery/,
    // PID-START.boneless).
    static QString recoveryPath();
    // The recovery files no other running Boneless holds (this one's, and those of Boneless no
    // longer running), newest first; lastAutosave() is the first, File → Recent Files → Last
    // Autosave.
    static QStringList recoveries();
    static QString lastAutosave();
    // The newest of them saved from `project`; empty when none was.
    static QString autosaveOf(const QString& project);
    // The project the recovery file `path` was last saved from; empty for an untitled session.
    static QString recoveredProject(const QString& path = recoveryPath());
    // The recovery files that hold work no project file holds, from a session that did not end,
    // and that no other session holds, newest first.
    QStringList unfinishedRecoveries() const;
    bool hasUnfinishedRecovery() const;
    // This session takes the work of the recovery file `path` as its own (it reopened it); another
    // Boneless's file goes once this one's own holds that work.
    void claimRecovery(const QString& path = recoveryPath());
    // The project file no longer holds what this session last read or wrote there.
    bool projectChangedOnDisk() const;
    // Writes the project file with this session's state whatever it holds now (Overwrite).
    bool overwriteProject();
    // The unfinished session's work in `path` is given up: a change may replace it. Nothing is
    // given up of a file another session holds.
    void discardRecovery(const QString& path = recoveryPath());
    // Takes the lock of the recovery file `path` for this session (while asking about it, and
    // once reopened while its work is this session's); false when another session holds it.
    bool hold(const QString& path);
    void release(const QString& path);
    // This session ended cleanly (the window closed): its recovery file is not offered at start.
    void endSession();

  public slots:
    // Writes at once if a change is pending. True when the document is kept where it belongs:
    // in the project file, or without one in the recovery file.
    bool saveNow();
    // Forgets the pending change, e.g. the one a Project::load just caused: the file on disk
    // already is that state.
    void discardPending();

  signals:
    // Before writing: a direct connection may still change the document (the window's frame,
    // speed and camera), and that change is saved with the rest.
    void aboutToSave();
    void saved(const QString& path);
    // The project file `path` changed on disk since this session read or wrote it: not written.
    void changedOnDisk(const QString& path);
    // Said once while saves keep failing alike (a full disk): again only when the message changes.
    void failed(const QString& message);
    // A save succeeded after failed(): the edits made meanwhile are in `path` now.
    void savedAgain(const QString& path);

  private:
    QPointer<Document> document_;
    QString path_;
    QByteArray known_;  // a hash of what path_ held when last read or written here
    bool changedOnDiskSaid_ = false;
    // `session` did not end: another window of this process (gone, as the app has one at a
    // time), or a session of a Boneless no longer running.
    bool sessionIsGone(const QString& session) const;
    // Just after an edit of a titled project (schedule): the session is marked unfinished, so
    // that a kill before the delayed save leaves its work offered.
    void markUnfinished();
    // After a save into recoveryPath(): the recovery file reopened, and those discarded or left by
    // a Boneless that closed, are replaced by it.
    void replaceFinishedAutosaves();

    // Another session (of this Boneless or another) holds `path`'s lock.
    bool isHeldElsewhere(const QString& path) const;

    const QString session_;  // this session's id in the recovery files' records
    std::map<QString, std::unique_ptr<QLockFile>> held_;  // recovery file -> its lock, held
    QString adopted_;            // another Boneless's recovery file reopened, until saved here
    bool heldBackSaid_ = false;  // failed() said the recovery file is another session's
    // Says `message` unless it is the failure said last, and tries again later (retry_).
    void fail(const QString& message);
    QString failureSaid_;  // the last failed() message, until a save succeeds
    QTimer* timer_;
    QTimer* retry_;
    QTimer* markTimer_;  // markUnfinished() once the event loop runs: not in the middle of a load
    bool enabled_ = true;
    bool pending_ = false;
    bool markedUnfinished_ = false;  // by markUnfinished(), not by a save
};

// Recently opened projects and files, newest first, kept in QSettings ("recentFiles").
namespace RecentFiles {
QStringList list();
void add(const QString& path);  // moves it to the front; keeps at most 10; drops missing files
void remove(const QString& path);
void clear();
}  // namespace RecentFiles

}  // namespace boneless::ui
