#include "boneless/TakeExport.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <optional>

#include "boneless/Error.h"
#include "boneless/Metrics.h"
#include "boneless/ObjWriter.h"
#include "boneless/PointCacheWriter.h"

namespace boneless {

using nlohmann::json;
namespace fs = std::filesystem;

const char* guessMeshUnits(double meshUnitsPerMm) {
    const struct {
        const char* name;
        double perMm;
    } units[] = {{"mm", 1.0}, {"cm", 0.1}, {"dm", 0.01}, {"m", 0.001}};
    const char* best = "mm";
    double bestGap = 1e300;
    for (const auto& u : units) {
        const double gap = std::abs(std::log(meshUnitsPerMm / u.perMm));
        if (gap < bestGap) best = u.name, bestGap = gap;
    }
    return best;
}

std::string guessUpAxis(const Similarity& s) {
    const Vec3 up = s.R * Vec3::UnitZ();
    int axis = 0;
    up.cwiseAbs().maxCoeff(&axis);
    return std::string(up[axis] < 0 ? "-" : "+") + "xyz"[axis];
}

std::string exportStem(const ExportRequest& request) {
    return fs::path(request.group.empty() ? request.meshPath : request.group).stem().string();
}

namespace {

json summaryJson(const json& perFrame) {
    double residualSum = 0, residualWorst = 0, distortionWorst = 0;
    int foldedWorst = 0;
    std::vector<double> ms;
    for (const json& f : perFrame) {
        residualSum += f["residual_rms_mm"].get<double>();
        residualWorst = std::max(residualWorst, f["residual_rms_mm"].get<double>());
        distortionWorst = std::max(distortionWorst, f["edge_distortion"].get<double>());
        foldedWorst = std::max(foldedWorst, f["folded_faces"].get<int>());
        ms.push_back(f["ms"].get<double>());
    }
    std::sort(ms.begin(), ms.end());
    const std::size_t n = perFrame.size();
    return {{"residual_rms_mm_mean", n ? residualSum / n : 0.0},
            {"residual_rms_mm_worst_frame", residualWorst},
            {"edge_distortion_worst_frame", distortionWorst},
            {"folded_faces_worst_frame", foldedWorst},
            {"ms_per_frame_median", n ? ms[n / 2] : 0.0}};
}

json sidecarJson(const C3dTake& take, const ExportRequest& request, const Calibration& c,
                 const ExportResult& result, json perFrame) {
    const Similarity& s = c.takeToMesh;
    const double meshUnitsPerMm = s.scale / take.unitToMm;
    const TakeSolveOptions& o = request.options;
    return {{"format", "boneless-solve"},
            {"version", 1},
            {"fps", take.rate},
            {"frame_range", {result.first, result.first + result.framesWritten}},
            {"frames_written", result.framesWritten},
            {"interrupted", result.cancelled},
            {"output", request.format == ExportRequest::Format::Pc2 ? "pc2" : "obj"},
            {"source",
             {{"mesh", request.meshPath},
              {"group", request.group},
              {"c3d", request.c3dPath},
              {"map", request.mapPath}}},
            {"units",
             {{"take", take.units},
              {"mesh_guess", guessMeshUnits(meshUnitsPerMm)},
              {"mesh_units_per_mm", meshUnitsPerMm}}},
            {"up_axis", {{"take", "+z"}, {"mesh_guess", guessUpAxis(s)}}},
            {"alignment",
             {{"calibration_frame", c.frame},
              {"residual_mm", c.residual / meshUnitsPerMm},
              {"scale", s.scale},
              {"rotation",
               {{s.R(0, 0), s.R(0, 1), s.R(0, 2)},
                {s.R(1, 0), s.R(1, 1), s.R(1, 2)},
                {s.R(2, 0), s.R(2, 1), s.R(2, 2)}}},
              {"translation", {s.t.x(), s.t.y(), s.t.z()}},
              {"overridden", o.alignment.has_value()}}},
            {"solver",
             {{"marker_weight", o.markerWeight},
              {"low_pass_hz", o.lowPassHz},
              {"continuation_steps", o.continuationSteps},
              {"coarsest_leads", o.coarsestLeads},
              {"rigidity_weight", o.solver.rigidityWeight},
              {"orientation_weight", o.solver.orientationWeight},
              {"orientation_threshold", o.solver.orientationThreshold},
              {"max_iterations", o.solver.maxIterations}}},
            {"summary", summaryJson(perFrame)},
            {"per_frame", std::move(perFrame)}};
}

}  // namespace

ExportResult exportTake(const TriMesh& mesh, const C3dTake& take, const Correspondence& map,
                        const ExportRequest& request, const ExportProgress& progress,
                        const ExportCalibrated& calibrated) {
    TakeSolver solver(mesh, take, map, request.options);
    const int count = solver.frameCount();
    const int end = request.end < 0 ? count : std::min(request.end, count);
    if (request.first < 0 || request.first >= end)
        throw Error("frames " + std::to_string(request.first) + ":" +
                    (request.end < 0 ? std::string() : std::to_string(request.end)) +
                    " select no frame of " + request.c3dPath + " (" + std::to_string(count) +
                    " frames)");

    std::error_code ec;
    fs::create_directories(request.outDir, ec);
    if (ec) throw Error(request.outDir + ": cannot create the folder (" + ec.message() + ")");
    const std::string stem = exportStem(request);
    const fs::path out(request.outDir);
    std::optional<PointCacheWriter> cache;
    if (request.format == ExportRequest::Format::Pc2)
        cache.emplace((out / (stem + ".pc2")).string(), mesh.vertexCount(), request.first, 1.0);

    if (calibrated) calibrated(solver.calibration());
    ExportResult result;
    result.first = request.first;
    json perFrame = json::array();
    for (int f = request.first; f < end; ++f) {
        FrameReport report;
        const Positions V = solver.solve(f, report);
        if (cache) {
            cache->append(V);
        } else {
            char name[16];
            std::snprintf(name, sizeof name, "_%04d.obj", f);
            writeObj((out / (stem + name)).string(), V, mesh.F,
                     "Boneless: " + request.c3dPath + " frame " + std::to_string(f));
        }
        // Quality a user checks before importing: stretch against the rest pose, and folds.
        perFrame.push_back({{"frame", f},
                            {"visible_markers", report.visibleMarkers},
                            {"residual_rms_mm", report.residualRmsMm},
                            {"residual_max_mm", report.residualMaxMm},
                            {"edge_distortion", edgeLengthDistortion(mesh.F, V, mesh.V)},
                            {"folded_faces", foldedFaceCount(mesh.F, V, mesh.V)},
                            {"iterations", report.iterations},
                            {"ms", report.milliseconds}});
        ++result.framesWritten;
        if (progress && !progress(result.framesWritten, end - request.first, report) &&
            f + 1 < end) {
            result.cancelled = true;
            break;
        }
    }
    if (cache) cache->finish();
    result.sidecarPath = (out / (stem + ".json")).string();
    writeFileAtomically(
        result.sidecarPath,
        sidecarJson(take, request, solver.calibration(), result, std::move(perFrame)).dump(2) +
            "\n");
    return result;
}

}  // namespace boneless
