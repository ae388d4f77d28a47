// boneless-bench-take: the quality figures of solved takes, issue 28's targets beside them. Each
// --solved DIR is a `boneless-cli solve --format pc2` output (the cache and its sidecar) of the
// same mesh, take and map; each is measured by the same code, so that a run before a change and
// one after it compare directly. Per frame: the 95th percentile edge strain |len/rest − 1| (the
// sidecar's EdgeStrain and quantile), the edge distortion (RMS of the same), folded faces
// (Metrics' foldedFaces, refitted from scratch), the dent ratio (DentGauge), the sidecar's marker
// residual, and the share of edges bent by more than 20° (bentEdgeShare: the kinks that the strain
// and the dent ratio cannot see; the issue sets no target for it); printed as worst frame and mean.
// A take solved with calibration is measured against its calibrated rest, as the sidecar measures
// it (solve it with --write-calibrated-rest); the actor's proportions are not a stretch.
// Nothing is asserted.

#include <CLI/CLI.hpp>
#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "boneless/ActorCalibration.h"
#include "boneless/Correspondence.h"
#include "boneless/DentGauge.h"
#include "boneless/Error.h"
#include "boneless/MeshReader.h"
#include "boneless/Metrics.h"
#include "boneless/PointCacheWriter.h"
#include "boneless/TakeOptionsJson.h"
#include "boneless/TakeSolver.h"

using namespace boneless;
namespace fs = std::filesystem;

namespace {

// Issue 28's targets.
constexpr double kTargetStrainP95 = 0.15, kTargetDistortion = 0.08, kTargetResidualMm = 2.0,
                 kTargetDent = 2.0;
constexpr double kBendDegrees = 20;  // a kink: more than skin's soft bend across one edge

struct Worst {
    double worst = 0, sum = 0;
    int frame = -1, count = 0;
    void add(double x, int f) {
        sum += x;
        ++count;
        if (frame < 0 || x > worst) worst = x, frame = f;
    }
    double mean() const { return count ? sum / count : 0; }
};

int measure(int argc, char** argv);

}  // namespace

int main(int argc, char** argv) {
    // A folder it cannot measure is one line naming the file, not an uncaught exception.
    try {
        return measure(argc, argv);
    } catch (const std::exception& e) {
        std::fprintf(stderr, "boneless-bench-take: %s\n", e.what());
        return 1;
    }
}

namespace {

int measure(int argc, char** argv) {
    CLI::App app{"Quality figures of solved takes (issue 28)"};
    std::string meshPath, group, mapPath;
    std::vector<std::string> solved;
    app.add_option("--mesh", meshPath)->required();
    app.add_option("--group", group);
    app.add_option("--map", mapPath)->required();
    app.add_option("--solved", solved, "boneless-cli solve --format pc2 output folders")
        ->required();
    CLI11_PARSE(app, argc, argv);

    MeshReadOptions read;
    read.group = group;
    const TriMesh input = readMesh(meshPath, read).mesh;
    const Correspondence map = Correspondence::read(mapPath);
    const std::vector<SurfacePoint> points = surfacePoints(map);
    const MeshTopology topology(input);

    for (const std::string& dir : solved) {
        const std::string stem = group.empty() ? fs::path(meshPath).stem().string() : group;
        const std::string sidecarPath = (fs::path(dir) / (stem + ".json")).string();
        std::ifstream sidecarFile(sidecarPath);
        if (!sidecarFile)
            throw Error(sidecarPath + ": cannot open the sidecar (" + std::strerror(errno) +
                        "): is " + dir + " a `boneless-cli solve --format pc2` output?");
        const auto sidecar = nlohmann::json::parse(sidecarFile, nullptr, false);
        if (sidecar.is_discarded() || !sidecar.is_object())
            throw Error(sidecarPath + ": not a sidecar (not a JSON object)");
        // Before the calibration: a folder solved to OBJ is told so, whatever its calibration.
        const std::string cachePath = (fs::path(dir) / (stem + ".pc2")).string();
        if (!fs::is_regular_file(cachePath))
            throw Error(cachePath +
                        ": cannot open the point cache (no such file): solve with "
                        "--format pc2; OBJ, MDD and glb outputs are not measured");
        TriMesh rest = input;
        const auto& calibration = sidecar["calibration"];
        if (calibration.value("calibrate", "none") != "none") {
            if (!calibration["calibrated_rest"].is_string())
                throw Error(sidecarPath +
                            ": the take was solved with calibration but its calibrated rest was "
                            "not written, and the figures are measured against it: solve again "
                            "with --write-calibrated-rest");
            rest.V =
                readMesh(
                    (fs::path(dir) / calibration["calibrated_rest"].get<std::string>()).string())
                    .mesh.V;
        }
        const ShapeEncoding encoding(rest, topology);
        const double unitsPerMm = sidecar["units"]["mesh_units_per_mm"].get<double>();
        const DentGauge dents(rest, topology, encoding, points,
                              TakeSolver::kDentRadiusMm * unitsPerMm);
        const EdgeStrain edgeStrain(rest.F, rest.V);
        const std::vector<Positions> frames = readPointCache(cachePath);
        const int first = sidecar["frame_range"][0].get<int>();
        Worst strain, distortion, folded, dent, residual, bent;
        int foldedFrames = 0, foldedTotal = 0;
        std::vector<double> perMarker(points.size(), 0.0);
        for (size_t i = 0; i < frames.size(); ++i) {
            const Positions& V = frames[i];
            const int f = first + static_cast<int>(i);
            // The sidecar's own gauge: its edge_strain_p95, to the last digit.
            std::vector<double> strains = edgeStrain.strains(V);
            distortion.add(rootMeanSquare(strains), f);
            strain.add(quantile(std::move(strains), 0.95), f);
            const int fold = foldedFaceCount(rest.F, V, rest.V);
            folded.add(fold, f);
            foldedFrames += fold > 0;
            foldedTotal += fold;
            bent.add(100 * bentEdgeShare(rest.F, V, rest.V, kBendDegrees), f);
            const std::vector<double> r = dents.ratios(V);
            for (size_t k = 0; k < r.size(); ++k) perMarker[k] = std::max(perMarker[k], r[k]);
            dent.add(*std::max_element(r.begin(), r.end()), f);
            // null on a frame that shows no marker (it holds a neighbour's pose)
            if (const nlohmann::json& r = sidecar["per_frame"][i]["residual_rms_mm"]; !r.is_null())
                residual.add(r.get<double>(), f);
        }
        // The options the run was solved with, read as the project reads its settings (a sidecar
        // before version 2 kept them under "solver", the calibrate mode under "calibration").
        TakeSolveOptions options;
        if (sidecar.contains("options")) {
            fromJson(sidecar["options"], options, dir);
        } else {
            fromJson(sidecar["solver"], options, dir);
            fromJson(sidecar["calibration"], options, dir);
        }
        std::printf("%s: %zu frames from %d\n  options %s\n", dir.c_str(), frames.size(), first,
                    toJson(options).dump().c_str());
        auto row = [](const char* name, const Worst& w, double target) {
            std::printf("  %-26s worst %8.4f (frame %d), mean %8.4f", name, w.worst, w.frame,
                        w.mean());
            if (target > 0) std::printf("  (target <= %g)", target);
            std::printf("\n");
        };
        row("edge strain p95", strain, kTargetStrainP95);
        row("edge distortion RMS", distortion, kTargetDistortion);
        row("marker residual RMS mm", residual, kTargetResidualMm);
        row("dent ratio", dent, kTargetDent);
        std::printf("  %-26s worst %d, %d faces over %d frames (target 0)\n", "folded faces",
                    static_cast<int>(folded.worst), foldedTotal, foldedFrames);
        row("edges bent > 20 deg, %", bent, 0);
        std::printf("  worst dent per marker:");
        for (size_t k = 0; k < points.size(); ++k)
            if (perMarker[k] > 1.5)
                std::printf(" %s %.2f", map.markers[k].label.c_str(), perMarker[k]);
        std::printf("\n");
    }
    return 0;
}

}  // namespace
