// boneless-cli solve: a take and a mesh in, an OBJ sequence or a PC2 cache out.
#include <unistd.h>
#include <atomic>
#include <chrono>
#include <csignal>
#include <cstdio>
#include <fstream>
#include <memory>
#include <nlohmann/json.hpp>

#include "Commands.h"
#include "FrameRange.h"
#include "boneless/C3dReader.h"
#include "boneless/Error.h"
#include "boneless/MeshReader.h"
#include "boneless/TakeExport.h"

using namespace boneless;

namespace {

std::atomic<bool> interrupted{false};
extern "C" void onInterrupt(int) {
    interrupted = true;
}

struct SolveArgs {
    std::string mesh, group, c3d, map, out, format = "obj", frames;
    double weight = TakeSolveOptions{}.markerWeight;
    double lowPass = 0;
    double fillGaps = TakeSolveOptions{}.fillGapSeconds;
    int calibrationFrame = -1;
    std::string solver = methodName(SolverOptions{}.method);
    std::string calibrate = calibrateModeName(TakeSolveOptions{}.calibrate);
    bool writeCalibratedRest = false;
    bool quiet = false;
};

void progress(int done, int total, double elapsedSeconds, const FrameReport& last) {
    // On a terminal the bar redraws in place; into a log it is a line every tenth of the take.
    static const bool terminal = ::isatty(STDERR_FILENO);
    if (!terminal && done != total && done % std::max(1, total / 10) != 0) return;
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

// The sidecar's quality figures, so a run's stretch and fit are seen without opening it.
void printSummary(const std::string& sidecarPath) {
    std::ifstream in(sidecarPath);
    const nlohmann::json sidecar = nlohmann::json::parse(in);
    const nlohmann::json& s = sidecar.at("summary");
    const nlohmann::json& c = sidecar.at("calibration");
    std::fprintf(stderr,
                 "calibrate %s: marker residual RMS %.2f mm mean, %.2f mm worst frame; edge "
                 "distortion RMS %.3f mean, %.3f worst frame; 95th percentile edge strain %.3f "
                 "worst frame; folded faces %d worst frame\n",
                 c.at("calibrate").get<std::string>().c_str(),
                 s.at("residual_rms_mm_mean").get<double>(),
                 s.at("residual_rms_mm_worst_frame").get<double>(),
                 s.at("edge_distortion_mean").get<double>(),
                 s.at("edge_distortion_worst_frame").get<double>(),
                 s.at("edge_strain_p95_worst_frame").get<double>(),
                 s.at("folded_faces_worst_frame").get<int>());
}

void run(const SolveArgs& args) {
    MeshReadOptions meshOptions;
    meshOptions.group = args.group;
    const TriMesh mesh = readMesh(args.mesh, meshOptions).mesh;
    const C3dTake take = readC3d(args.c3d);
    const Correspondence map = Correspondence::read(args.map);

    ExportRequest request;
    request.meshPath = args.mesh;
    request.group = args.group;
    request.c3dPath = args.c3d;
    request.mapPath = args.map;
    request.outDir = args.out;
    request.format = args.format == "pc2" ? ExportRequest::Format::Pc2 : ExportRequest::Format::Obj;
    const FrameRange range = parseFrameRange(args.frames);
    request.first = range.first;
    request.end = range.end;
    request.options.markerWeight = args.weight;
    request.options.lowPassHz = args.lowPass;
    request.options.fillGapSeconds = args.fillGaps;
    request.options.calibrationFrame = args.calibrationFrame;
    parseMethod(args.solver, request.options.solver.method);  // CLI11 has checked the name
    parseCalibrateMode(args.calibrate, request.options.calibrate);
    request.writeCalibratedRest = args.writeCalibratedRest;

    auto announce = [&](const Calibration& c) {
        if (args.quiet) return;
        const double meshUnitsPerMm = c.takeToMesh.scale / take.unitToMm;
        std::fprintf(stderr,
                     "%s: %zu frames at %g Hz, units %s; aligned at frame %d (residual %.1f mm), "
                     "mesh units look like %s, mesh up axis %s\n",
                     args.c3d.c_str(), take.frameCount(), take.rate, take.units.c_str(), c.frame,
                     c.residual / meshUnitsPerMm, guessMeshUnits(meshUnitsPerMm),
                     guessUpAxis(c.takeToMesh).c_str());
    };
    const auto start = std::chrono::steady_clock::now();
    auto onFrame = [&](int done, int total, const FrameReport& report) {
        const double elapsed =
            std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        if (!args.quiet) progress(done, total, elapsed, report);
        return !interrupted.load();
    };

    interrupted = false;
    auto previousHandler = std::signal(SIGINT, onInterrupt);
    ExportResult result;
    try {
        result = exportTake(mesh, take, map, request, onFrame, announce);
    } catch (...) {
        std::signal(SIGINT, previousHandler);
        throw;
    }
    std::signal(SIGINT, previousHandler);
    if (!args.quiet && ::isatty(STDERR_FILENO)) std::fprintf(stderr, "\n");
    if (!args.quiet) printSummary(result.sidecarPath);
    if (result.cancelled)
        throw Error("interrupted after " + std::to_string(result.framesWritten) + " frames; " +
                    "the frames written and " + exportStem(request) + ".json are complete");
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
    cmd->add_option("--fill-gaps", args->fillGaps,
                    "Place a marker missing for at most this many seconds on its trajectory "
                    "(0 = off)")
        ->check(CLI::NonNegativeNumber);
    cmd->add_option("--calibration-frame", args->calibrationFrame,
                    "Frame to align the take at (default: chosen automatically)");
    cmd->add_option("--solver", args->solver,
                    "local-global (each frame from its own markers, fast) or exact (Gauss-Newton "
                    "refining it: the energy's minimum, slower)")
        ->check(CLI::IsMember({methodName(SolverOptions::Method::LocalGlobal),
                               methodName(SolverOptions::Method::Exact)}));
    cmd->add_option("--calibrate", args->calibrate,
                    "shape (fit the rest mesh to the actor at the calibration frame, then solve "
                    "every frame against it) or none (solve against the rest mesh as given)")
        ->check(CLI::IsMember(
            {calibrateModeName(CalibrateMode::Shape), calibrateModeName(CalibrateMode::None)}));
    cmd->add_flag("--write-calibrated-rest", args->writeCalibratedRest,
                  "Also write <stem>_calibrated_rest.obj, the rest fitted to the actor");
    cmd->add_flag("--quiet", args->quiet, "No progress on stderr");
    cmd->callback([args] { run(*args); });
}
