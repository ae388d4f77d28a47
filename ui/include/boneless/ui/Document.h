#pragma once

#include <QObject>
#include <QString>
#include <QStringList>
#include <QVariantMap>
#include <atomic>
#include <optional>
#include <vector>

#include "boneless/Alignment.h"
#include "boneless/C3dTake.h"
#include "boneless/Correspondence.h"
#include "boneless/TakeExport.h"
#include "boneless/TakeSolver.h"
#include "boneless/TriMesh.h"

class QUndoStack;

namespace boneless {
struct Suggestion;
}

namespace boneless::ui {

// The open session: one rest mesh, one take, the marker-to-vertex map being authored, the
// alignment and the solver settings. Every edit of the map, the alignment or the settings is an
// undo command on undoStack(); loading never throws: a failure leaves the previous state and emits
// errorOccurred with boneless::Error's complete message.
//
// Markers are the rows the user works with: the take's points classified as markers, in file
// order (without a take: the map's entries). A marker is "mapped" when the map has an entry whose
// label the take resolves to it.
class Document : public QObject {
    Q_OBJECT
  public:
    explicit Document(QObject* parent = nullptr);
    ~Document() override;

    // --- files -----------------------------------------------------------------------------
    bool loadMesh(const QString& path, const QString& group = {});
    bool loadTake(const QString& path);
    // Replaces the map (one undo step). Entries that do not fit the mesh are an error.
    // Replace: the file's map instead of this one. Merge: this map plus the file's mappings of
    // markers not mapped here (unless their vertex is taken), and in place of suggestions still
    // marked for review (needs_review): those are no one's word yet. One undo step either way.
    // *added (when given): the mappings the file added; *replaced: the suggestions it replaced;
    // a merge that does neither is no edit.
    enum class MapLoad { Replace, Merge };
    bool loadCorrespondence(const QString& path, MapLoad mode = MapLoad::Replace,
                            int* added = nullptr, int* replaced = nullptr);
    // Whether the file is a correspondence that fits the mesh, as loadCorrespondence checks it
    // (errorOccurred says why not), leaving the map alone: checked before asking how to load it.
    bool checkCorrespondence(const QString& path);
    // Writes the map as a correspondence file (atomic); remembers the path.
    bool saveCorrespondence(const QString& path);
    // Back to an empty session: no mesh, no take, empty map, default settings, empty undo stack.
    void reset();
    // Drops the edits since the state opened or saved: undoes back to the undo stack's clean
    // state, which redo reaches again; when that state cannot be reached (work reopened from an
    // autosave), the map, the alignment and the settings go back to none and the defaults in one
    // undo step named `text`.
    void discardEdits(const QString& text);

    bool hasMesh() const { return hasMesh_; }
    const TriMesh& mesh() const { return mesh_; }
    QString meshPath() const { return meshPath_; }
    QString meshGroup() const { return meshGroup_; }
    QStringList meshWarnings() const { return meshWarnings_; }

    bool hasTake() const { return hasTake_; }
    const C3dTake& take() const { return take_; }
    QString takePath() const { return takePath_; }
    // What opening the take let through or changed: the reader's warnings (a truncated file),
    // a calibration frame past its end set back to automatic.
    QStringList takeNotes() const { return takeNotes_; }
    int frameCount() const;    // 0 without a take
    double frameRate() const;  // frames per second, 0 without a take

    const Correspondence& correspondence() const { return map_; }
    // What the map file opened last said of itself (Correspondence::warnings: a version 1 entry's
    // "face", which only version 2 reads), naming the file.
    QStringList correspondenceNotes() const { return mapNotes_; }
    // The correspondence file the map came from or was last saved to (may be empty).
    QString correspondencePath() const { return mapPath_; }

    // --- markers ---------------------------------------------------------------------------
    int markerCount() const { return static_cast<int>(markers_.size()); }
    QString markerLabel(int marker) const;
    int markerPoint(int marker) const;  // the take's point index, -1 without a take
    // Core's words when another point of the take has this marker's full label, which no map
    // label can tell apart ("points 1 and 3 are both labelled Male:LFWT"); empty otherwise. Such a
    // marker cannot be mapped.
    QString sharedLabelText(int marker) const;
    int mappedVertex(int marker) const;  // -1 when unmapped
    // Where the marker sits: its vertex, or a point of a face (vertex −1 when unmapped).
    SurfacePoint mappedPoint(int marker) const;
    double markerOffsetMm(int marker) const;
    bool markerSuggested(int marker) const;  // the entry came from "suggest" and was not edited
    // Why a suggested entry should be checked before it is trusted (empty: nothing to check).
    QString markerReviewReason(int marker) const;
    int markerForVertex(int vertex) const;            // -1 when no marker sits on that vertex
    int markerByLabel(const QString& label) const;    // -1 when none
    bool markerVisible(int marker, int frame) const;  // false without a take or when missing
    int mappedCount() const;

    // The markers' positions at `frame` in mesh coordinates (markerCount() by 3, NaN rows where
    // missing), placed with displayAlignment(). Empty without a take.
    Positions markerPositions(int frame) const;

    // --- alignment -------------------------------------------------------------------------
    // The alignment the user fixed (align, suggest, or a loaded project); empty = the solver
    // chooses one itself, as boneless-cli solve does.
    const std::optional<Calibration>& alignment() const { return alignment_; }
    // What the view places markers with: alignment() if set, else the automatic calibration
    // from the mapped markers (at least 3), else a rough fit of the take's extent onto the mesh.
    Calibration displayAlignment() const;

    // --- settings --------------------------------------------------------------------------
    // Solver settings of this session (saved in the project). options().alignment is always
    // empty here; solveOptions() fills it from alignment().
    const TakeSolveOptions& settings() const { return settings_; }
    // One undo step named `text` (a default when empty); none when nothing changes.
    void setSettings(const TakeSolveOptions& settings, const QString& text = {});
    // Calibrates at `frame` (-1: chosen automatically), one undo step: the settings' calibration
    // frame, calibration on, and a fixed alignment redone at that frame, since the solver aligns
    // and fits at one frame (solveOptions()). Refused when that alignment fails.
    bool calibrateAt(int frame);
    // The alignment the solver would find at `frame` (-1: its automatic choice) for the map and
    // settings as they are, changing nothing (no undo step, no error reported); empty when it
    // finds none. It builds a solver: up to a second on a 13K-vertex mesh.
    std::optional<Calibration> alignmentAt(int frame) const;
    // The settings' take_units as Edit → Take Units names them: "From the File", "Metres (m)".
    static QString takeUnitsName(const std::string& units);
    // What sets the take's units when not its file, as the take's messages name it.
    static constexpr const char* kTakeUnitsFrom = "Edit → Take Units";
    // What the solver and the export use: settings() plus the fixed alignment, if any, without
    // the options only the exact solver reads when it is not the one chosen (their defaults).
    TakeSolveOptions solveOptions() const;
    // Free-form view state the window keeps in the project (labels, trails, heat map, ...).
    QVariantMap viewSettings() const { return viewSettings_; }
    void setViewSetting(const QString& key, const QVariant& value);
    void setViewSettings(const QVariantMap& settings);

    // --- selection (shared by the marker list and the 3D view; not undoable) ---------------
    int selectedMarker() const { return selected_; }
    void setSelectedMarker(int marker);  // -1 = none

    // --- edits: each one undo command; false (and errorOccurred) when refused ---------------
    // How far off the skin the first marker mapped sits (mm) when none is mapped: a marker's
    // base, ball and the skin's give keep it 10 to 15 mm off (the generated demo's sit at 10).
    // Later ones take the median of those mapped; the offset row changes either.
    static constexpr double kFirstOffsetMm = 10.0;
    // Maps `marker` to a point of the surface (a clicked point of a face, or a vertex): the map
    // entry's "vertex" is its nearest corner. Refused when another marker already sits on that
    // vertex. Mapping a marker again near its own vertex moves it there, and confirms a
    // suggestion.
    bool assign(int marker, const SurfacePoint& point);
    bool assign(int marker, int vertex) { return assign(marker, SurfacePoint{vertex}); }
    bool clearMapping(int marker);
    // How far the mapped `markers` sit off the skin (mm, along the normal), one undo step.
    // Refused outside Correspondence::kMinOffsetMm to kMaxOffsetMm, as a map file would be.
    bool setOffsetMm(const std::vector<int>& markers, double mm);
    bool clearAllMappings();
    // Suggest Rest's inputs, copied so that a worker can suggest from them (up to half a minute
    // on a 100K-face mesh) while the document changes: the mesh, the take, the map, and the
    // settings' mesh up, which `map suggest --mesh-up` takes too.
    struct SuggestInputs {
        TriMesh mesh;
        C3dTake take;
        Correspondence map;
        std::optional<Vec3> meshUp;
    };
    SuggestInputs suggestInputs() const;
    // Core's suggestMappings on them; throws its Error. stop: as core's.
    static Suggestion suggest(const SuggestInputs& inputs, const std::atomic<bool>* stop = nullptr);
    // canSuggest() checks the edit may start, and applySuggestion() makes a suggestion, made from
    // suggestInputs() as they still are, one undo step. The alignment is left as it is: the
    // suggestion's own only placed the proposals.
    bool canSuggest();
    void applySuggestion(Suggestion suggestion);
    // Fixes the alignment from the mapped markers (at least 3); calibrationFrame -1 = automatic.
    bool align(int calibrationFrame = -1);
    bool clearAlignment();
    QUndoStack* undoStack() const { return undoStack_; }
    // While an export runs, which solves the map, alignment and settings it started with, the
    // window holds the edits: each is refused with `reason` (empty: edits go ahead again). Loading
    // a file, which the export does not read either, is no edit.
    void holdEdits(const QString& reason);
    bool editsHeld() const { return !heldBecause_.isEmpty(); }

    // --- solving and export ----------------------------------------------------------------
    // True when a frame can be solved: mesh, take, at least 3 mapped markers, and memory for
    // the mesh's solve. Else *why says what is missing.
    // *detail (when given): what *why, kept to a status bar's length, leaves out.
    bool canSolve(QString* why = nullptr, QString* detail = nullptr) const;
    // Empty when solving the mesh fits the memory this process may use; else the refusal, naming
    // the file, its size, the memory its solve would need and the limit (checkSolveFits).
    QString memoryRefusal() const;
    // The request `boneless-cli solve` would make for the same inputs. mapPath is the
    // correspondence file when the map is unchanged since it was read or saved, else empty (the
    // sidecar then holds the map itself).
    ExportRequest exportRequest(const QString& outDir, ExportFormat format) const;
    // True when the map differs from correspondencePath()'s content (or there is no file).
    bool correspondenceModified() const;

    // A whole session at once: Project::load reads the files into one of these and hands it over
    // with restoreState(), so that a failed load leaves the document untouched.
    struct State {
        bool hasMesh = false;
        TriMesh mesh;
        QString meshPath, meshGroup;
        QStringList meshWarnings;
        bool hasTake = false;
        C3dTake take;
        QString takePath;
        Correspondence map;
        QString mapPath;
        std::optional<Calibration> alignment;
        TakeSolveOptions settings;
        QVariantMap viewSettings;
    };
    // Read a file into `state` (mesh: also its warnings); false with *error, state untouched.
    static bool readMeshFile(const QString& path, const QString& group, State& state,
                             QString* error);
    static bool readTakeFile(const QString& path, State& state, QString* error);
    // Replaces everything (map checked against the mesh); clears the undo stack and selection.
    bool restoreState(State state);

    QString lastError() const { return lastError_; }

  signals:
    void meshChanged();
    void takeChanged();
    // The map changed (edit, undo, redo, load): rows' mapped vertices and offsets.
    void correspondenceChanged();
    void alignmentChanged();
    void settingsChanged();
    void viewSettingsChanged();
    void selectionChanged(int marker);
    void editsHeldChanged(bool held);
    // Anything the project file stores changed: the autosave listens to this one.
    void changed();
    void errorOccurred(const QString& message);

  private:
    friend class EditCommand;
    // What an undo step restores, all at once: a calibration changes settings and alignment.
    struct EditState {
        Correspondence map;
        QString mapPath;
        std::optional<Calibration> alignment;
        TakeSolveOptions settings;
    };
    EditState editState() const;
    void applyEditState(const EditState& state);  // used by the undo commands
    void pushEdit(const QString& text, EditState after);
    // Fixes after.alignment from after's map and settings at `frame` (-1: automatic).
    bool fitAlignment(int frame, EditState& after);
    // The alignment the solver finds at `frame` (-1: automatic) for `state`'s map and settings;
    // empty with *error when none is found.
    std::optional<Calibration> solverAlignment(const EditState& state, int frame,
                                               QString* error) const;
    void rebuildMarkers();
    void startAfresh();
    // takeNotes_ from the take's warnings, and a calibration frame past its end set back to
    // automatic with a note (true then).
    bool noteTake();
    // How many mapped markers the take shows at `frame`.
    int mappedSeenAt(int frame) const;
    // The take read in the settings' take_units (setTakeUnits), its marker span judged in them.
    void applyTakeUnits();
    bool fail(const QString& message);
    // True (and errorOccurred) while edits are held.
    bool refusedWhileHeld();
    Correspondence emptyMap() const;
    // The map names this mesh: its file, group and vertex count.
    void stampMesh(Correspondence& map) const;
    // The same for an edit: the vertex count, and the file and group where the map names none.
    void stampEdit(Correspondence& map) const;

    bool hasMesh_ = false, hasTake_ = false;
    TriMesh mesh_;
    QString meshPath_, meshGroup_;
    QStringList meshWarnings_;
    C3dTake take_;
    QString takePath_;
    QStringList takeNotes_;
    Correspondence map_;
    QString mapPath_;
    QStringList mapNotes_;
    std::string savedMapJson_;  // the map as in savedMapPath_'s file, to tell unsaved edits
    QString savedMapPath_;
    std::optional<Calibration> alignment_;
    mutable std::optional<Calibration> autoAlignment_;  // cache of displayAlignment()'s fallback
    TakeSolveOptions settings_;
    QVariantMap viewSettings_;
    int selected_ = -1;
    QUndoStack* undoStack_;
    QString lastError_;
    QString heldBecause_;  // why edits are held; empty when they are not

    struct Marker {
        QString label;
        int point = -1;    // take point index
        int mapping = -1;  // index into map_.markers
    };
    std::vector<Marker> markers_;
    std::vector<int> markerOfVertex_;  // vertex -> marker row, -1
};

}  // namespace boneless::ui
