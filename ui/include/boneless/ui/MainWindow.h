#pragma once

#include <QMainWindow>
#include <QMap>
#include <QString>
#include <functional>
#include <memory>
#include <utility>
#include <vector>

#include "boneless/ui/Document.h"

class QAction;
class QLabel;
class QLineEdit;
class QComboBox;
class QMenu;
class QMessageBox;
class QProgressBar;
class QTableView;

namespace boneless::ui {

class ExportDialog;
class FrameDisplay;
class FrameSolver;
class MarkerFilterProxy;
class MarkerListModel;
class MeshView;
class ProjectAutosave;
class Timeline;
class TimelineWidget;

// The application window: the 3D view, the marker list, the timeline, menus and status bar.
// Every failure becomes a message in the window (a non-modal box and the status bar), never an
// exception or a blocking dialog that would stall the solver's results.
class MainWindow : public QMainWindow {
    Q_OBJECT
  public:
    explicit MainWindow(QWidget* parent = nullptr);
    ~MainWindow() override;

    Document* document() const { return document_; }
    Timeline* timeline() const { return timeline_; }
    TimelineWidget* timelineWidget() const { return timelineWidget_; }
    MeshView* meshView() const { return view_; }
    FrameSolver* frameSolver() const { return solver_; }
    QTableView* markerTable() const { return markerTable_; }
    QLineEdit* markerFilter() const { return filterEdit_; }
    MarkerFilterProxy* markerProxy() const { return proxy_; }

    // Opens by extension: .boneless project; .obj/.ply/.off/.stl mesh; .c3d take; .json map.
    bool openFile(const QString& path);
    // Several files as one action (a drop, the command line): mesh, then take, then map, and
    // one question about unsaved edits. True when every one opened.
    bool openFiles(QStringList paths);
    // A mesh file; an OBJ with groups first asks which group (GroupChooser).
    bool openMesh(const QString& path);
    // A project that will not open leaves the window as it was and the file untouched, and the
    // message offers the recovery autosave (openRecovery()) when it was made from that project.
    // A file it names that is missing can be located (Locate…): the project then opens with the
    // file chosen, as an edit, saved into the project next.
    bool openProject(const QString& path) { return openProject(path, {}); }
    // A map that does not fit the mesh can be set aside (Open Without the Map): the project
    // opens unmapped, the map kept on disk (Project::load's setMapAside), and says so.
    // `located`: files the project names (resolved) that are read from elsewhere.
    bool openProject(const QString& path, const QMap<QString, QString>& located,
                     bool setMapAside = false);
    // Writes the demo afresh and opens it. The demo is never saved into: Save goes to Save As,
    // autosave to the recovery file.
    bool openDemo();
    bool isDemoOpen() const { return demo_; }
    // Opens the recovery file `path` (by default ProjectAutosave::lastAutosave()) as an untitled
    // project, this session's from then on. One that will not open is kept (offered again at the
    // next start); a file it names that has moved since can be located (Locate…), as a project's.
    // A map that does not fit its mesh can be set aside, as a project's (openProject()).
    bool openRecovery(const QString& path = {}) { return openRecovery(path, {}); }
    bool openRecovery(const QString& path, const QMap<QString, QString>& located,
                      bool setMapAside = false);
    // At start-up: for each recovery file holding work that no project file holds, left by a
    // session that did not close (ProjectAutosave::unfinishedRecoveries(), newest first), asks
    // Reopen or Discard (recoveryQuestion), saying that reopened it opens instead of the files
    // `named` (the command line's). True when one was reopened (the others are asked about at the
    // next start); without message boxes it asks nothing and leaves that work alone.
    bool offerRecovery(const QStringList& named = {});
    // What the command line asks for at start-up: a crash's work first (offerRecovery), then the
    // project and files, or with none the demo. Reopened, the crash's work opens where it was
    // left (the start frame is not its) instead of the files, which are not opened: the window
    // holds one session, and opening them asked at once to save the work just reopened. True
    // when what was chosen opened.
    bool openAtStart(const QString& project, const QStringList& files);
    bool saveProject();  // Save As when untitled or the demo
    bool saveProjectAs(const QString& path);
    // Writes the map to `path` (Save Correspondence As, once a name is chosen): never over the
    // mesh, the take or the project, and an existing file only after asking. True when saved.
    bool saveCorrespondenceAs(const QString& path);
    QString projectPath() const { return projectPath_; }
    ProjectAutosave* autosave() const { return autosave_; }
    // File → Export: range, format, folder, estimate, progress.
    ExportDialog* exportDialog() const { return exportDialog_; }
    void showExportDialog();
    // Edit → Suggest Rest, on a worker thread (half a minute on a 100K-face mesh): the status bar
    // says it runs, edits wait, and the window keeps drawing; when it ends the suggestions are
    // one undo step and the status bar says how many to check. A suggestion made from a mesh,
    // take, map or mesh up that changed meanwhile is dropped, as is one the window's closing
    // stopped. False when it could not start.
    bool suggestMappings();
    bool isSuggesting() const;
    // Ends the suggestion running, if any, at its next fit, mapping nothing: the window closes,
    // and the app would otherwise wait for it to end (half a minute on a 100K-face mesh).
    void stopSuggesting();
    // Align (Edit menu and marker panel), and the status bar says how well the alignment fits.
    void alignTake();

    // The frame the timeline moves to once the next take is loaded (for --frame).
    void setStartFrame(int frame) { startFrame_ = frame; }
    // --group: the OBJ group the files named at start open, without asking.
    void setStartGroup(const QString& group) { startGroup_ = group; }
    // false: failures only go to the status bar and errorShown (batch use, screenshots).
    void setMessageBoxesEnabled(bool enabled) { messageBoxes_ = enabled; }
    // false: nothing of the user's session is recorded (a scripted run, --screenshot): no recent
    // files, no autosave and no autosave records. A render script over a library had replaced
    // the user's File → Recent Files with the files it rendered.
    void setRecordsSession(bool records);
    // SIGTERM, SIGHUP and SIGINT (logout, shutdown, kill, Ctrl+C) save the edits pending and quit,
    // asking nothing: killed within the autosave's delay, the last edit was lost. For the process;
    // the last window to call it handles them. Any question up (a box, the recovery question
    // at start-up) is left unanswered: a crash's work stays offered at the next start.
    void quitOnTerminationSignals();
    // A termination signal ended the session: every event loop was told to end, so main() must
    // not start its own (one asked before app.exec(), as the recovery question is).
    bool endedBySignal() const { return endedBySignal_; }
    // The frame on screen, and whether it is the timeline's frame, rendered.
    int displayedFrame() const;
    bool frameUpToDate() const;
    bool isSolving() const;
    // What the status bar shows about the frame: "Frame 10 / 59 · solved in 80 ms · residual …".
    QString frameSummary() const;

    // `message` is one plain sentence; `detail` (the technical cause) goes under "Show Details".
    void showError(const QString& message, const QString& detail = {});

  signals:
    void errorShown(const QString& message);
    void frameDisplayed(int frame);
    // From moving the playhead to the render that shows the frame.
    void latencyMeasured(int frame, double milliseconds, bool fromCache);
    // Suggest Rest ended: `applied` when its suggestions (if any) went into the map.
    void suggestionFinished(bool applied);

  protected:
    void dragEnterEvent(QDragEnterEvent* event) override;
    void dropEvent(QDropEvent* event) override;
    void closeEvent(QCloseEvent* event) override;

  private:
    // Asks where the missing file `file` is now; empty when not chosen.
    QString locate(const QString& file);
    // The buttons of a project's or the last autosave's message for the file it named that is
    // missing, or that the map does not fit: Locate…, and Open Without the Map for a mesh there.
    // Each calls `reopen` with the files located and whether to set the map aside. Returns the
    // sentence that says what they do.
    QString offerMissingFile(
        QMessageBox* box, const QString& missingFile, const QMap<QString, QString>& located,
        const std::function<void(const QMap<QString, QString>&, bool)>& reopen);
    void buildMenus();
    void buildFileMenu();
    QMenu* buildEditMenu();  // returned for the calibration actions
    QMenu* buildViewMenu();
    void buildPlaybackMenu();
    void buildHelpMenu();
    void buildMarkerDock();
    void buildStatusBar();
    void buildShortcuts();
    void connectDocument();
    void applyViewSettings();
    void rebuildRecentMenu();
    void addRecentFile(const QString& path);  // unless !recordsSession_
    // The start-up question about one recovery file; true when it was reopened.
    bool offerRecovery(const QString& path, const QStringList& named);
    void updateTitle();
    // unsavedEdits_, and the title's mark of edits no project file holds.
    void setUnsavedEdits(bool edited);
    void syncTableSelection(int marker);
    void onPointPicked(const SurfacePoint& point);
    // Maps the selected marker to a point (clicked in Map Markers) or a vertex (typed), one
    // undoable edit.
    void mapSelectedMarker(const SurfacePoint& point);
    // Edit → Map Selected Marker to Vertex: asks for the vertex's number, within the mesh's.
    void askVertexForSelected();
    void onTakeLoaded();
    void startUntitled();
    // One plain sentence for a file that would not open ("garbage.c3d is not a C3D file.").
    QString plainError(const QString& path) const;
    // Over existing mappings, asks replace, merge or cancel (false); without message boxes,
    // replace.
    bool askMapLoad(const QString& path, Document::MapLoad& mode);
    // Before closing or opening another project, mesh or take: saves what is pending and, when
    // the project could not be saved or edits were made untitled or on the demo (kept only in
    // the recovery file, which the next change overwrites), asks Save As, go on, or cancel.
    // True to go on.
    bool keepUnsavedWork(bool closing);
    void endForSignal();  // quitOnTerminationSignals()
    // The project file changed on disk since it was opened or saved here: Reload, Save As… or
    // Overwrite, asked in a box that stays up (an autosave found it).
    void askChangedOnDisk(const QString& path);
    void showHelp(const QString& title, const QString& html);
    // A status message whose whole `detail` (a list it names a few of) is the bar's tooltip while
    // it is shown.
    void showStatus(const QString& message, const QString& detail, int timeoutMs);
    void storeSession();
    // The suggestion the worker made, applied or dropped.
    void finishSuggestion();
    // Why edits wait: an export, a suggestion, or nothing.
    void updateEditsHeld();
    void restoreSession();
    QMessageBox* errorBox(const QString& message, const QString& detail);
    // "Opened X", and what opening it let through or changed, if anything.
    void showOpened(const QString& path, const QStringList& notes);

    void chooseMesh();
    void chooseTake();
    void chooseCorrespondence();
    void chooseProject();
    bool chooseSaveProjectAs();  // true when it saved
    void chooseSaveCorrespondence();
    // Asks whether to replace the file `path` that a Save As (`title`) would write over; true when
    // it may (no such file, or Yes).
    bool askToReplace(const QString& title, const QString& path);
    // Which of the window's own files `path` is ("mesh", "take", "correspondence", "project",
    // however either is spelled), "" for none or for `except`, the file being saved again.
    QString ownFileAt(const QString& path, const QString& except) const;

    Document* document_;
    FrameSolver* solver_;
    Timeline* timeline_;
    TimelineWidget* timelineWidget_;
    MeshView* view_;
    MarkerListModel* markerModel_;
    MarkerFilterProxy* proxy_;
    FrameDisplay* display_;
    ProjectAutosave* autosave_;
    ExportDialog* exportDialog_;

    QTableView* markerTable_ = nullptr;
    QLineEdit* filterEdit_ = nullptr;
    QComboBox* stateFilter_ = nullptr;
    QLabel* frameLabel_ = nullptr;
    QLabel* solveLabel_ = nullptr;
    QLabel* residualLabel_ = nullptr;
    QMenu* recentMenu_ = nullptr;
    QAction* labelsAction_ = nullptr;
    QAction* trailsAction_ = nullptr;
    QAction* heatMapAction_ = nullptr;
    QAction* mappingAction_ = nullptr;
    QAction* followAction_ = nullptr;
    QAction* offsetAllAction_ = nullptr;

    QString projectPath_;
    bool demo_ = false;
    QString opening_;  // the file being opened, for plainError()
    // While a project file loads, the document's errors are left to the project's message.
    bool loadingProject_ = false;
    // An edit (each one undoable) since the project was opened or saved; loading a file is none.
    bool unsavedEdits_ = false;
    // > 0 while a file is being loaded, in a Loading's scope: what it changes is no edit.
    class Loading;
    int loading_ = 0;
    bool workAsked_ = false;  // keepUnsavedWork was answered for the files being opened
    int startFrame_ = -1;
    QString startGroup_;
    bool messageBoxes_ = true;
    bool syncingTable_ = false;  // syncTableSelection is moving the table's current row
    bool recordsSession_ = true;
    bool endedBySignal_ = false;
    // While keepUnsavedWork's question waits, error boxes are held (one over the question would
    // hide it); the answer shows them if the session stays, drops them if it is left.
    bool asking_ = false;
    std::vector<std::pair<QString, QString>> heldErrors_;  // message, detail
    QString detailedMessage_;  // the status message the bar's tooltip goes with
    struct SuggestJob;
    std::shared_ptr<SuggestJob> suggestJob_;  // the suggestion running, if any
    QProgressBar* busyBar_ = nullptr;         // shown while it runs
    quint64 suggestInputs_ = 0;  // counts changes of the mesh, take and map a suggestion reads
};

}  // namespace boneless::ui
