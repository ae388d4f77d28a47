#include "boneless/TakeExport.h"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <condition_variable>
#include <cstdio>
#include <exception>
#include <filesystem>
#include <fstream>
#include <map>
#include <memory>
#include <mutex>
#include <nlohmann/json.hpp>
#include <numeric>
#include <optional>
#include <thread>
#include <vector>

#include "FrameOutput.h"
#include "OutputGuards.h"
#include "SolveMemory.h"
#include "boneless/ActorCalibration.h"
#include "boneless/C3dFrameReader.h"
#include "boneless/C3dParameters.h"
#include "boneless/Error.h"
#include "boneless/MaterialFiles.h"
#include "boneless/Metrics.h"
#include "boneless/ObjWriter.h"
#include "boneless/OutputFolder.h"
#include "boneless/Parallel.h"
#include "boneless/SolveFits.h"
#include "boneless/SpoolFile.h"
#include "boneless/Statistics.h"
#include "boneless/TakeOptionsJson.h"
#include "boneless/Text.h"

namespace boneless {

using nlohmann::json;
namespace fs = std::filesystem;

namespace {

// The sidecar's per-frame figures, written out as they come (a long take's would not fit in
// memory as JSON), and its summary of them, kept as they pass.
class PerFrameFigures {
  public:
    PerFrameFigures() : spool_(std::tmpfile()) {
        if (!spool_) throw Error("cannot create a temporary file for the sidecar's figures");
    }
    ~PerFrameFigures() {
        if (spool_) std::fclose(spool_);
    }
    void add(const json& f) {
        // A frame without markers has no residual: it would pull the mean towards 0.
        if (!f["residual_rms_mm"].is_null()) {
            residualSum_ += f["residual_rms_mm"].get<double>();
            residualWorst_ = std::max(residualWorst_, f["residual_rms_mm"].get<double>());
            ++residualFrames_;
        }
        if (f.contains("held_from")) {
            const int frame = f["frame"].get<int>();
            if (!held_.empty() && held_.back().second == frame - 1)
                held_.back().second = frame;
            else
                held_.emplace_back(frame, frame);
        }
        distortionWorst_ = std::max(distortionWorst_, f["edge_distortion"].get<double>());
        distortionSum_ += f["edge_distortion"].get<double>();
        strainWorst_ = std::max(strainWorst_, f["edge_strain_p95"].get<double>());
        foldedWorst_ = std::max(foldedWorst_, f["folded_faces"].get<int>());
        dentWorst_ = std::max(dentWorst_, f["dent_ratio"].get<double>());
        ms_.push_back(f["ms"].get<double>());
        // As json::dump(2) lays out an array element two levels down.
        const std::string lead = ms_.size() > 1 ? ",\n    " : "    ";
        std::string text = lead + f.dump(2);
        for (std::size_t i = text.find('\n', lead.size()); i != std::string::npos;
             i = text.find('\n', i + 1))
            text.insert(i + 1, "    ");
        if (std::fwrite(text.data(), 1, text.size(), spool_) != text.size())
            throw Error("cannot write the sidecar's figures to a temporary file (" +
                        writeFailure() + ")");
    }
    json summary() const {
        std::vector<double> ms = ms_;
        std::sort(ms.begin(), ms.end());
        const std::size_t n = ms.size();
        // Every frame held (none shows a marker): no residual at all, which 0 would call a
        // perfect fit.
        const auto residual = [&](double x) { return residualFrames_ ? json(x) : json(nullptr); };
        return {{"residual_rms_mm_mean", residual(residualSum_ / std::max(residualFrames_, 1))},
                {"residual_rms_mm_worst_frame", residual(residualWorst_)},
                {"edge_distortion_mean", n ? distortionSum_ / n : 0.0},
                {"edge_distortion_worst_frame", distortionWorst_},
                {"edge_strain_p95_worst_frame", strainWorst_},
                {"folded_faces_worst_frame", foldedWorst_},
                {"dent_ratio_worst_frame", dentWorst_},
                {"ms_per_frame_mean", n ? std::accumulate(ms.begin(), ms.end(), 0.0) / n : 0.0},
                {"ms_per_frame_worst", n ? ms.back() : 0.0},
                {"ms_per_frame_median", median(ms)},
                {"frames_held", held_}};
    }
    const std::vector<std::pair<int, int>>& held() const { return held_; }
    // Writes `sidecar` (whose "per_frame" is an empty array) to path with the figures in it.
    void write(const std::string& path, const json& sidecar) {
        const std::string text = sidecar.dump(2) + "\n";
        const std::string slot = "\"per_frame\": []";
        const std::size_t at = text.find(slot) + slot.size() - 1;
        std::FILE* spool = spool_;
        spool_ = nullptr;  // writeSpooled closes it
        writeSpooled(path, text.substr(0, at) + (ms_.empty() ? "" : "\n"), spool,
                     (ms_.empty() ? "" : "\n  ") + text.substr(at));
    }

  private:
    std::FILE* spool_;
    double residualSum_ = 0, residualWorst_ = 0, distortionWorst_ = 0, distortionSum_ = 0,
           strainWorst_ = 0, dentWorst_ = 0;
    int foldedWorst_ = 0, residualFrames_ = 0;
    std::vector<double> ms_;
    std::vector<std::pair<int, int>> held_;
};

// How the rest was fitted to the actor, and how far that moved it from the input mesh.
json calibrationJson(const ExportRequest& request, const TriMesh& mesh, const TakeSolver& solver,
                     const std::string& restFile) {
    json j = {{"calibrate", calibrateModeName(request.options.calibrate)}};
    if (request.options.calibrate == CalibrateMode::None) return j;
    j["frame"] = solver.calibration().frame;
    j["overridden"] = request.options.calibratedRest.has_value();
    j["edge_distortion_from_rest"] = edgeLengthDistortion(mesh.F, solver.rest().V, mesh.V);
    j["calibrated_rest"] = restFile.empty() ? json(nullptr) : json(validUtf8(restFile));
    return j;
}

// An input as the outputs name it: in full, so that the same file is named alike whichever folder
// solve, batch or the app ran in (and their outputs match byte for byte).
std::string fullPath(const std::string& path) {
    std::error_code ec;
    const fs::path full = fs::absolute(path, ec).lexically_normal();
    return ec ? path : full.string();
}

// JSON holds only UTF-8: a Latin-1 name is read as Latin-1.
json recordedPath(const std::string& path) {
    if (path.empty()) return nullptr;  // the app's map may be in no file
    return validUtf8(fullPath(path));
}

// vertices: the points a frame of the outputs holds; batch checks a cache's header against it and
// the mesh, as a cache of another mesh is the right size for its own header.
json sidecarJson(const C3dTake& take, const Correspondence& map, const ExportRequest& request,
                 const Calibration& c, const ExportResult& result, json fingerprints,
                 json calibration, json summary, int vertices) {
    const Similarity& s = c.takeToMesh;
    const double meshUnitsPerMm = s.scale / take.unitToMm;
    const TakeSolveOptions& o = request.options;
    const Vec3 up = take.vertical;
    return {{"format", "boneless-solve"},
            {"version", 2},
            {"fps", take.hasFrameRate() ? json(take.rate) : json(nullptr)},
            {"frame_range", {result.first, result.first + result.framesWritten}},
            {"frames_written", result.framesWritten},
            {"complete", !result.cancelled},
            {"output", exportFormatInfo(request.format).name},
            {"source",
             {{"mesh", recordedPath(request.meshPath)},
              {"group", validUtf8(request.group)},
              {"c3d", recordedPath(request.c3dPath)},
              {"map", recordedPath(request.mapPath)}}},
            {"subjects", map.subjects(take)},
            {"source_fingerprints", std::move(fingerprints)},
            {"units",
             {{"take", take.units},
              {"mesh_guess", guessMeshUnits(meshUnitsPerMm)},
              {"mesh_units_per_mm", meshUnitsPerMm}}},
            {"up_axis", {{"take", axisName(up)}, {"mesh_guess", guessUpAxis(s, up)}}},
            {"alignment",
             {{"calibration_frame", c.frame},
              {"residual_mm", c.residualMm(take.unitToMm)},
              {"scale", s.scale},
              {"rotation",
               {{s.R(0, 0), s.R(0, 1), s.R(0, 2)},
                {s.R(1, 0), s.R(1, 1), s.R(1, 2)},
                {s.R(2, 0), s.R(2, 1), s.R(2, 2)}}},
              {"translation", {s.t.x(), s.t.y(), s.t.z()}},
              {"overridden", o.alignment.has_value()}}},
            {"calibration", std::move(calibration)},
            {"options", toJson(o)},
            {"summary", std::move(summary)},
            {"vertices", vertices},
            {"per_frame", json::array()}};
}

// Frames do not depend on each other, so each core solves frames of its own (each worker with a
// TakeSolver of its own; the first is `first`), and `write` gets them in order on the calling
// thread until it returns false. A worker runs at most a few frames ahead of the writing.
// Returns how many workers solved.
using FrameSink = std::function<bool(int frame, const Positions& V, const FrameReport& report,
                                     double distortion, double strainP95)>;
int solveInOrder(TakeSolver& first, const TriMesh& mesh, const Correspondence& map,
                 const TakeSolveOptions& options, int begin, int end, int maxWorkers,
                 const FrameSink& write) {
    struct Solved {
        Positions V;
        FrameReport report;
        double distortion = 0, strainP95 = 0;
    };
    // A further worker first prepares a solver of its own, in the time the first solves some 7
    // (the koala in solve) to 14 (boneless-bench --sweep) frames: on a shorter take it solved
    // none, and the export waited for it (the koala's 2 frames, 3.5 s after the last was written).
    constexpr int kFramesForAnotherWorker = 16;
    const int workers = end - begin < kFramesForAnotherWorker
                            ? 1
                            : std::max(1, std::min({solverThreadCount(), end - begin, maxWorkers}));
    const int window = 4 * workers;
    std::mutex mutex;
    std::condition_variable changed;
    std::map<int, Solved> solved;
    int next = begin, written = begin;
    bool stop = false;
    std::exception_ptr error;
    std::atomic<bool> stopSolving{false};  // the writing stopped: frames in flight are of no use
    auto work = [&](int worker) {
        const RunSerially serial;  // the cores are taken by the workers themselves
        try {
            std::unique_ptr<TakeSolver> own;
            if (worker > 0) {
                // The first solver's trajectories and alignment, rather than finding them again.
                TakeSolveOptions same = options;
                same.alignment = first.calibration().takeToMesh;
                same.calibrationFrame = first.calibration().frame;
                if (options.calibrate == CalibrateMode::Shape) same.calibratedRest = first.rest().V;
                own = std::make_unique<TakeSolver>(mesh, first, map, same);
            }
            TakeSolver& solver = worker > 0 ? *own : first;
            const EdgeStrain edgeStrain(mesh.F, solver.rest().V);
            for (;;) {
                int f;
                {
                    std::unique_lock<std::mutex> lock(mutex);
                    changed.wait(lock,
                                 [&] { return stop || next >= end || next < written + window; });
                    if (stop || next >= end) return;
                    f = next++;
                }
                Solved s;
                s.V = solver.solve(f, s.report, &stopSolving);
                if (s.report.stopped) return;
                // Measured against what the frame was solved from: the calibrated rest when
                // calibrating, since the actor's proportions are not a stretch.
                std::vector<double> strains = edgeStrain.strains(s.V);
                s.distortion = rootMeanSquare(strains);
                s.strainP95 = quantile(std::move(strains), 0.95);
                if (s.report.foldedFaces < 0)
                    s.report.foldedFaces = foldedFaceCount(mesh.F, s.V, solver.rest().V);
                std::lock_guard<std::mutex> lock(mutex);
                solved.emplace(f, std::move(s));
                changed.notify_all();
            }
        } catch (...) {
            std::lock_guard<std::mutex> lock(mutex);
            if (!error) error = std::current_exception();
            stop = true;
            changed.notify_all();
        }
    };
    auto stopAll = [&] {
        {
            std::lock_guard<std::mutex> lock(mutex);
            stop = true;
            changed.notify_all();
        }
        stopSolving = true;
    };
    std::vector<std::thread> threads;
    try {
        for (int w = 0; w < workers; ++w) threads.emplace_back(work, w);
        bool more = true;
        for (int f = begin; f < end && more; ++f) {
            Solved s;
            {
                std::unique_lock<std::mutex> lock(mutex);
                changed.wait(lock, [&] { return error || solved.count(f); });
                if (error) break;
                s = std::move(solved.at(f));
                solved.erase(f);
            }
            more = write(f, s.V, s.report, s.distortion, s.strainP95);
            std::lock_guard<std::mutex> lock(mutex);
            written = f + 1;
            changed.notify_all();
        }
    } catch (...) {
        // A write that failed (a full disk) ends the workers before it goes on up.
        stopAll();
        for (auto& t : threads) t.join();
        throw;
    }
    stopAll();
    for (auto& t : threads) t.join();
    if (error) std::rethrow_exception(error);
    return workers;
}

SolveMemory solveMemory(const TriMesh& mesh, const ExportRequest& request) {
    return estimateSolveMemory(mesh.vertexCount(), mesh.faceCount(), request.options.solver.method);
}

// Else the automatic alignment finds no frame with three markers and blames the take. After the
// labels are resolved: a label the take lacks is the more precise mistake.
void requireMarkersToAlign(const Correspondence& map, const ExportRequest& request,
                           const C3dTake& take) {
    if (request.options.alignment) return;
    map.resolve(take);
    if (map.markers.size() >= 3) return;
    const std::string name = !map.source().empty()      ? map.source()
                             : !request.mapPath.empty() ? request.mapPath
                                                        : std::string("the map");
    throw Error(name + ": maps " + plural(static_cast<long long>(map.markers.size()), "marker") +
                "; solving needs at least 3");
}

// A glb or MDD keys each frame at its time (frame / rate): of a take without a rate every key was
// at 0, which glTF forbids and Blender plays as one frame.
void requireFrameRate(const ExportRequest& request, const C3dTake& take) {
    const ExportFormatInfo& format = exportFormatInfo(request.format);
    if (!format.timed || take.hasFrameRate()) return;
    throw Error(take.file + ": its frame rate is " + take.rateText() +
                " (the file gives none), and the " + format.name +
                " format keys each frame at its time; export obj or pc2, which number frames");
}

// What both sources check before a solver is built: the options, that the format can hold the
// take, that the mesh fits memory, and that no output would replace an input.
void checkRequest(const TriMesh& mesh, const Correspondence& map, const ExportRequest& request,
                  const C3dTake& take, int frames) {
    validate(request.options);
    // Here, before anything is written: refused once the solver was prepared, the earlier run's
    // complete sidecar had already given way to an incomplete one.
    if (request.writeCalibratedRest && request.options.calibrate == CalibrateMode::None)
        throw Error("writing the calibrated rest needs calibration (calibrate: none was given)");
    // The sidecar records take_units: a take read in other units than it says would lie there.
    const std::string& units = request.options.takeUnits;
    if (units == "file" ? !take.unitsFrom.empty() : take.unitsFrom.empty() || take.units != units)
        throw Error(request.c3dPath + ": take_units is " + units + " but the take was read in " +
                    take.units + (take.unitsFrom.empty() ? " (the file's)" : "") +
                    ": set its units (setTakeUnits) where it is read");
    requireFrameRate(request, take);
    refuseOutputsOverInputs(request, frames);
    // A glb's weight keys grow with the square of its frames: said before hours of solving.
    if (request.format == ExportFormat::Glb) {
        const int end = request.end < 0 ? frames : std::min(request.end, frames);
        checkGlbFits((fs::path(request.outDir) / (exportStem(request) + ".glb")).string(), mesh,
                     end - request.first);
    }
    checkSolveFits(mesh, request.meshPath, request.options.solver.method);
    // Here, where the mesh's file is known: the solver's own check can only say "the mesh".
    map.checkMesh(mesh.vertexCount(), request.meshPath.empty() ? "the mesh" : request.meshPath,
                  &mesh);
}

// What the sidecar's "source_fingerprints" records, taken before the solver is prepared: a map
// saved while it was (seconds, minutes on a large mesh) was recorded as the one solved, and every
// later batch skipped the take solved from the map before.
json sourceFingerprints(const TriMesh& mesh, const ExportRequest& request) {
    json fingerprints = {
        {"mesh", fileFingerprint(request.meshPath, true)},
        {"c3d", fileFingerprint(request.c3dPath, false)},
        {"map",
         request.mapPath.empty() ? json(nullptr) : json(fileFingerprint(request.mapPath, true))}};
    // A glb embeds the OBJ's materials and textures, so they are its inputs as much as the mesh.
    if (request.format == ExportFormat::Glb) {
        json& materials = fingerprints["materials"] = json::object();
        if (mesh.sourceFaces)
            for (const std::string& file : materialFiles(*mesh.sourceFaces))
                materials[validUtf8(file)] = fileFingerprint(file, true);
    }
    return fingerprints;
}

// take: what the sidecar says of the take (its samples are not read). The caller holds the
// outputs' OutputLock.
ExportResult exportSolved(TakeSolver& solver, const TriMesh& mesh, const C3dTake& take,
                          const Correspondence& map, const ExportRequest& request,
                          const json& fingerprints, const ExportProgress& progress,
                          const ExportCalibrated& calibrated) {
    const int count = solver.frameCount();
    const int end = request.end < 0 ? count : std::min(request.end, count);
    if (request.first < 0 || request.first >= end)
        throw Error("frames " + std::to_string(request.first) + ":" +
                    (request.end < 0 ? std::string() : std::to_string(request.end)) +
                    " select no frame of " + request.c3dPath + " (" + std::to_string(count) +
                    " frames)");

    const std::string stem = exportStem(request);
    const fs::path out(request.outDir);
    ExportResult result;
    result.first = request.first;
    // Told first: what the caller does with it (the CLI compares another alignment, seconds) is
    // part of preparing, during which a stop writes nothing.
    if (calibrated) calibrated(solver.calibration());
    // A stop asked for while the solver was prepared (Ctrl-C, Cancel): nothing is written, and an
    // earlier export in the folder stays whole. It was noticed after the first frame, written over
    // that export's.
    if (progress && !progress(0, end - request.first, FrameReport{})) {
        result.cancelled = true;
        return result;
    }
    result.sidecarPath = (out / (stem + ".json")).string();
    // While the outputs are being rewritten no earlier sidecar may say they are complete: one
    // saying "complete": false stands in until the last. Removed instead, a run that then failed
    // (a full disk) left the earlier export's cache named by no sidecar, and every later run
    // refused it as no Boneless export's.
    {
        ExportResult started;
        started.first = request.first;
        started.cancelled = true;
        const json placeholder = sidecarJson(
            take, map, request, solver.calibration(), started, fingerprints,
            calibrationJson(request, mesh, solver, ""), json::object(), mesh.vertexCount());
        writeFileAtomically(result.sidecarPath, placeholder.dump(2) + "\n");
    }
    // Made once, not per frame: a library the OBJ files could not name is copied beside them.
    std::shared_ptr<const SourceFaces> objFaces = mesh.sourceFaces;
    if (objFaces && (request.format == ExportFormat::Obj || request.writeCalibratedRest))
        objFaces =
            std::make_shared<const SourceFaces>(withLibraryCopies(*objFaces, request.outDir));
    // The OBJ frames and calibrated rest this run wrote: a take that fails part-way (a full disk)
    // removes them, or they filled the disk for every take after it. Never a file it did not write.
    std::vector<fs::path> framesWritten;
    fs::path restWritten;
    try {
        FrameOutput output = openFrameOutput(
            request.format, request.outDir, stem, mesh, request.first, take.rate,
            "Boneless: " + fullPath(request.c3dPath),
            gltfPlacement(solver.calibration().takeToMesh, take.unitToMm, take.vertical), objFaces);

        std::string restFile;
        if (request.writeCalibratedRest) {
            restFile = stem + "_calibrated_rest.obj";
            writeObj((out / restFile).string(), solver.rest().V, mesh.F,
                     "Boneless: " + fullPath(request.meshPath) + " fitted to " +
                         fullPath(request.c3dPath) + " at frame " +
                         std::to_string(solver.calibration().frame),
                     objFaces.get());
            restWritten = out / restFile;
        }
        PerFrameFigures perFrame;
        result.workers = solveInOrder(
            solver, mesh, map, request.options, request.first, end,
            solversThatFit(solveMemory(mesh, request), solverThreadCount()),
            [&](int f, const Positions& V, const FrameReport& report, double distortion,
                double strainP95) {
                output.append(f, V);
                if (request.format == ExportFormat::Obj)
                    framesWritten.push_back(out / objFrameFile(stem, f));
                // Quality a user checks before importing: stretch against the rest pose,
                // and folds.
                const bool seen = report.visibleMarkers > 0;
                json figures = {{"frame", f},
                                {"visible_markers", report.visibleMarkers},
                                {"residual_rms_mm", seen ? json(report.residualRmsMm) : json()},
                                {"residual_max_mm", seen ? json(report.residualMaxMm) : json()},
                                {"edge_distortion", distortion},
                                {"edge_strain_p95", strainP95},
                                {"folded_faces", report.foldedFaces},
                                {"dent_ratio", report.dentRatio},
                                {"iterations", report.iterations},
                                {"ms", report.milliseconds}};
                if (report.heldFrom >= 0) figures["held_from"] = report.heldFrom;
                perFrame.add(figures);
                ++result.framesWritten;
                if (progress && !progress(result.framesWritten, end - request.first, report) &&
                    f + 1 < end) {
                    result.cancelled = true;
                    return false;
                }
                return true;
            });
        output.finish();
        result.held = perFrame.held();
        json sidecar = sidecarJson(take, map, request, solver.calibration(), result, fingerprints,
                                   calibrationJson(request, mesh, solver, restFile),
                                   perFrame.summary(), mesh.vertexCount());
        // The app's map may be in no file (edited, or kept in the project): the sidecar then holds
        // the map that was solved, so the frames can be traced and solved again.
        if (request.mapPath.empty()) sidecar["map"] = json::parse(map.toJson());
        perFrame.write(result.sidecarPath, std::move(sidecar));
    } catch (const Error& e) {
        const std::string removed = removeWritten(framesWritten, restWritten);
        if (removed.empty()) throw;
        throw Error(std::string(e.what()) + "; " + removed);
    } catch (...) {
        removeWritten(framesWritten, restWritten);
        throw;
    }
    return result;
}

// What the first solver is built with: the request's options, starting from its fitted rest.
TakeSolveOptions firstSolverOptions(const ExportRequest& request) {
    TakeSolveOptions options = request.options;
    if (request.fittedRest && !options.calibratedRest && options.calibrate == CalibrateMode::Shape)
        options.calibratedRest = request.fittedRest;
    return options;
}

}  // namespace

ExportResult exportTake(const TriMesh& mesh, const C3dTake& take, const Correspondence& map,
                        const ExportRequest& request, const ExportProgress& progress,
                        const ExportCalibrated& calibrated) {
    checkRequest(mesh, map, request, take, static_cast<int>(take.frameCount()));
    requireMarkersToAlign(map, request, take);
    const json fingerprints = sourceFingerprints(mesh, request);
    const OutputLock lock(request);
    TakeSolver solver(mesh, take, map, firstSolverOptions(request));
    return exportSolved(solver, mesh, take, map, request, fingerprints, progress, calibrated);
}

ExportResult exportTake(const TriMesh& mesh, const C3dFrameReader& take, const Correspondence& map,
                        const ExportRequest& request, const ExportProgress& progress,
                        const ExportCalibrated& calibrated) {
    checkRequest(mesh, map, request, take.take(), static_cast<int>(take.frameCount()));
    requireMarkersToAlign(map, request, take.take());
    const json fingerprints = sourceFingerprints(mesh, request);
    const OutputLock lock(request);
    TakeSolver solver(mesh, take, map, firstSolverOptions(request));
    return exportSolved(solver, mesh, take.take(), map, request, fingerprints, progress,
                        calibrated);
}

}  // namespace boneless
