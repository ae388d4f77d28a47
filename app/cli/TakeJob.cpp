#include "TakeJob.h"

#include <unistd.h>
#include <algorithm>
#include <atomic>
#include <chrono>
#include <csignal>
#include <cstdio>
#include <ctime>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <optional>

#include "FrameRange.h"
#include "OptionFlags.h"
#include "boneless/Alignment.h"
#include "boneless/C3dFrameReader.h"
#include "boneless/C3dReader.h"
#include "boneless/Error.h"
#include "boneless/MarkerSuggestion.h"
#include "boneless/MeshReader.h"
#include "boneless/OutputFolder.h"
#include "boneless/ProgressPace.h"
#include "boneless/Reconstruction.h"
#include "boneless/TakeOptionsJson.h"
#include "boneless/Text.h"

using namespace boneless;

namespace {

std::atomic<int> stopSignal{0};         // the signal that stopped the run; 0 while none has
int stopSignalsHeld = 0;                // StopSignals alive; the outermost installs and restores
std::atomic<long long> firstStopNs{0};  // when it came (CLOCK_MONOTONIC)
extern "C" void onStopSignal(int signal) {
    timespec now{};
    ::clock_gettime(CLOCK_MONOTONIC, &now);  // async-signal-safe, as raise and signal are
    const long long ns = now.tv_sec * 1000000000LL + now.tv_nsec;
    // A second one a second or more later is a user who will not wait for a long read or
    // preparation to end: it ends the process, as the signal would have. One sooner is the same
    // stop come twice (timeout sends it to the process and to its group).
    if (stopSignal != 0) {
        if (ns - firstStopNs.load() < 1000000000LL) return;
        std::signal(signal, SIG_DFL);
        std::raise(signal);
        return;
    }
    firstStopNs = ns;
    stopSignal = signal;
}

std::string stoppedBy() {
    return stopSignal == SIGTERM ? "stopped by SIGTERM" : "interrupted";
}

void progress(int done, int total, double elapsedSeconds, const FrameReport& last,
              ProgressPace& pace) {
    // On a terminal the bar redraws in place; into a log it is a line as ProgressPace paces it.
    static const bool terminal = ::isatty(STDERR_FILENO);
    if (!terminal && !pace.due(done, elapsedSeconds)) return;
    const int width = 30;
    const int filled = total ? width * done / total : width;
    const double perFrame = done ? elapsedSeconds / done : 0;
    const int eta = static_cast<int>(perFrame * (total - done) + 0.5);
    std::fprintf(stderr, "%s[%.*s%.*s] %d/%d frames  %.3f s/frame  ETA %d:%02d  residual %.1f mm%s",
                 terminal ? "\r" : "", filled, "##############################", width - filled,
                 "..............................", done, total, perFrame, eta / 60, eta % 60,
                 last.residualRmsMm, terminal ? " " : "\n");
    std::fflush(stderr);
}

}  // namespace

StopSignals::StopSignals() {
    if (stopSignalsHeld++ > 0) return;
    stopSignal = 0;
    sigint_ = std::signal(SIGINT, onStopSignal);
    sigterm_ = std::signal(SIGTERM, onStopSignal);
}

StopSignals::~StopSignals() {
    if (--stopSignalsHeld > 0) return;
    std::signal(SIGINT, sigint_);
    std::signal(SIGTERM, sigterm_);
}

int StopSignals::received() {
    return stopSignal.load();
}

void StopSignals::throwIfReceived(const std::string& when) {
    if (stopSignal != 0) throw TakeJobInterrupted(stoppedBy() + " " + when, stopSignal);
}

namespace {

std::vector<std::string> formatNames() {
    std::vector<std::string> names;
    for (const ExportFormatInfo& f : exportFormats()) names.push_back(f.name);
    return names;
}

}  // namespace

// Said even when quiet: without it, a stretch where the actor left the volume plays as a pose
// frozen on purpose. The warning without the take's name, or "" when no frame is held.
static std::string heldFramesWarning(const ExportResult& result) {
    if (result.held.empty()) return "";
    std::vector<std::string> runs;
    int frames = 0;
    for (const auto& [first, last] : result.held) {
        runs.push_back(first == last ? std::to_string(first)
                                     : std::to_string(first) + " to " + std::to_string(last));
        frames += last - first + 1;
    }
    return std::string(frames == 1 ? "frame " : "frames ") + joined(runs) +
           (frames == 1 ? " shows" : " show") + " no marker; " +
           (frames == 1 ? "it holds" : "each holds") +
           " the pose of the nearest frame that shows one";
}

// The sidecar's quality figures, so a run's stretch and fit are seen without opening it.
static void printSummary(const nlohmann::json& sidecar) {
    const nlohmann::json& s = sidecar.at("summary");
    const nlohmann::json& c = sidecar.at("calibration");
    // null when every frame held a neighbour's pose: then there is no residual to give.
    char residual[96] = "none (no frame shows a marker)";
    if (!s.at("residual_rms_mm_mean").is_null())
        std::snprintf(residual, sizeof residual, "%.2f mm mean, %.2f mm worst frame",
                      s.at("residual_rms_mm_mean").get<double>(),
                      s.at("residual_rms_mm_worst_frame").get<double>());
    std::fprintf(stderr,
                 "calibrate %s: marker residual RMS %s; edge "
                 "distortion RMS %.3f mean, %.3f worst frame; 95th percentile edge strain %.3f "
                 "worst frame; folded faces %d worst frame; dent ratio %.2f worst frame\n",
                 c.at("calibrate").get<std::string>().c_str(), residual,
                 s.at("edge_distortion_mean").get<double>(),
                 s.at("edge_distortion_worst_frame").get<double>(),
                 s.at("edge_strain_p95_worst_frame").get<double>(),
                 s.at("folded_faces_worst_frame").get<int>(),
                 s.at("dent_ratio_worst_frame").get<double>());
}

void addTakeJobOptions(CLI::App* cmd, TakeJob& job) {
    std::string formats;
    for (const ExportFormatInfo& f : exportFormats())
        formats += std::string(formats.empty() ? "" : "; ") + f.name + ": " + f.description;
    cmd->add_option("--format", job.format, withDefault(formats, job.format))
        ->check(CLI::IsMember(formatNames()));
    cmd->add_option("--frames", job.frames, "Frame range A:B (0-based, B excluded; A: or :B)");
    addOptionFlags(cmd, job.options, toJson(TakeSolveOptions{}), false);
    cmd->add_flag("--write-calibrated-rest", job.writeCalibratedRest,
                  "Also write <stem>_calibrated_rest.obj, the rest fitted to the actor");
}

void refuseDoubtfulUnits(const C3dTake& take, const std::string& outcome, bool keys) {
    const MarkerSpan& span = take.markerSpan;
    if (span.doubt.empty()) return;
    // The option first: it fixes the solve without another tool; the file is for every reader.
    const std::string give = "give " + takeUnitsName(keys) +
                             (keys ? ": \"" + span.likelyUnits + "\"" : " " + span.likelyUnits);
    if (!take.unitsFrom.empty())
        throw Error(take.file + ": " + span.doubt + "; " + outcome + ": " + give + " instead");
    throw Error(take.file + ": " + span.doubt + "; " + outcome + ": " + give +
                ", or set the file's POINT:UNITS to " + span.likelyUnits +
                " (Mokka, or ezc3d or btk in a script), or scale its coordinates");
}

std::string takeUnitsName(bool keys) {
    return keys ? "\"take_units\"" : "--take-units";
}

void applyTakeUnits(C3dTake& take, const nlohmann::json& options) {
    TakeSolveOptions o;
    fromJson(options, o, "options");
    setTakeUnits(take, o.takeUnits, takeUnitsName(false));  // "file" leaves a take as read
}

std::string unitsText(const C3dTake& take) {
    if (take.unitsFrom.empty()) return take.units;
    const std::string file = c3dFileUnits(take);
    return take.units + " (" + take.unitsFrom + "; the file says " +
           (file.empty() ? "none" : file) + ")";
}

// A word as a shell takes it back: "Walker Body" quoted, so that the hint can be pasted.
static std::string shellWord(const std::string& word) {
    if (!word.empty() &&
        word.find_first_not_of("ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz"
                               "0123456789._-/:+@%,") == std::string::npos)
        return word;
    std::string quoted = "'";
    for (char c : word) quoted += c == '\'' ? std::string("'\\''") : std::string(1, c);
    return quoted + "'";
}

void checkMapFitsMesh(const Correspondence& map, const TriMesh& mesh, const std::string& meshPath,
                      const std::string& group, bool keys) {
    try {
        map.checkMesh(mesh.vertexCount(), meshPath, &mesh);
    } catch (const Error& e) {
        if (map.meshGroup.empty() || map.meshGroup == group) throw;
        // The hint only where it helps: a mesh without the map's group would refuse it next.
        const std::vector<ObjGroup> groups = objGroups(meshPath);
        if (std::none_of(groups.begin(), groups.end(),
                         [&](const ObjGroup& g) { return g.name == map.meshGroup; }))
            throw;
        // A manifest's entry takes a key, not a flag.
        throw Error(std::string(e.what()) + "; open it with " +
                    (keys ? "\"group\": \"" + map.meshGroup + "\""
                          : "--group " + shellWord(map.meshGroup)));
    }
}

std::string takeJobSidecar(const TakeJob& job) {
    ExportRequest request;
    request.meshPath = job.mesh;
    request.group = job.group;
    return (std::filesystem::path(job.out) / (exportStem(request) + ".json")).string();
}

namespace {

// OBJ frames of an earlier run that this one did not write would play as part of this take in a
// tool that reads the folder by pattern (Houdini's <stem>_$F4.obj); they are the user's to remove.
// The note, or "" when there are none.
std::string otherFramesNote(const std::string& out, const std::string& stem,
                            const ExportResult& r) {
    std::vector<int> others;
    for (int frame : objFramesIn(out, stem))
        if (frame < r.first || frame >= r.first + r.framesWritten) others.push_back(frame);
    if (others.empty()) return "";
    // As runs ("0 to 2 and 6 to 9"): the lowest and highest alone took in the frames just written.
    std::sort(others.begin(), others.end());
    std::vector<std::string> runs;
    for (std::size_t i = 0; i < others.size();) {
        std::size_t j = i;
        while (j + 1 < others.size() && others[j + 1] == others[j] + 1) ++j;
        runs.push_back(std::to_string(others[i]) +
                       (j > i ? " to " + std::to_string(others[j]) : std::string()));
        i = j + 1;
    }
    // Four runs named at most: scattered frames would make the note a page.
    if (runs.size() > 4) {
        const std::size_t more = runs.size() - 3;
        runs.resize(3);
        runs.push_back(std::to_string(more) + " more runs up to " + std::to_string(others.back()));
    }
    const std::string listed =
        runs.size() == 1 ? runs[0] : joined({runs.begin(), runs.end() - 1}) + " and " + runs.back();
    return out + " also holds " + plural(others.size(), "OBJ frame") + " this run did not write (" +
           (others.size() == 1 ? "frame " : "frames ") + listed + " of " + stem +
           "_*.obj, from an earlier run)";
}

// An earlier export of another format (or its calibrated rest) stays beside this one, under a
// sidecar that now describes this one alone: the user's to remove, so named. OBJ frames in an OBJ
// run are otherFramesNote's to name, by frame. The note, or "" when there are none.
std::string otherOutputsNote(const ExportRequest& request) {
    const std::string stem = exportStem(request);
    std::vector<std::string> others;
    std::size_t frames = 0;
    for (const std::string& name : exportFilesIn(request.outDir, stem)) {
        if (name == stem + ".json" || name == stem + exportFormatInfo(request.format).extension)
            continue;
        if (name == stem + "_calibrated_rest.obj") {
            if (!request.writeCalibratedRest) others.push_back(name);
        } else if (name.size() > 4 && name.compare(name.size() - 4, 4, ".obj") == 0) {
            if (request.format != ExportFormat::Obj) ++frames;  // an OBJ run's: otherFramesNote
        } else {
            others.push_back(name);
        }
    }
    if (frames) others.push_back(plural(long(frames), "OBJ frame") + " (" + stem + "_*.obj)");
    if (others.empty()) return "";
    const std::string listed =
        others.size() == 1 ? others[0]
                           : joined({others.begin(), others.end() - 1}) + " and " + others.back();
    return request.outDir + " also holds an earlier export's " + listed + ", which " + stem +
           ".json no longer describes; remove " +
           (others.size() == 1 && others[0].find("OBJ frames") == std::string::npos ? "it"
                                                                                    : "them") +
           ", or solve into another folder";
}

// The warning that the alignment the job chose (its calibration frame, its mesh up) is much worse
// than the automatic choice's (core's rule, the app's), or "": measured as the app measures it, by
// the solver's alignment alone with the frame and the up left to it. A solve otherwise went on
// from a body turned against its markers, its summary looking fine. `keys`: named as a manifest's.
std::string worseAlignmentWarning(const TriMesh& mesh, const C3dFrameReader& take,
                                  const Correspondence& map, const TakeSolveOptions& options,
                                  const Calibration& chosen, bool keys) {
    if (options.alignment || (options.calibrationFrame < 0 && !options.meshUp)) return "";
    TakeSolveOptions automatic = options;
    automatic.calibrationFrame = -1;
    automatic.meshUp.reset();
    automatic.calibrate = CalibrateMode::None;  // the alignment alone, not the fit
    automatic.solver.method = SolverOptions::Method::LocalGlobal;
    const Calibration found = TakeSolver(mesh, take, map, automatic).calibration();
    const double unitToMm = take.take().unitToMm;
    const double chosenMm = chosen.residualMm(unitToMm), automaticMm = found.residualMm(unitToMm);
    if (!alignsMuchWorse(chosenMm, automaticMm)) return "";
    const auto at = [&](const Calibration& c) {
        return "frame " + std::to_string(c.frame) +
               (options.meshUp ? " with mesh up " + guessUpAxis(c.takeToMesh, take.take().vertical)
                               : std::string());
    };
    std::vector<std::string> chose;
    for (const std::string key : {"calibration_frame", "mesh_up"}) {
        if (key == "calibration_frame" ? options.calibrationFrame < 0 : !options.meshUp) continue;
        chose.push_back(keys ? "\"" + key + "\"" : optionFlag(*findTakeOption(key)));
    }
    char figures[160];
    std::snprintf(figures, sizeof figures,
                  "%.1f mm (RMS), over %g times and %g mm more than the automatic choice's %.1f mm",
                  chosenMm, kMuchWorseAlignmentRatio, kMuchWorseAlignmentMm, automaticMm);
    return "the alignment at " + at(chosen) + " leaves " + figures + " at " + at(found) +
           "; try without " + joined(chose, " and ") +
           " (a pose far from the rest's, or a wrong up, turns the body against its markers)";
}

// A calibration frame that misses mapped markers fits the rest without them: a limb there keeps
// the mesh's length in every frame, and the alignment's residual does not show it.
std::string unseenAtCalibrationWarning(const Correspondence& map, const Calibration& c) {
    if (c.unseen.empty()) return "";
    std::vector<std::string> labels;
    for (const int k : c.unseen) labels.push_back(map.markers[k].label);
    constexpr std::size_t kListed = 5;
    std::string named = joined({labels.begin(), labels.begin() + std::min(kListed, labels.size())});
    if (labels.size() > kListed)
        named += " and " + std::to_string(labels.size() - kListed) + " more";
    return "calibration frame " + std::to_string(c.frame) + " does not show " + named + " (" +
           std::to_string(labels.size()) + " of the " + std::to_string(map.markers.size()) +
           " mapped markers), so the rest is fitted to the actor without " +
           (labels.size() == 1 ? "it" : "them") + "; a frame that shows every one fits it whole";
}

// A solve this far from a body's is a wrong map far more often than a wrong take: measured on CMU
// 85_02 and MakeHuman, a right map leaves an edge distortion of 0.14 (calibrate none) and aligns to
// 102 mm at a pose far from the rest's; the binary STL of that body with the OBJ's map (another
// vertex order), calibrate none, gave 0.893 and 227.7 mm, exit 0 and no word.
constexpr double kImplausibleDistortion = 0.5;
constexpr double kImplausibleAlignmentMm = 200.0;

// The warning that the solve `sidecar` describes is no body's, pointing at the map first, or "".
std::string implausibleSolveWarning(const nlohmann::json& sidecar, const std::string& mapPath) {
    const double distortion = sidecar.at("summary").at("edge_distortion_mean").get<double>();
    const double alignedMm = sidecar.at("alignment").at("residual_mm").get<double>();
    std::vector<std::string> signs;
    char text[200];
    if (distortion >= kImplausibleDistortion) {
        std::snprintf(text, sizeof text,
                      "its edges stretch by %.0f%% on average (edge distortion RMS %.3f; a body "
                      "following its markers stays under %.1f)",
                      100 * distortion, distortion, kImplausibleDistortion);
        signs.push_back(text);
    }
    if (alignedMm >= kImplausibleAlignmentMm) {
        std::snprintf(
            text, sizeof text,
            "the alignment leaves %.1f mm (a right map leaves about 100 mm even at a pose "
            "far from the rest's)",
            alignedMm);
        signs.push_back(text);
    }
    if (signs.empty()) return "";
    return "the solve is no body's: " + joined(signs, " and ") +
           "; check the map first: " + mapPath +
           " must name this mesh file's vertices, in its vertex order (a map made on another "
           "export or format of the body, an STL beside the OBJ, names other places)";
}

// The map names vertices by their order in the file it was made on: another file of the body (an
// STL exported beside the OBJ) may number them otherwise. The note, or "" for the same file name.
std::string otherMeshFileNote(const Correspondence& map, const std::string& mapPath,
                              const std::string& meshPath) {
    namespace fs = std::filesystem;
    if (map.meshFile.empty()) return "";
    const fs::path made = fs::path(map.meshFile).filename(), given = fs::path(meshPath).filename();
    if (made == given) return "";
    return mapPath + " was made on " + made.string() + ", and the mesh is " + given.string() +
           ": if that is another file of the body (another export or format), its vertices may "
           "be in another order, and the map name other places";
}

// Files of the outputs' names that no Boneless export wrote are the user's: refused unless forced,
// naming the first few, before anything is solved or written.
void refuseToReplaceOthersFiles(const ExportRequest& request, int end) {
    const std::vector<std::string> foreign = filesNoExportWrote(request, end);
    if (foreign.empty()) return;
    constexpr std::size_t kListed = 3;
    std::string named =
        joined({foreign.begin(), foreign.begin() + std::min(kListed, foreign.size())});
    if (foreign.size() > kListed)
        named += " and " + plural(long(foreign.size() - kListed), "more file", "more files");
    const bool one = foreign.size() == 1;
    throw Error(request.outDir + ": " + named + (one ? " was" : " were") +
                " not written by a Boneless export, and this solve would replace " +
                (one ? "it" : "them") + "; nothing was written: give --force to replace " +
                (one ? "it" : "them") + ", or another output folder");
}

// A shell loop solving each take with one --out left only the last take's solve, each run
// replacing the one before in silence: core's otherSolveIn refuses it (`subjects`: the actors
// this solve animates), as the app asks before its Export replaces it.
void refuseToReplaceAnotherTake(const ExportRequest& request,
                                const std::vector<std::string>& subjects) {
    const std::optional<OtherSolve> other = otherSolveIn(request, subjects);
    if (!other) return;
    if (other->sameTake)
        throw Error(other->sidecar + " is the solve of " + other->whose() + ", and solving " +
                    subjectsText(subjects) + " into " + request.outDir +
                    " would replace it; nothing was written: give each subject its own --out, or "
                    "--force to replace it");
    throw Error(other->sidecar + " is the solve of " + other->whose() + ", and solving " +
                request.c3dPath + " into " + request.outDir +
                " would replace it; nothing was written: give each take its own --out, or --force "
                "to replace it");
}

}  // namespace

ExportResult runTakeJob(const TakeJob& job, bool quiet, std::vector<std::string>* meshWarnings,
                        std::vector<std::string>* takeWarnings,
                        std::vector<std::string>* mapWarnings,
                        std::vector<std::string>* takeNotes) {
    const StopSignals stop;
    ExportRequest request;
    const auto format = findExportFormat(job.format);
    if (!format) throw Error("unknown output format \"" + job.format + "\"");
    request.format = *format;
    const FrameRange range = parseFrameRange(job.frames);
    request.first = range.first;
    request.end = range.end;
    fromJson(job.options, request.options, "options");
    request.writeCalibratedRest = job.writeCalibratedRest;
    request.meshPath = job.mesh;
    request.group = job.group;
    request.c3dPath = job.c3d;
    request.mapPath = job.map;
    request.outDir = job.out;

    MeshReadOptions meshOptions;
    meshOptions.group = job.group;
    const MeshReadResult read = readMesh(job.mesh, meshOptions);
    const TriMesh& mesh = read.mesh;
    if (meshWarnings)
        *meshWarnings = read.warnings;
    else if (!quiet)
        for (const std::string& w : read.warnings)
            std::fprintf(stderr, "note: %s: %s\n", job.mesh.c_str(), w.c_str());
    // Streamed: a take of any length solves in the memory of a short one. A take in other units
    // than it says is refused here, before the solver is prepared.
    C3dFrameReader take(job.c3d);
    // As a manifest names it in batch, which gives takeNotes.
    const bool keys = takeNotes != nullptr;
    take.setUnits(request.options.takeUnits, takeUnitsName(keys));
    refuseDoubtfulUnits(take.take(), "nothing was solved", keys);
    // Said even when quiet: a truncated take solves the frames it holds, and without this only
    // `inspect` would tell.
    if (takeWarnings)
        *takeWarnings = take.take().warnings;
    else
        for (const std::string& w : take.take().warnings)
            std::fprintf(stderr, "warning: %s: %s\n", job.c3d.c_str(), w.c_str());
    const Correspondence map = Correspondence::read(job.map);
    checkMapFitsMesh(map, mesh, job.mesh, job.group, keys);
    // In batch under the take's line, once it is finished (docs/batch.md).
    const auto note = [&](const std::string& text) {
        if (text.empty()) return;
        if (takeNotes)
            takeNotes->push_back(text);
        else
            std::fprintf(stderr, "note: %s\n", text.c_str());
    };
    note(otherMeshFileNote(map, job.map, job.mesh));
    const auto warnOfMap = [&](const std::string& warning) {
        if (mapWarnings)
            mapWarnings->push_back(warning);
        else
            std::fprintf(stderr, "warning: %s\n", warning.c_str());
    };
    for (const std::string& w : map.warnings) warnOfMap(w);  // a version 1 entry's "face"
    // The reader's component count alone read as if every part were solved.
    std::vector<int> markerVertices;
    for (const auto& m : map.markers) markerVertices.push_back(m.vertex);
    if (const int carried = componentsWithoutMarkers(mesh, markerVertices); carried > 0) {
        const std::string text = plural(carried, "component") +
                                 (carried == 1 ? " carries" : " carry") +
                                 " no marker: each follows the nearest marked part rigidly";
        if (meshWarnings)
            meshWarnings->push_back(text);
        else if (!quiet)
            std::fprintf(stderr, "note: %s: %s\n", job.mesh.c_str(), text.c_str());
    }
    // Not an error: the user may have looked and accepted them; but a suggestion on a prop or
    // the wrong limb pulls the mesh there, and nothing else would say so.
    if (const std::vector<std::string> review = labelsToReview(map); !review.empty()) {
        const std::string warning =
            job.map + ": " + std::to_string(review.size()) +
            (review.size() == 1 ? " suggested entry is" : " suggested entries are") +
            " still marked for review: " + joined(review);
        warnOfMap(warning);
    }
    // Refused or noted before the solver is prepared (the export would cut the range itself).
    const FrameRange within =
        withinFrames(range, job.frames, static_cast<int>(take.frameCount()), job.c3d, "solving",
                     takeNotes, takeNotes ? "\"frames\"" : "--frames");
    // A folder's OBJ frames of the same stem that no solve wrote (the demo's truth/) were
    // replaced, with only a note about those outside the range; an earlier export's are replaced
    // as before, by the run that follows it.
    if (!job.force)
        refuseToReplaceOthersFiles(
            request, within.end < 0 ? static_cast<int>(take.frameCount()) : within.end);
    if (!job.force && !job.replacesOtherTakes)
        refuseToReplaceAnotherTake(request, map.subjects(take.take()));

    // Preparing (the alignment, the calibration, the factorisation) takes seconds on a large
    // mesh: said as it starts and ends, and kept out of the seconds a frame takes.
    const auto begun = std::chrono::steady_clock::now();
    auto start = begun;  // the first frame's: s/frame and the ETA count from it
    if (!quiet) {
        const TakeSolveOptions& o = request.options;
        std::string steps = o.alignment ? "" : "aligning the take to the mesh, ";
        if (o.calibrate != CalibrateMode::None) steps += "calibrating the rest to the actor, ";
        std::fprintf(stderr, "preparing: %sfactorising (%s, %s)...\n", steps.c_str(),
                     plural(mesh.vertexCount(), "vertex", "vertices").c_str(),
                     plural(mesh.faceCount(), "face").c_str());
    }
    auto announce = [&](const Calibration& c) {
        // Said even when quiet, under the take's line in batch, as the take's own warnings.
        const std::string worse =
            worseAlignmentWarning(mesh, take, map, request.options, c, takeNotes != nullptr);
        if (!worse.empty() && takeWarnings) takeWarnings->push_back(worse);
        // A mesh 100 times too small came out so in a .glb, said only as "units look like m".
        const std::string scale =
            meshScaleWarning(mesh, c.takeToMesh, take.take().unitToMm, take.take().vertical);
        if (!scale.empty() && takeWarnings) takeWarnings->push_back(scale);
        const std::string unseen = unseenAtCalibrationWarning(map, c);
        if (!unseen.empty() && takeWarnings) takeWarnings->push_back(unseen);
        const auto warnOfWorse = [&] {
            for (const std::string& w : {worse, scale, unseen})
                if (!w.empty() && !takeWarnings)
                    std::fprintf(stderr, "warning: %s: %s\n", job.c3d.c_str(), w.c_str());
        };
        start = std::chrono::steady_clock::now();
        if (quiet) return warnOfWorse();
        std::fprintf(stderr, "prepared in %.1f s\n",
                     std::chrono::duration<double>(start - begun).count());
        const double meshUnitsPerMm = c.takeToMesh.scale / take.take().unitToMm;
        std::fprintf(stderr,
                     "%s: %zu frames at %g Hz, units %s; aligned at frame %d (residual %.1f mm), "
                     "mesh units look like %s, mesh up axis %s%s\n",
                     job.c3d.c_str(), take.frameCount(), take.take().rate,
                     unitsText(take.take()).c_str(), c.frame, c.residualMm(take.take().unitToMm),
                     guessMeshUnits(meshUnitsPerMm),
                     guessUpAxis(c.takeToMesh, take.take().vertical).c_str(),
                     request.options.meshUp ? "" : " (guessed; --mesh-up sets it)");
        warnOfWorse();
    };
    std::optional<ProgressPace> pace;
    auto onFrame = [&](int done, int total, const FrameReport& report) {
        const double elapsed =
            std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        if (!pace) pace.emplace(total);
        if (!quiet && done > 0) progress(done, total, elapsed, report, *pace);
        return stopSignal.load() == 0;
    };

    StopSignals::throwIfReceived();  // while the inputs were read: no solver prepared for nothing
    const ExportResult result = exportTake(mesh, take, map, request, onFrame, announce);
    if (!quiet && ::isatty(STDERR_FILENO)) std::fprintf(stderr, "\n");
    if (result.wroteNothing()) StopSignals::throwIfReceived();  // no note on files it left
    // Stopped or not: an earlier run's frames past the stop play as part of this take as much.
    if (request.format == ExportFormat::Obj)
        note(otherFramesNote(job.out, exportStem(request), result));
    note(otherOutputsNote(request));
    // The sidecar says "complete": false; the message must not call anything complete.
    if (result.cancelled) {
        const int n = result.framesWritten;
        // A run again solves the take from its first frame (there is no resuming part-way): "valid"
        // frames read as kept.
        throw TakeJobInterrupted(
            stoppedBy() + " after " + plural(n, "frame") + ": " + exportStem(request) +
                ".json records the take as incomplete, and solving it again starts from its "
                "first frame",
            stopSignal);
    }
    // Read once for the warning and the summary line.
    const nlohmann::json sidecar = nlohmann::json::parse(std::ifstream(result.sidecarPath));
    // Said even when quiet, as the held frames: the summary's figures alone looked like a solve.
    for (const std::string& w :
         {heldFramesWarning(result), implausibleSolveWarning(sidecar, job.map)}) {
        if (!w.empty() && takeWarnings)
            takeWarnings->push_back(w);
        else if (!w.empty())
            std::fprintf(stderr, "warning: %s: %s\n", job.c3d.c_str(), w.c_str());
    }
    if (!quiet) {
        namespace fs = std::filesystem;
        const std::string stem = exportStem(request);
        std::uintmax_t bytes = 0;
        std::string written;
        if (request.format == ExportFormat::Obj) {
            for (int f = result.first; f < result.first + result.framesWritten; ++f)
                bytes += fs::file_size(fs::path(job.out) / objFrameFile(stem, f));
            written = (fs::path(job.out) / (stem + "_*.obj")).string();
        } else {
            written =
                (fs::path(job.out) / (stem + exportFormatInfo(request.format).extension)).string();
            bytes = fs::file_size(written);
        }
        const double seconds =
            std::chrono::duration<double>(std::chrono::steady_clock::now() - begun).count();
        std::fprintf(stderr, "wrote %s: %s, %.1f MB in %.1f s\n", written.c_str(),
                     plural(result.framesWritten, "frame").c_str(), bytes / 1e6, seconds);
        printSummary(sidecar);
    }
    return result;
}
