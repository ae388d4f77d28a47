// boneless-cli solve: a take and a mesh in, an OBJ sequence or a PC2 cache out.
#include <unistd.h>
#include <atomic>
#include <chrono>
#include <cmath>
#include <csignal>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>

#include "Commands.h"
#include "FrameRange.h"
#include "boneless/C3dReader.h"
#include "boneless/Error.h"
#include "boneless/MeshReader.h"
#include "boneless/ObjWriter.h"
#include "boneless/PointCacheWriter.h"
#include "boneless/TakeSolver.h"

using namespace boneless;
using nlohmann::json;

namespace {

std::atomic<bool> interrupted{false};
extern "C" void onInterrupt(int) {
    interrupted = true;
}

struct SolveArgs {
    std::string mesh, group, c3d, map, out, format = "obj", frames;
    double weight = TakeSolveOptions{}.markerWeight;
    double lowPass = 0;
    int calibrationFrame = -1;
    int continuation = TakeSolveOptions{}.continuationSteps;
    bool quiet = false;
};

// The nearest of mm/cm/dm/m for the mesh's unit, from how many mesh units a millimetre is.
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

// The mesh axis the take's vertical (C3D: +z) maps onto.
std::string guessUpAxis(const Similarity& s) {
    const Vec3 up = s.R * Vec3::UnitZ();
    int axis = 0;
    up.cwiseAbs().maxCoeff(&axis);
    return std::string(up[axis] < 0 ? "-" : "+") + "xyz"[axis];
}

void progress(int done, int total, double elapsedSeconds, const FrameReport& last) {
    // On a terminal the bar redraws in place; into a log it is a line every tenth of the take.
    static const bool terminal = ::isatty(STDERR_FILENO);
    if (!terminal && done != total && done % std::max(1, total / 10) != 0) return;
    const int width = 30;
    const int filled = total ? width * done / total : width;
    const double perFrame = done ? elapsedSeconds / done : 0;
    const int eta = static_cast<int>(perFrame * (total - done) + 0.5);
    std::fprintf(stderr, "%s[%.*s%.*s] %d/%d frames  %.2f s/frame  ETA %d:%02d  residual %.1f mm%s",
                 terminal ? "\r" : "", filled, "##############################", width - filled,
                 "..............................", done, total, perFrame, eta / 60, eta % 60,
                 last.residualRmsMm, terminal ? " " : "\n");
    std::fflush(stderr);
}

void run(const SolveArgs& args) {
    namespace fs = std::filesystem;
    MeshReadOptions meshOptions;
    meshOptions.group = args.group;
    const TriMesh mesh = readMesh(args.mesh, meshOptions).mesh;
    const C3dTake take = readC3d(args.c3d);
    const Correspondence map = Correspondence::read(args.map);

    TakeSolveOptions options;
    options.markerWeight = args.weight;
    options.lowPassHz = args.lowPass;
    options.calibrationFrame = args.calibrationFrame;
    options.continuationSteps = args.continuation;
    TakeSolver solver(mesh, take, map, options);

    const FrameRange range = parseFrameRange(args.frames);
    const int first = range.first;
    const int end = range.end < 0 ? solver.frameCount() : std::min(range.end, solver.frameCount());
    if (first < 0 || first >= end)
        throw Error("--frames " + args.frames + " selects no frame of " + args.c3d + " (" +
                    std::to_string(solver.frameCount()) + " frames)");

    std::error_code ec;
    fs::create_directories(args.out, ec);
    if (ec) throw Error(args.out + ": cannot create the folder (" + ec.message() + ")");
    const std::string stem = fs::path(args.group.empty() ? args.mesh : args.group).stem().string();
    const fs::path out(args.out);
    std::optional<PointCacheWriter> cache;
    if (args.format == "pc2")
        cache.emplace((out / (stem + ".pc2")).string(), mesh.vertexCount(), first, 1.0);

    const Calibration& c = solver.calibration();
    const double meshUnitsPerMm = c.takeToMesh.scale / take.unitToMm;
    if (!args.quiet)
        std::fprintf(stderr,
                     "%s: %zu frames at %g Hz, units %s; aligned at frame %d (residual %.1f mm), "
                     "mesh units look like %s, mesh up axis %s\n",
                     args.c3d.c_str(), take.frameCount(), take.rate, take.units.c_str(), c.frame,
                     c.residual / meshUnitsPerMm, guessMeshUnits(meshUnitsPerMm),
                     guessUpAxis(c.takeToMesh).c_str());

    interrupted = false;
    auto previousHandler = std::signal(SIGINT, onInterrupt);
    json perFrame = json::array();
    const auto start = std::chrono::steady_clock::now();
    int done = 0;
    for (int f = first; f < end && !interrupted; ++f) {
        FrameReport report;
        const Positions V = solver.solve(f, report);
        if (cache) {
            cache->append(V);
        } else {
            char name[16];
            std::snprintf(name, sizeof name, "_%04d.obj", f);
            writeObj((out / (stem + name)).string(), V, mesh.F,
                     "Boneless: " + args.c3d + " frame " + std::to_string(f));
        }
        perFrame.push_back({{"frame", f},
                            {"visible_markers", report.visibleMarkers},
                            {"residual_rms_mm", report.residualRmsMm},
                            {"residual_max_mm", report.residualMaxMm},
                            {"iterations", report.iterations},
                            {"ms", report.milliseconds}});
        ++done;
        const double elapsed =
            std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        if (!args.quiet) progress(done, end - first, elapsed, report);
    }
    std::signal(SIGINT, previousHandler);
    if (!args.quiet && ::isatty(STDERR_FILENO)) std::fprintf(stderr, "\n");
    if (cache) cache->finish();

    const Similarity& s = c.takeToMesh;
    json sidecar = {
        {"format", "boneless-solve"},
        {"version", 1},
        {"fps", take.rate},
        {"frame_range", {first, first + done}},
        {"frames_written", done},
        {"interrupted", interrupted.load()},
        {"output", args.format},
        {"source",
         {{"mesh", args.mesh}, {"group", args.group}, {"c3d", args.c3d}, {"map", args.map}}},
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
          {"translation", {s.t.x(), s.t.y(), s.t.z()}}}},
        {"solver",
         {{"marker_weight", args.weight},
          {"low_pass_hz", args.lowPass},
          {"continuation_steps", args.continuation},
          {"rigidity_weight", SolverOptions{}.rigidityWeight},
          {"max_iterations", SolverOptions{}.maxIterations}}},
        {"per_frame", perFrame}};
    writeFileAtomically((out / (stem + ".json")).string(), sidecar.dump(2) + "\n");
    if (interrupted)
        throw Error("interrupted after " + std::to_string(done) + " frames; " +
                    "the frames written and " + stem + ".json are complete");
}

}  // namespace

void registerSolveCommand(CLI::App& app) {
    auto args = std::make_shared<SolveArgs>();
    CLI::App* cmd = app.add_subcommand("solve", "Animate a mesh from a C3D take");
    cmd->add_option("--mesh", args->mesh, "Rest mesh (OBJ, PLY, OFF, STL)")->required();
    cmd->add_option("--group", args->group, "OBJ group to use as the mesh");
    cmd->add_option("--c3d", args->c3d, "The take")->required();
    cmd->add_option("--map", args->map, "Correspondence file (JSON)")->required();
    cmd->add_option("--out", args->out, "Output folder")->required();
    cmd->add_option("--format", args->format, "obj (one file per frame) or pc2 (one point cache)")
        ->check(CLI::IsMember({"obj", "pc2"}));
    cmd->add_option("--frames", args->frames, "Frame range A:B (0-based, B excluded)");
    cmd->add_option("--weight", args->weight, "Marker weight (soft constraints)")
        ->check(CLI::PositiveNumber);
    cmd->add_option("--lowpass", args->lowPass, "Low-pass cutoff in Hz (0 = off)");
    cmd->add_option("--calibration-frame", args->calibrationFrame,
                    "Frame to align the take at (default: chosen automatically)");
    cmd->add_option("--continuation", args->continuation,
                    "Steps from the rest pose to the first frame");
    cmd->add_flag("--quiet", args->quiet, "No progress on stderr");
    cmd->callback([args] { run(*args); });
}
