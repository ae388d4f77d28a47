// Document: the undoable edits of the map, the alignment and the settings, and what solving needs.
#include <QFileInfo>
#include <QUndoStack>
#include <algorithm>
#include <cmath>
#include <nlohmann/json.hpp>

#include "Counted.h"
#include "EditCommand.h"
#include "boneless/Error.h"
#include "boneless/MarkerSuggestion.h"
#include "boneless/SolveFits.h"
#include "boneless/TakeOptionsJson.h"
#include "boneless/ui/Document.h"
#include "boneless/ui/Timeline.h"

namespace boneless::ui {

namespace {

bool sameAlignment(const std::optional<Calibration>& a, const std::optional<Calibration>& b) {
    return a.has_value() == b.has_value() &&
           (!a || (a->takeToMesh.R == b->takeToMesh.R && a->takeToMesh.t == b->takeToMesh.t &&
                   a->takeToMesh.scale == b->takeToMesh.scale));
}

// As the project stores them.
bool sameSettings(const TakeSolveOptions& a, const TakeSolveOptions& b) {
    return toJson(a) == toJson(b);
}

std::string withoutSuggested(const std::string& extraJson) {
    nlohmann::json extra =
        nlohmann::json::parse(extraJson.empty() ? "{}" : extraJson, nullptr, false);
    if (!extra.is_object()) return "{}";
    for (const char* key : {"suggested", "needs_review", "review_reason"}) extra.erase(key);
    return extra.dump();
}

}  // namespace

Document::EditState Document::editState() const {
    return {map_, mapPath_, alignment_, settings_};
}

void Document::applyEditState(const EditState& state) {
    const bool alignmentChangedToo = !sameAlignment(alignment_, state.alignment);
    const bool settingsChangedToo = !sameSettings(settings_, state.settings);
    const bool unitsChanged = settings_.takeUnits != state.settings.takeUnits;
    map_ = state.map;
    mapPath_ = state.mapPath;
    alignment_ = state.alignment;
    settings_ = state.settings;
    // The take's coordinates stay as they are: what they measure in mm changes, and the marker
    // span is judged again. settingsChanged tells the solver and the view.
    if (unitsChanged) {
        applyTakeUnits();
        noteTake();
        autoAlignment_.reset();
    }
    rebuildMarkers();
    emit correspondenceChanged();
    if (alignmentChangedToo) emit alignmentChanged();
    if (settingsChangedToo) emit settingsChanged();
    emit changed();
}

void Document::pushEdit(const QString& text, EditState after) {
    stampEdit(after.map);
    undoStack_->push(new EditCommand(this, text, editState(), std::move(after)));
}

void Document::holdEdits(const QString& reason) {
    if (reason == heldBecause_) return;
    const bool was = editsHeld();
    heldBecause_ = reason;
    if (editsHeld() != was) emit editsHeldChanged(editsHeld());
}

bool Document::refusedWhileHeld() {
    if (!editsHeld()) return false;
    fail(heldBecause_);
    return true;
}

void Document::discardEdits(const QString& text) {
    if (undoStack_->cleanIndex() >= 0) {
        undoStack_->setIndex(undoStack_->cleanIndex());
        return;
    }
    EditState none{emptyMap(), {}, std::nullopt, TakeSolveOptions()};
    if (map_.toJson() == none.map.toJson() && !alignment_ && sameSettings(settings_, none.settings))
        return;
    pushEdit(text, std::move(none));
}

bool Document::assign(int marker, const SurfacePoint& point) {
    if (refusedWhileHeld()) return false;
    if (!hasMesh_) return fail(tr("Load a mesh before mapping markers."));
    if (marker < 0 || marker >= markerCount()) return fail(tr("No marker is selected."));
    // Its entry would name both points, and the solver refuses that (Correspondence::resolve).
    if (const QString shared = sharedLabelText(marker); !shared.isEmpty())
        return fail(tr("%1 cannot be mapped: in %2, %3, so no map label can say which; relabel one "
                       "of them in the take.")
                        .arg(markerLabel(marker), QFileInfo(takePath_).fileName(), shared));
    const int vertex = point.vertex;
    if (vertex < 0 || vertex >= mesh_.vertexCount())
        return fail(
            tr("Vertex %1 is not on the mesh (%2 vertices).").arg(vertex).arg(mesh_.vertexCount()));
    if (point.face >= mesh_.faceCount() ||
        (point.face >= 0 && (mesh_.F.row(point.face).array() != vertex).all()))
        return fail(tr("Face %1 is not a face of vertex %2.").arg(point.face).arg(vertex));
    const int other = markerForVertex(vertex);
    if (other >= 0 && other != marker)
        return fail(tr("Vertex %1 already carries marker %2; clear that marker first.")
                        .arg(vertex)
                        .arg(markerLabel(other)));
    // Where the entry says the marker sits: a click names a point of a face, a typed number the
    // vertex itself (version 1's meaning, no face).
    auto place = [&](MarkerMapping& m) {
        m.vertex = vertex;
        m.face = point.face;
        m.barycentric = point.face >= 0
                            ? std::array<double, 3>{point.barycentric[0], point.barycentric[1],
                                                    point.barycentric[2]}
                            : std::array<double, 3>{1.0, 0.0, 0.0};
    };
    const QString where = point.face >= 0 ? tr("face %1 by vertex %2").arg(point.face).arg(vertex)
                                          : tr("vertex %1").arg(vertex);
    const int mapping = markers_[marker].mapping;
    if (other == marker) {
        // Mapping a suggestion again by its own vertex is the user's word that it is right.
        EditState after = editState();
        MarkerMapping& m = after.map.markers[mapping];
        const SurfacePoint now = surfacePoint(m);
        const bool moved =
            now.face != point.face ||
            (point.face >= 0 && (now.barycentric - point.barycentric).cwiseAbs().maxCoeff() > 1e-9);
        const auto json =
            nlohmann::json::parse(m.extraJson.empty() ? "{}" : m.extraJson, nullptr, false);
        const bool suggested = json.is_object() && json.contains("suggested");
        if (!moved && !suggested) return true;
        place(m);
        m.extraJson = withoutSuggested(m.extraJson);
        pushEdit(moved ? tr("Move %1 to %2").arg(markerLabel(marker), where)
                       : tr("Confirm %1 on %2").arg(markerLabel(marker), where),
                 std::move(after));
        return true;
    }
    EditState after = editState();
    if (mapping >= 0) {
        MarkerMapping& m = after.map.markers[mapping];
        place(m);
        m.extraJson = withoutSuggested(m.extraJson);
    } else {
        MarkerMapping m;
        // The row's name is already the bare one ("LFHD" of "actor:LFHD") where that still names
        // this point, which keeps the map usable for other actors' takes.
        m.label = markers_[marker].label.toStdString();
        place(m);
        m.extraJson = "{}";
        // Markers of one set sit alike off the skin: a new one takes the median of those mapped,
        // the first kFirstOffsetMm (at 0 every later one stayed 0, the skin pulled out to them).
        m.offsetMm = kFirstOffsetMm;
        std::vector<double> offsets;
        for (const auto& mapped : after.map.markers) offsets.push_back(mapped.offsetMm);
        if (!offsets.empty()) {
            std::nth_element(offsets.begin(), offsets.begin() + offsets.size() / 2, offsets.end());
            m.offsetMm = offsets[offsets.size() / 2];
        }
        after.map.markers.push_back(std::move(m));
    }
    pushEdit(tr("Map %1 to %2").arg(markerLabel(marker), where), std::move(after));
    return true;
}

bool Document::clearMapping(int marker) {
    if (refusedWhileHeld()) return false;
    if (marker < 0 || marker >= markerCount()) return fail(tr("No marker is selected."));
    const int mapping = markers_[marker].mapping;
    if (mapping < 0) return true;
    EditState after = editState();
    after.map.markers.erase(after.map.markers.begin() + mapping);
    pushEdit(tr("Clear %1").arg(markerLabel(marker)), std::move(after));
    return true;
}

bool Document::setOffsetMm(const std::vector<int>& markers, double mm) {
    if (refusedWhileHeld()) return false;
    if (!(mm >= Correspondence::kMinOffsetMm && mm <= Correspondence::kMaxOffsetMm))
        return fail(tr("An offset off the skin of %1 mm is not a marker's: from %2 to %3 mm.")
                        .arg(mm)
                        .arg(Correspondence::kMinOffsetMm)
                        .arg(Correspondence::kMaxOffsetMm));
    EditState after = editState();
    int changed = 0;
    for (int marker : markers) {
        if (marker < 0 || marker >= markerCount() || markers_[marker].mapping < 0) continue;
        double& offset = after.map.markers[markers_[marker].mapping].offsetMm;
        changed += offset != mm;
        offset = mm;
    }
    if (changed == 0) return true;
    const QString what = markers.size() == 1 ? markerLabel(markers.front())
                                             : counted(changed, tr("%n marker"), tr("%n markers"));
    pushEdit(tr("Set the offset of %1 to %2 mm").arg(what).arg(mm), std::move(after));
    return true;
}

bool Document::clearAllMappings() {
    if (refusedWhileHeld()) return false;
    if (map_.markers.empty()) return true;
    EditState after = editState();
    after.map.markers.clear();
    pushEdit(tr("Clear all markers"), std::move(after));
    return true;
}

bool Document::canSuggest() {
    if (refusedWhileHeld()) return false;
    if (!hasMesh_ || !hasTake_) return fail(tr("Suggesting needs a mesh and a take."));
    // Said here, not as "Suggest Rest failed." with the reason under Show Details.
    if (map_.markers.size() < 4)
        return fail(tr("Map at least 4 markers to suggest the rest: the take is aligned from them "
                       "(%1 mapped).")
                        .arg(map_.markers.size()));
    return true;
}

Document::SuggestInputs Document::suggestInputs() const {
    return {mesh_, take_, map_, settings_.meshUp};
}

Suggestion Document::suggest(const SuggestInputs& inputs, const std::atomic<bool>* stop) {
    return boneless::suggestMappings(inputs.mesh, inputs.take, inputs.map, inputs.meshUp, stop);
}

void Document::applySuggestion(Suggestion s) {
    if (s.suggested == 0) return;
    EditState after = editState();
    after.map = std::move(s.map);
    pushEdit(counted(s.suggested, tr("Suggest %n marker"), tr("Suggest %n markers")),
             std::move(after));
}

std::optional<Calibration> Document::solverAlignment(const EditState& state, int frame,
                                                     QString* error) const {
    QString why;
    if (!canSolve(&why)) {
        if (error) *error = why;
        return std::nullopt;
    }
    try {
        // The solver's own calibration also corrects for the markers' offsets off the skin, so
        // a fixed alignment is exactly what an automatic solve would have used.
        TakeSolveOptions options = state.settings;
        options.alignment.reset();
        options.calibrationFrame = frame;
        options.calibrate = CalibrateMode::None;  // the alignment alone, not the fit
        TakeSolver solver(mesh_, take_, state.map, options);
        return solver.calibration();
    } catch (const std::exception& e) {
        if (error) *error = QString::fromStdString(e.what());
        return std::nullopt;
    }
}

bool Document::fitAlignment(int frame, EditState& after) {
    QString error;
    const std::optional<Calibration> found = solverAlignment(after, frame, &error);
    if (!found) return fail(error);
    after.alignment = found;
    return true;
}

std::optional<Calibration> Document::alignmentAt(int frame) const {
    return solverAlignment(editState(), frame, nullptr);
}

bool Document::align(int calibrationFrame) {
    if (refusedWhileHeld()) return false;
    EditState after = editState();
    if (!fitAlignment(calibrationFrame, after)) return false;
    pushEdit(tr("Align take"), std::move(after));
    return true;
}

bool Document::clearAlignment() {
    if (refusedWhileHeld()) return false;
    if (!alignment_) return true;
    EditState after = editState();
    after.alignment.reset();
    pushEdit(tr("Clear alignment"), std::move(after));
    return true;
}

Calibration Document::displayAlignment() const {
    if (alignment_) return *alignment_;
    if (autoAlignment_) return *autoAlignment_;
    Calibration c;
    if (!hasTake_ || !hasMesh_) return c;
    std::vector<std::size_t> points;
    Positions rest(0, 3);
    for (const auto& m : markers_) {
        if (m.mapping < 0) continue;
        points.push_back(m.point);
        rest.conservativeResize(rest.rows() + 1, 3);
        rest.row(rest.rows() - 1) = mesh_.V.row(map_.markers[m.mapping].vertex);
    }
    bool found = false;
    if (points.size() >= 3) {
        try {
            c = calibrate(take_, points, rest);
            found = true;
        } catch (const std::exception&) {
            // Collinear or hidden markers: fall back to roughAlignment below.
        }
    }
    if (!found) {
        // Upright and the mesh's size, from conventions: enough to see the markers on the mesh
        // before three are mapped.
        std::vector<std::size_t> all;
        for (const auto& m : markers_) all.push_back(m.point);
        c = roughAlignment(take_, all, mesh_);
    }
    autoAlignment_ = c;
    return c;
}

void Document::setSettings(const TakeSolveOptions& settings, const QString& text) {
    if (refusedWhileHeld()) return;
    EditState after = editState();
    after.settings = settings;
    after.settings.alignment.reset();
    if (sameSettings(after.settings, settings_)) return;
    // The user's alignment was levelled onto the mesh's up: another up refits it at its frame, as
    // another calibration frame does, or the view and the exports would keep the old one.
    if (alignment_ && after.settings.meshUp != settings_.meshUp &&
        !fitAlignment(alignment_->frame, after))
        return;
    pushEdit(text.isEmpty() ? tr("Change the solver settings") : text, std::move(after));
}

int Document::mappedSeenAt(int frame) const {
    int seen = 0;
    for (int r = 0; r < markerCount(); ++r)
        seen += markers_[r].mapping >= 0 && markerVisible(r, frame);
    return seen;
}

bool Document::calibrateAt(int frame) {
    if (refusedWhileHeld()) return false;
    // Taken, a frame that aligns nothing left every frame unsolved, the reason under Show Details.
    if (frame >= 0 && hasTake_) {
        const int seen = mappedSeenAt(frame);
        if (seen < kMinAlignmentMarkers)
            return fail(tr("Frame %1 shows %2 of the %3 mapped markers: calibrating needs at least "
                           "%4 seen at once. The calibration is kept as it was; choose a frame "
                           "that shows more.")
                            .arg(frameName(frame, take_.firstFrame))
                            .arg(seen)
                            .arg(mappedCount())
                            .arg(kMinAlignmentMarkers));
    }
    EditState after = editState();
    after.settings.calibrationFrame = frame;
    after.settings.calibrate = CalibrateMode::Shape;
    if (alignment_ && !fitAlignment(frame, after)) return false;
    if (sameSettings(after.settings, settings_) && sameAlignment(after.alignment, alignment_))
        return true;
    // Named as the Edit menu names them: Undo and Redo say "Undo Calibrate Automatically".
    pushEdit(frame >= 0 ? tr("Calibrate at Frame %1").arg(frameName(frame, take_.firstFrame))
                        : tr("Calibrate Automatically"),
             std::move(after));
    return true;
}

TakeSolveOptions Document::solveOptions() const {
    // A project may keep a fold guard for the exact solver; local-global reads none, and an
    // export's sidecar recorded it as an option it was solved with.
    TakeSolveOptions options = withoutUnusedExactOptions(settings_);
    options.alignment.reset();
    if (alignment_) {
        options.alignment = alignment_->takeToMesh;
        options.calibrationFrame = alignment_->frame;
    }
    return options;
}

void Document::setViewSetting(const QString& key, const QVariant& value) {
    if (viewSettings_.value(key) == value) return;
    viewSettings_.insert(key, value);
    emit viewSettingsChanged();
    emit changed();
}

void Document::setViewSettings(const QVariantMap& settings) {
    viewSettings_ = settings;
    emit viewSettingsChanged();
    emit changed();
}

void Document::setSelectedMarker(int marker) {
    if (marker < -1 || marker >= markerCount()) marker = -1;
    if (marker == selected_) return;
    selected_ = marker;
    emit selectionChanged(marker);
}

bool Document::canSolve(QString* why, QString* detail) const {
    auto no = [&](const QString& reason) {
        if (why) *why = reason;
        return false;
    };
    if (!hasMesh_) return no(tr("No mesh is loaded."));
    // Before the take: loading one would not help.
    if (const QString refusal = memoryRefusal(); !refusal.isEmpty()) return no(refusal);
    if (!hasTake_) return no(tr("No take is loaded."));
    QStringList unknown, shared, refused;
    int resolved = 0;
    for (const auto& m : map_.markers) {
        const std::vector<std::size_t> named = take_.pointsNamed(m.label);
        if (named.empty())
            unknown << QString::fromStdString(m.label);
        else if (named.size() > 1 && take_.pointsNamed(take_.points[named.front()].label) == named)
            shared << QString::fromStdString(take_.sharedLabelText(named));
        else if (const std::string problem = Correspondence::labelProblem(take_, m.label);
                 !problem.empty())
            refused << QString::fromStdString(problem);  // two subjects wear it, a model output
        else
            ++resolved;
    }
    // Two points with one full label, not two subjects: no label can say which (core refuses it).
    shared.removeDuplicates();  // "LFWT" and "Male:LFWT" name one group
    if (!shared.isEmpty()) {
        if (detail) *detail = tr("In the take, %1.").arg(shared.join("; "));
        return no(counted(shared.size(),
                          tr("The map names %n label that points of the take share (%1): no map "
                             "label can say which; relabel one of them in the take, or open a "
                             "map without it."),
                          tr("The map names %n labels that points of the take share (%1): no map "
                             "label can say which; relabel one of each in the take, or open a "
                             "map without them."))
                      .arg(shared.first()));
    }
    // Core's words, as the solve would refuse the map: the first, and every one in the details.
    if (!refused.isEmpty()) {
        if (detail) *detail = refused.join(".\n") + ".";
        return no(refused.size() == 1
                      ? refused.first() + "."
                      : counted(refused.size() - 1,
                                tr("%1; and %n more label of the map cannot be solved."),
                                tr("%1; and %n more labels of the map cannot be solved."))
                            .arg(refused.first()));
    }
    if (!unknown.isEmpty()) {
        if (detail) *detail = tr("Not in the take: %1.").arg(unknown.join(", "));
        return no(counted(unknown.size(),
                          tr("The map names %n marker the take does not have (%1): open this "
                             "take's map, or Edit → Clear All Mappings and map anew."),
                          tr("The map names %n markers the take does not have (%1): open this "
                             "take's map, or Edit → Clear All Mappings and map anew."))
                      .arg(firstFew(unknown)));
    }
    if (resolved < 3) return no(tr("Map at least 3 markers to solve (%1 mapped).").arg(resolved));
    return true;
}

QString Document::memoryRefusal() const {
    if (!hasMesh_) return {};
    try {
        checkSolveFits(mesh_, meshPath_.toStdString(), settings_.solver.method);
    } catch (const Error& e) {
        return QString::fromStdString(e.what());
    }
    return {};
}

bool Document::correspondenceModified() const {
    // Undo and redo across a Save Correspondence As bring back the path before it, and the map of
    // either side: compared with the file it was not read from, it passed for that file's.
    return mapPath_.isEmpty() || mapPath_ != savedMapPath_ || map_.toJson() != savedMapJson_;
}

ExportRequest Document::exportRequest(const QString& outDir, ExportFormat format) const {
    ExportRequest r;
    r.meshPath = meshPath_.toStdString();
    r.group = meshGroup_.toStdString();
    r.c3dPath = takePath_.toStdString();
    if (!correspondenceModified()) r.mapPath = mapPath_.toStdString();
    r.outDir = outDir.toStdString();
    r.format = format;
    r.options = solveOptions();
    return r;
}

}  // namespace boneless::ui
