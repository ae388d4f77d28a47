#include "boneless/ui/Document.h"
#include "boneless/ui/Timeline.h"

#include <QFileInfo>
#include <QUndoStack>
#include <algorithm>
#include <cmath>
#include <limits>

#include "Counted.h"
#include "EditCommand.h"
#include "boneless/Alignment.h"
#include "boneless/C3dReader.h"
#include "boneless/Error.h"
#include "boneless/MarkerSuggestion.h"
#include "boneless/MeshReader.h"

namespace boneless::ui {

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

std::string std8(const QString& s) {
    return s.toStdString();
}

}  // namespace

Document::Document(QObject* parent) : QObject(parent), undoStack_(new QUndoStack(this)) {
    map_ = emptyMap();
}

Document::~Document() = default;

bool Document::fail(const QString& message) {
    lastError_ = message;
    emit errorOccurred(message);
    return false;
}

Correspondence Document::emptyMap() const {
    Correspondence map;
    stampMesh(map);
    return map;
}

void Document::stampMesh(Correspondence& map) const {
    if (!hasMesh_) return;
    map.meshFile = std8(QFileInfo(meshPath_).fileName());
    map.meshGroup = std8(meshGroup_);
    map.meshVertices = mesh_.vertexCount();
}

void Document::stampEdit(Correspondence& map) const {
    if (!hasMesh_) return;
    map.meshVertices = mesh_.vertexCount();
    if (map.meshFile.empty()) stampMesh(map);
}

bool Document::readMeshFile(const QString& path, const QString& group, State& state,
                            QString* error) {
    try {
        MeshReadOptions options;
        options.group = std8(group);
        MeshReadResult read = readMesh(std8(path), options);
        state.mesh = std::move(read.mesh);
        state.meshWarnings.clear();
        for (const auto& w : read.warnings) state.meshWarnings << QString::fromStdString(w);
    } catch (const std::exception& e) {
        if (error) *error = QString::fromStdString(e.what());
        return false;
    }
    state.hasMesh = true;
    state.meshPath = path;
    state.meshGroup = group;
    return true;
}

bool Document::readTakeFile(const QString& path, State& state, QString* error) {
    try {
        state.take = readC3d(std8(path));
    } catch (const std::exception& e) {
        if (error) *error = QString::fromStdString(e.what());
        return false;
    }
    if (state.take.frameCount() == 0) {
        if (error) *error = path + ": the take has no frames";
        return false;
    }
    state.hasTake = true;
    state.takePath = path;
    return true;
}

bool Document::loadMesh(const QString& path, const QString& group) {
    State s;
    QString error;
    if (!readMeshFile(path, group, s, &error)) return fail(error);
    hasMesh_ = true;
    mesh_ = std::move(s.mesh);
    meshPath_ = path;
    meshGroup_ = group;
    meshWarnings_ = s.meshWarnings;
    // A map made for another mesh means nothing on this one. An empty one is no map to clear:
    // opening a second mesh said "The marker map (0 markers) ... was cleared".
    try {
        map_.checkMesh(mesh_.vertexCount(), std8(path), &mesh_);
    } catch (const Error&) {
        if (!map_.markers.empty())
            meshWarnings_ << counted(
                int(map_.markers.size()),
                tr("The marker map (%n marker) was made for another mesh and was cleared."),
                tr("The marker map (%n markers) was made for another mesh and was cleared."));
        map_ = emptyMap();
        mapPath_.clear();
        savedMapJson_.clear();
        savedMapPath_.clear();
    }
    if (map_.markers.empty()) map_ = emptyMap();
    alignment_.reset();
    undoStack_->clear();
    rebuildMarkers();
    emit meshChanged();
    emit correspondenceChanged();
    emit alignmentChanged();
    emit changed();
    return true;
}

bool Document::loadTake(const QString& path) {
    State s;
    QString error;
    if (!readTakeFile(path, s, &error)) return fail(error);
    hasTake_ = true;
    take_ = std::move(s.take);
    takePath_ = path;
    applyTakeUnits();  // the session's, as the project keeps them
    bool calibrationReset = noteTake();
    alignment_.reset();
    undoStack_->clear();
    selected_ = -1;
    rebuildMarkers();
    // A calibration frame chosen on the take before: the same number here may show too few of
    // the mapped markers to align at, which Calibrate at This Frame refuses and which left every
    // frame unsolved.
    if (const int frame = settings_.calibrationFrame;
        frame >= 0 && mappedCount() >= kMinAlignmentMarkers) {
        if (const int seen = mappedSeenAt(frame); seen < kMinAlignmentMarkers) {
            takeNotes_ << tr("The calibration frame %1 shows %2 of the %3 mapped markers in this "
                             "take, fewer than the %4 it is aligned at: the take is calibrated "
                             "automatically.")
                              .arg(frameName(frame, take_.firstFrame))
                              .arg(seen)
                              .arg(mappedCount())
                              .arg(kMinAlignmentMarkers);
            settings_.calibrationFrame = -1;
            calibrationReset = true;
        }
    }
    emit takeChanged();
    emit correspondenceChanged();
    emit alignmentChanged();
    emit selectionChanged(-1);
    if (calibrationReset) emit settingsChanged();
    emit changed();
    return true;
}

bool Document::checkCorrespondence(const QString& path) {
    if (refusedWhileHeld()) return false;
    try {
        const Correspondence file = Correspondence::read(std8(path));
        if (hasMesh_) file.checkMesh(mesh_.vertexCount(), std8(meshPath_), &mesh_);
    } catch (const std::exception& e) {
        return fail(QString::fromStdString(e.what()));
    }
    return true;
}

bool Document::loadCorrespondence(const QString& path, MapLoad mode, int* added, int* replaced) {
    if (refusedWhileHeld()) return false;
    EditState after = editState();
    Correspondence file;
    try {
        file = Correspondence::read(std8(path));
        if (hasMesh_) file.checkMesh(mesh_.vertexCount(), std8(meshPath_), &mesh_);
    } catch (const std::exception& e) {
        return fail(QString::fromStdString(e.what()));
    }
    mapNotes_.clear();
    for (const std::string& w : file.warnings) mapNotes_ << QString::fromStdString(w);
    if (replaced) *replaced = 0;
    if (mode == MapLoad::Replace) {
        if (added) *added = int(file.markers.size());
        after.map = std::move(file);
        after.mapPath = path;
        // As the edit will stamp it: a file naming no mesh is not edited by being opened.
        stampEdit(after.map);
        savedMapJson_ = after.map.toJson();
        savedMapPath_ = path;
        pushEdit(tr("Open Correspondence"), std::move(after));  // as File names it
        return true;
    }
    // A suggestion still marked for review is no one's word yet: the file's mapping replaces it.
    // A hand-made or reviewed mapping is the user's, kept.
    const auto toReview = [](const MarkerMapping& mine) {
        return suggestionMark(mine).needsReview;
    };
    int addedHere = 0, replacedHere = 0;
    for (const MarkerMapping& m : file.markers) {
        // A label the take resolves to a marker mapped already ("lfhd", "actor:LFHD" for
        // "LFHD") is that marker: adding it would map it twice, and the file's would win.
        const auto point = hasTake_ ? take_.findPoint(m.label) : std::nullopt;
        const auto clashes = [&](const MarkerMapping& mine) {
            return mine.vertex == m.vertex || mine.label == m.label ||
                   (point && take_.findPoint(mine.label) == point);
        };
        auto& mine = after.map.markers;
        if (std::any_of(mine.begin(), mine.end(),
                        [&](const MarkerMapping& x) { return clashes(x) && !toReview(x); }))
            continue;
        const std::size_t before = mine.size();
        mine.erase(std::remove_if(mine.begin(), mine.end(), clashes), mine.end());
        ++(mine.size() < before ? replacedHere : addedHere);
        mine.push_back(m);
    }
    if (added) *added = addedHere;
    if (replaced) *replaced = replacedHere;
    if (addedHere + replacedHere == 0) return true;  // an empty undo step would undo nothing
    if (after.mapPath.isEmpty()) after.mapPath = path;
    pushEdit(tr("Merge Correspondence"), std::move(after));
    return true;
}

bool Document::saveCorrespondence(const QString& path) {
    Correspondence map = map_;
    stampMesh(map);
    const std::string json = map.toJson();
    // Only a map made for another file or group of the mesh changes by being saved.
    const bool restamped = json != map_.toJson();
    try {
        map.write(std8(path));
    } catch (const std::exception& e) {
        return fail(QString::fromStdString(e.what()));
    }
    map_ = map;
    mapPath_ = path;
    savedMapJson_ = json;
    savedMapPath_ = path;
    // The entries are as they were: the solved frames and a running suggestion still hold, so a
    // save is no correspondenceChanged (it cleared every solved frame and dropped the suggestion).
    if (restamped) emit correspondenceChanged();
    emit changed();
    return true;
}

void Document::reset() {
    hasMesh_ = hasTake_ = false;
    mesh_ = TriMesh();
    take_ = C3dTake();
    meshPath_.clear();
    meshGroup_.clear();
    meshWarnings_.clear();
    takePath_.clear();
    takeNotes_.clear();
    map_ = emptyMap();
    mapPath_.clear();
    savedMapJson_.clear();
    savedMapPath_.clear();
    alignment_.reset();
    autoAlignment_.reset();
    settings_ = TakeSolveOptions();
    viewSettings_.clear();
    startAfresh();
}

bool Document::restoreState(State state) {
    if (state.hasMesh) {
        try {
            state.map.checkMesh(state.mesh.vertexCount(), std8(state.meshPath), &state.mesh);
        } catch (const std::exception& e) {
            return fail(QString::fromStdString(e.what()));
        }
    }
    hasMesh_ = state.hasMesh;
    mesh_ = std::move(state.mesh);
    meshPath_ = state.meshPath;
    meshGroup_ = state.meshGroup;
    meshWarnings_ = state.meshWarnings;
    hasTake_ = state.hasTake;
    take_ = std::move(state.take);
    takePath_ = state.takePath;
    map_ = std::move(state.map);
    if (map_.markers.empty()) map_ = emptyMap();
    stampEdit(map_);  // both sides stamped alike: a file naming no mesh is not an edit
    mapPath_ = state.mapPath;
    savedMapJson_.clear();
    savedMapPath_.clear();
    if (!mapPath_.isEmpty() && QFileInfo::exists(mapPath_)) {
        try {
            Correspondence saved = Correspondence::read(std8(mapPath_));
            stampEdit(saved);
            savedMapJson_ = saved.toJson();
            savedMapPath_ = mapPath_;
        } catch (const std::exception&) {
            // An unreadable file just means the project's map counts as unsaved.
        }
    }
    alignment_ = state.alignment;
    settings_ = state.settings;
    settings_.alignment.reset();
    applyTakeUnits();
    // A project whose take was cut short since (a truncated copy) says so, as the take would.
    if (noteTake()) alignment_.reset();
    viewSettings_ = state.viewSettings;
    startAfresh();
    return true;
}

QString Document::takeUnitsName(const std::string& units) {
    static const std::pair<const char*, const char*> names[] = {
        {"file", QT_TR_NOOP("From the File")},  {"mm", QT_TR_NOOP("Millimetres (mm)")},
        {"cm", QT_TR_NOOP("Centimetres (cm)")}, {"dm", QT_TR_NOOP("Decimetres (dm)")},
        {"m", QT_TR_NOOP("Metres (m)")},        {"in", QT_TR_NOOP("Inches (in)")},
        {"ft", QT_TR_NOOP("Feet (ft)")}};
    for (const auto& [key, name] : names)
        if (units == key) return tr(name);
    return QString::fromStdString(units);
}

void Document::applyTakeUnits() {
    if (!hasTake_) return;
    try {
        setTakeUnits(take_, settings_.takeUnits, kTakeUnitsFrom);
    } catch (const std::exception& e) {
        fail(QString::fromStdString(e.what()));  // the options table's choices: never
    }
}

bool Document::noteTake() {
    takeNotes_.clear();
    for (const auto& w : take_.warnings) {
        if (w != take_.markerSpan.doubt) {
            takeNotes_ << QString::fromStdString(w);
            continue;
        }
        // The fix first, in this window: the file is another tool's to edit.
        const QString menu =
            tr("Edit → Take Units → %1").arg(takeUnitsName(take_.markerSpan.likelyUnits));
        const QString units = QString::fromStdString(take_.markerSpan.likelyUnits);
        takeNotes_ << (take_.unitsFrom.empty()
                           ? tr("%1: choose %2, or set the file's POINT:UNITS to %3.")
                                 .arg(QString::fromStdString(w), menu, units)
                           : tr("%1: choose %2 instead.").arg(QString::fromStdString(w), menu));
    }
    if (!hasTake_ || settings_.calibrationFrame < frameCount()) return false;
    // Every frame would fail on it.
    takeNotes_ << tr("The calibration frame %1 is past this take's %2 frames: the take is "
                     "calibrated automatically.")
                      .arg(frameName(settings_.calibrationFrame, take_.firstFrame))
                      .arg(frameCount());
    settings_.calibrationFrame = -1;
    return true;
}

// After the whole state was replaced: no selection, no undo history into the old state, and every
// view told.
void Document::startAfresh() {
    selected_ = -1;
    undoStack_->clear();
    rebuildMarkers();
    emit meshChanged();
    emit takeChanged();
    emit correspondenceChanged();
    emit alignmentChanged();
    emit settingsChanged();
    emit viewSettingsChanged();
    emit selectionChanged(-1);
    emit changed();
}

int Document::frameCount() const {
    return hasTake_ ? static_cast<int>(take_.frameCount()) : 0;
}

double Document::frameRate() const {
    return hasTake_ ? take_.rate : 0.0;
}

void Document::rebuildMarkers() {
    autoAlignment_.reset();
    markers_.clear();
    if (hasTake_) {
        // A marker is named as a map names it: without the subject ("LFWT" for "Male:LFWT") unless
        // another subject wears that name, so the list's narrow column tells L from R.
        for (std::size_t p : take_.markerIndices())
            markers_.push_back({QString::fromStdString(take_.shortLabel(p)), int(p), -1});
    }
    for (int i = 0; i < static_cast<int>(map_.markers.size()); ++i) {
        const MarkerMapping& m = map_.markers[i];
        if (!hasTake_) {
            markers_.push_back({QString::fromStdString(m.label), -1, i});
            continue;
        }
        const auto point = take_.findPoint(m.label);
        if (!point) continue;
        for (auto& row : markers_)
            if (row.point == int(*point)) row.mapping = i;
    }
    markerOfVertex_.assign(hasMesh_ ? mesh_.vertexCount() : 0, -1);
    for (int r = 0; r < markerCount(); ++r) {
        const int v = mappedVertex(r);
        if (v >= 0 && v < int(markerOfVertex_.size())) markerOfVertex_[v] = r;
    }
    if (selected_ >= markerCount()) selected_ = -1;
}

QString Document::markerLabel(int marker) const {
    return marker >= 0 && marker < markerCount() ? markers_[marker].label : QString();
}

int Document::markerPoint(int marker) const {
    return marker >= 0 && marker < markerCount() ? markers_[marker].point : -1;
}

int Document::mappedVertex(int marker) const {
    return mappedPoint(marker).vertex;
}

SurfacePoint Document::mappedPoint(int marker) const {
    if (marker < 0 || marker >= markerCount() || markers_[marker].mapping < 0) return {};
    return surfacePoint(map_.markers[markers_[marker].mapping]);
}

QString Document::sharedLabelText(int marker) const {
    const int point = markerPoint(marker);
    if (point < 0) return {};
    const std::vector<std::size_t> named = take_.pointsNamed(take_.points[point].label);
    return named.size() > 1 ? QString::fromStdString(take_.sharedLabelText(named)) : QString();
}

double Document::markerOffsetMm(int marker) const {
    if (marker < 0 || marker >= markerCount() || markers_[marker].mapping < 0) return 0.0;
    return map_.markers[markers_[marker].mapping].offsetMm;
}

bool Document::markerSuggested(int marker) const {
    if (marker < 0 || marker >= markerCount() || markers_[marker].mapping < 0) return false;
    return suggestionMark(map_.markers[markers_[marker].mapping]).suggested;
}

QString Document::markerReviewReason(int marker) const {
    if (marker < 0 || marker >= markerCount() || markers_[marker].mapping < 0) return {};
    return QString::fromStdString(
        suggestionMark(map_.markers[markers_[marker].mapping]).reviewReason);
}

int Document::markerForVertex(int vertex) const {
    return vertex >= 0 && vertex < int(markerOfVertex_.size()) ? markerOfVertex_[vertex] : -1;
}

int Document::markerByLabel(const QString& label) const {
    for (int r = 0; r < markerCount(); ++r)
        if (markers_[r].label.compare(label, Qt::CaseInsensitive) == 0) return r;
    if (hasTake_) {  // "LFHD" for "actor:LFHD"
        const auto point = take_.findPoint(std8(label));
        for (int r = 0; point && r < markerCount(); ++r)
            if (markers_[r].point == int(*point)) return r;
    }
    return -1;
}

bool Document::markerVisible(int marker, int frame) const {
    const int p = markerPoint(marker);
    if (p < 0 || frame < 0 || frame >= frameCount()) return false;
    return take_.samples.valid(frame, p);
}

int Document::mappedCount() const {
    int n = 0;
    for (const auto& m : markers_) n += m.mapping >= 0;
    return n;
}

Positions Document::markerPositions(int frame) const {
    if (!hasTake_) return Positions();
    Positions P = Positions::Constant(markerCount(), 3, kNaN);
    if (frame < 0 || frame >= frameCount()) return P;
    const Similarity s = displayAlignment().takeToMesh;
    for (int r = 0; r < markerCount(); ++r)
        if (const auto x = take_.samples.position(frame, markers_[r].point))
            P.row(r) = s.apply(*x).transpose();
    return P;
}

}  // namespace boneless::ui
