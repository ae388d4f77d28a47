// boneless-bench-stream: peak memory of `boneless-cli solve` on a long take against a short one
// (issue 29: a 200,000-frame take streams through solve; target: peak RSS at most 1.5 times the
// 2,000-frame one's). Both takes are generated with the project's own generators and writers: the
// demo creature at a coarse resolution (a small mesh, so that every frame of the long take is
// solved in reasonable time on a shared machine), its 2,000-frame take, and that take repeated to
// the long one's length (writeC3d). Each solve runs as a user runs
// it, in a process of its own; its resident set is sampled every 50 ms for the mean and read
// from the kernel's high-water mark for the peak.

#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <CLI/CLI.hpp>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>
#include <thread>
#include <vector>

#include "DemoCreature.h"
#include "DemoTake.h"
#include "boneless/C3dWriter.h"
#include "boneless/ObjWriter.h"

using namespace boneless;
namespace fs = std::filesystem;

namespace {

constexpr double kTargetRatio = 1.5;

struct Inputs {
    std::string mesh, map, take;
    int vertices = 0, markers = 0;
};

struct Run {
    int frames = 0;
    double seconds = 0, meanMb = 0, peakMb = 0;
};

// Resident set of a running process in kB (0 once it is gone).
long residentKb(pid_t pid) {
    std::ifstream status("/proc/" + std::to_string(pid) + "/status");
    std::string line;
    while (std::getline(status, line))
        if (line.rfind("VmRSS:", 0) == 0) return std::stol(line.substr(6));
    return 0;
}

Run solve(const std::string& cli, const Inputs& demo, const std::string& c3d, int frames,
          const std::string& out, const std::vector<std::string>& extra) {
    std::vector<std::string> args = {cli,     "solve",  "--mesh", demo.mesh, "--c3d",  c3d,
                                     "--map", demo.map, "--out",  out,       "--quiet"};
    args.insert(args.end(), extra.begin(), extra.end());
    std::vector<char*> argv;
    for (auto& a : args) argv.push_back(a.data());
    argv.push_back(nullptr);
    const auto start = std::chrono::steady_clock::now();
    const pid_t pid = ::fork();
    if (pid == 0) {
        ::execv(cli.c_str(), argv.data());
        std::perror("execv");
        ::_exit(127);
    }
    double sum = 0;
    long samples = 0;
    int status = 0;
    rusage usage{};
    for (;;) {
        const pid_t done = ::wait4(pid, &status, WNOHANG, &usage);
        if (done == pid) break;
        if (const long kb = residentKb(pid)) sum += kb, ++samples;
        std::this_thread::sleep_for(std::chrono::milliseconds(50));
    }
    if (!WIFEXITED(status) || WEXITSTATUS(status) != 0) {
        std::fprintf(stderr, "solve of %s failed (status %d)\n", c3d.c_str(), status);
        std::exit(1);
    }
    Run r;
    r.frames = frames;
    r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    r.peakMb = usage.ru_maxrss / 1024.0;
    r.meanMb = samples ? sum / samples / 1024.0 : r.peakMb;
    return r;
}

}  // namespace

int main(int argc, char** argv) {
    CLI::App app{"Peak memory of boneless-cli solve on a long take against a short one"};
    int small = 2000, large = 200000, rings = 16, segments = 8;
    std::string work = (fs::temp_directory_path() / "boneless-bench-stream").string();
    std::string cli = BONELESS_CLI, format = "pc2";
    double lowPass = 6.0;
    app.add_option("--small", small, "Frames of the baseline take")->check(CLI::PositiveNumber);
    app.add_option("--large", large, "Frames of the long take")->check(CLI::PositiveNumber);
    app.add_option("--rings", rings, "The creature's rings (48 is the demo's)");
    app.add_option("--segments", segments, "The creature's segments (24 is the demo's)");
    app.add_option("--work", work, "Folder for the takes and outputs (emptied)");
    app.add_option("--cli", cli, "The boneless-cli to measure");
    app.add_option("--format", format, "solve's --format");
    app.add_option("--low-pass-hz", lowPass, "solve's --low-pass-hz (Hz; 0 = off)");
    CLI11_PARSE(app, argc, argv);

    fs::remove_all(work);
    fs::create_directories(work);
    Inputs demo;
    demo.mesh = (fs::path(work) / "creature.obj").string();
    demo.map = (fs::path(work) / "creature.map.json").string();
    demo.take = (fs::path(work) / "short.c3d").string();
    const std::string longTake = (fs::path(work) / "long.c3d").string();
    {
        const DemoCreature creature = makeDemoCreature(small, rings, segments);
        const DemoTake take = makeDemoTake(creature);
        writeObj(demo.mesh, creature.rest.V, creature.rest.F, "boneless-bench-stream creature");
        take.map.write(demo.map);
        writeC3d(take.take, demo.take);
        demo.vertices = creature.rest.vertexCount();
        demo.markers = static_cast<int>(take.take.points.size());
        C3dTake repeated = take.take;
        repeated.samples = C3dSamples(std::size_t(large), take.take.points.size());
        for (std::size_t f = 0; f < std::size_t(large); ++f)
            for (std::size_t k = 0; k < take.take.points.size(); ++k)
                if (const auto p = take.take.samples.position(f % take.take.frameCount(), k))
                    repeated.samples.set(f, k, p->x(), p->y(), p->z());
        writeC3d(repeated, longTake);
    }
    std::printf("creature: %d vertices, %d markers; --format %s --low-pass-hz %g; %s\n",
                demo.vertices, demo.markers, format.c_str(), lowPass, cli.c_str());
    const std::vector<std::string> extra = {"--format", format, "--low-pass-hz",
                                            std::to_string(lowPass)};
    const Run base =
        solve(cli, demo, demo.take, small, (fs::path(work) / "out-small").string(), extra);
    const Run big =
        solve(cli, demo, longTake, large, (fs::path(work) / "out-large").string(), extra);
    std::printf("%8s %9s %9s %14s %14s\n", "frames", "wall s", "ms/frame", "mean RSS MB",
                "peak RSS MB");
    for (const Run& r : {base, big})
        std::printf("%8d %9.1f %9.2f %14.1f %14.1f\n", r.frames, r.seconds,
                    1000 * r.seconds / r.frames, r.meanMb, r.peakMb);
    const double ratio = big.peakMb / base.peakMb;
    std::printf("ratio %d / %d frames: mean RSS %.3f, peak RSS %.3f (target <= %.1f: %s)\n", large,
                small, big.meanMb / base.meanMb, ratio, kTargetRatio,
                ratio <= kTargetRatio ? "met" : "MISSED");
    fs::remove_all(work);
    return 0;
}
