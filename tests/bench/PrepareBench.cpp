// boneless-bench-prepare: how long preparing a solve of a short range of a long take takes, against
// reading that take once. The takes review's 25-minute take (180,000 frames at 120 Hz, 112 MB)
// printed "prepared in 20.1 s" for `solve --frames 179900:180000`, and `inspect` took 10.1 s: the
// take was read and scanned four times. The take is generated: the demo walker's take (its 39
// markers, gaps and "walker:" labels) repeated to the long take's length at 120 Hz (writeC3d).
// Timed, each --repeats times (mean and worst), and as ratios to the baseline of the same run:
//   parse     readC3d of the whole take, in this process (the baseline: the take read once)
//   prepare   the streamed take opened and its TakeSolver built (alignment, calibration frame,
//             fit, factorisation), in this process: what "prepared in" counts
//   solve     `boneless-cli solve --frames A:B --quiet` as a user runs it, in its own process
//   inspect   `boneless-cli inspect` as a user runs it, in its own process

#include <sys/wait.h>
#include <unistd.h>

#include <CLI/CLI.hpp>
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <functional>
#include <random>
#include <string>
#include <vector>

#include "DemoWalker.h"
#include "boneless/C3dFrameReader.h"
#include "boneless/C3dReader.h"
#include "boneless/C3dWriter.h"
#include "boneless/Correspondence.h"
#include "boneless/MeshReader.h"
#include "boneless/ObjWriter.h"
#include "boneless/TakeSolver.h"

using namespace boneless;
namespace fs = std::filesystem;

namespace {

struct Timing {
    double mean = 0, worst = 0;
};

Timing timed(int repeats, const std::function<void()>& run) {
    Timing t;
    for (int i = 0; i < repeats; ++i) {
        const auto t0 = std::chrono::steady_clock::now();
        run();
        const double s =
            std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
        t.mean += s / repeats;
        t.worst = std::max(t.worst, s);
    }
    return t;
}

// Runs the command (argv[0] a path) with its output discarded; exits naming it when it fails.
void runQuiet(const std::vector<std::string>& args) {
    std::vector<char*> argv;
    for (const auto& a : args) argv.push_back(const_cast<char*>(a.c_str()));
    argv.push_back(nullptr);
    std::fflush(stdout);  // or the child's copy of the buffer is printed again
    const pid_t pid = ::fork();
    if (pid == 0) {
        std::freopen("/dev/null", "w", stdout);
        ::execv(argv[0], argv.data());
        std::perror(argv[0]);
        ::_exit(127);
    }
    int status = 0;
    if (pid < 0 || ::waitpid(pid, &status, 0) < 0 || !WIFEXITED(status) ||
        WEXITSTATUS(status) != 0) {
        std::string line;
        for (const auto& a : args) line += a + " ";
        std::fprintf(stderr, "failed (status %d): %s\n", status, line.c_str());
        std::exit(1);
    }
}

}  // namespace

int main(int argc, char** argv) {
    CLI::App app{
        "Times preparing a solve of a short range of a long generated take (the demo walker's "
        "take repeated), and boneless-cli solve and inspect of it, against reading the take once"};
    int frames = 180000, walk = 240, repeats = 3, range = 100;
    double rate = 120.0, noiseMm = 1.0;
    std::string work = (fs::temp_directory_path() / "boneless-bench-prepare").string();
    std::string cli = BONELESS_CLI;
    bool keep = false;
    app.add_option("--frame-count", frames, "Frames of the long take")->check(CLI::PositiveNumber);
    app.add_option("--walk", walk, "Frames of the walk that is repeated")
        ->check(CLI::PositiveNumber);
    app.add_option("--rate", rate, "The long take's frame rate (Hz)")->check(CLI::PositiveNumber);
    app.add_option("--noise-mm", noiseMm,
                   "Noise on each coordinate (standard deviation, mm): without it frame 0, the "
                   "rest pose, fits exactly and the calibration frame is found at once");
    app.add_option("--range", range, "Frames solved, the take's last ones")
        ->check(CLI::PositiveNumber);
    app.add_option("--repeats", repeats, "Times each is run")->check(CLI::PositiveNumber);
    app.add_option("--work", work, "Folder for the take, mesh, map and outputs (emptied)");
    app.add_option("--cli", cli, "The boneless-cli to measure");
    app.add_flag("--keep", keep, "Keep the folder (the take, mesh and map) afterwards");
    CLI11_PARSE(app, argc, argv);
    range = std::min(range, frames);

    fs::remove_all(work);
    fs::create_directories(work);
    const std::string mesh = (fs::path(work) / "walker.obj").string();
    const std::string mapFile = (fs::path(work) / "walker.map.json").string();
    const std::string take = (fs::path(work) / "long.c3d").string();
    std::size_t markers = 0;
    {
        const DemoWalker walker = makeDemoWalker(walk);
        const DemoTake demo = makeDemoWalkerTake(walker);
        writeObj(mesh, walker.rest.V, walker.rest.F, "boneless-bench-prepare walker");
        demo.map.write(mapFile);
        C3dTake repeated = demo.take;
        repeated.rate = rate;
        markers = demo.take.points.size();
        repeated.samples = C3dSamples(std::size_t(frames), markers);
        std::mt19937 random(7);
        std::normal_distribution<double> noise(0.0, noiseMm / demo.take.unitToMm);
        for (std::size_t f = 0; f < std::size_t(frames); ++f)
            for (std::size_t k = 0; k < markers; ++k)
                if (const auto p = demo.take.samples.position(f % demo.take.frameCount(), k))
                    repeated.samples.set(f, k, p->x() + noise(random), p->y() + noise(random),
                                         p->z() + noise(random));
        writeC3d(repeated, take);
    }
    std::printf(
        "take: %d frames at %g Hz (%.1f min), %zu markers, noise %g mm, %.1f MB; solving frames "
        "%d:%d\n",
        frames, rate, frames / rate / 60, markers, noiseMm, fs::file_size(take) / 1e6,
        frames - range, frames);

    const Timing parse = timed(repeats, [&] { readC3d(take); });
    const TriMesh rest = readMesh(mesh).mesh;
    const Correspondence map = Correspondence::read(mapFile);
    int calibrationFrame = -1;
    const Timing prepare = timed(repeats, [&] {
        const C3dFrameReader reader(take);
        calibrationFrame = TakeSolver(rest, reader, map).calibration().frame;
    });
    const std::string frameRange = std::to_string(frames - range) + ":" + std::to_string(frames);
    const std::string out = (fs::path(work) / "out").string();
    const Timing solve = timed(repeats, [&] {
        runQuiet({cli, "solve", "--mesh", mesh, "--c3d", take, "--map", mapFile, "--out", out,
                  "--frames", frameRange, "--format", "pc2", "--quiet", "--force"});
    });
    const Timing inspect = timed(repeats, [&] { runQuiet({cli, "inspect", take}); });

    std::printf("calibration frame %d\n", calibrationFrame);
    std::printf("%-10s %9s %9s %9s\n", "", "mean s", "worst s", "ratio");
    const auto row = [&](const char* name, const Timing& t) {
        std::printf("%-10s %9.2f %9.2f %9.2f\n", name, t.mean, t.worst, t.mean / parse.mean);
    };
    row("parse", parse);
    row("prepare", prepare);
    row("solve", solve);
    row("inspect", inspect);
    std::printf("ratio: mean over parse's mean, the take read once in this run (%d repeats)\n",
                repeats);
    if (!keep) fs::remove_all(work);
    return 0;
}
