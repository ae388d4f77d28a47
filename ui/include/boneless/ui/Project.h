#pragma once

#include <QObject>
#include <QPointer>
#include <QString>
#include <QStringList>

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
bool load(Document& document, const QString& path, QString* error = nullptr,
          QString* missing = nullptr);
// The project's JSON text (what save() writes), for tests and comparisons.
QByteArray toJson(const Document& document, const QString& path);

}  // namespace Project

// Keeps a project file up to date: after each change of the document (Document::changed) it
// saves the project within a short delay, so a crash loses at most that delay's edits. Each save
// also goes to recoveryPath() (the only place it goes without a project path), which the window
// offers to reopen when the project it was saved from will not open; a project that cannot be
// written does not keep the change from it.
// The recovery file belongs to one session at a time: while it holds work that no project file
// holds, from a session that did not end (a crash), another session does not write over it until
// that work is reopened (claimRecovery) or discarded (discardRecovery); the window offers both at
// start-up.
class ProjectAutosave : public QObject {
    Q_OBJECT
  public:
    explicit ProjectAutosave(Document* document, QObject* parent = nullptr);
    ~ProjectAutosave() override;  // saves a pending change

    void setProjectPath(const QString& path);  // empty = untitled
    QString projectPath() const { return path_; }
    void setDelay(int ms);  // default 1000
    bool isPending() const;
    // Where an untitled session is kept (in the per-user data folder).
    static QString recoveryPath();
    // The project the recovery file was last saved from; empty for an untitled session.
    static QString recoveredProject();
    // The recovery file holds work that no project file holds, from a session that did not end.
    bool hasUnfinishedRecovery() const;
    // This session takes the recovery file's work as its own (it reopened it).
    void claimRecovery();
    // The unfinished session's work is given up: the next save may write over it.
    void discardRecovery();
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
    void failed(const QString& message);

  private:
    QPointer<Document> document_;
    QString path_;
    const QString session_;      // this session's id in the recovery file's record
    bool heldBackSaid_ = false;  // failed() said the recovery file is another session's
    QTimer* timer_;
    bool pending_ = false;
};

// Recently opened projects and files, newest first, kept in QSettings ("recentFiles").
namespace RecentFiles {
QStringList list();
void add(const QString& path);  // moves it to the front; keeps at most 10; drops missing files
void remove(const QString& path);
void clear();
}  // namespace RecentFiles

}  // namespace boneless::ui
