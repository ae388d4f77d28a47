// boneless-bench-large: what `boneless-cli solve` needs on a million-face mesh (issue 29, "Large
// inputs"). The demo creature is generated at two resolutions (a baseline near 100K faces and the
// large one), each with its synthetic take (30 markers, with gaps), and `boneless-cli solve` runs
// on each as a user runs it, in a child process: its peak RSS (from wait4), wall time, time per
// frame (mean and worst, from the sidecar) and the rest of the wall time (reading, preparing,
// calibrating, writing). Ratios are large over baseline, from the same run. Target: the large
// mesh's peak RSS within kTargetPeakMb, so that it solves on a 16 GB laptop beside the rest of
// the user's work (docs/benchmarks.md, "Large meshes").

#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <CLI/CLI.hpp>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "boneless/DemoFiles.h"

using namespace boneless;
namespace fs = std::filesystem;

namespace {

constexpr double kTargetPeakMb = 10240;

struct Run {
    int faces = 0, vertices = 0, frames = 0;
    double generateS = 0, wallS = 0, peakMb = 0, frameMsMean = 0, frameMsWorst = 0, otherS = 0;
};

double secondsSince(std::chrono::steady_clock::time_point t0) {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

// Runs the command (argv[0] a path) and returns its exit status; peakKb gets its peak RSS.
int runMeasured(const std::vector<std::string>& args, long& peakKb) {
    std::vector<char*> argv;
    for (const auto& a : args) argv.push_back(const_cast<char*>(a.c_str()));
    argv.push_back(nullptr);
    const pid_t pid = fork();
    if (pid == 0) {
        execv(argv[0], argv.data());
        std::perror(argv[0]);
        _exit(127);
    }
    int status = 0;
    rusage usage{};
    if (pid < 0 || wait4(pid, &status, 0, &usage) < 0) return -1;
    peakKb = usage.ru_maxrss;
    return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

Run measure(const std::string& cli, const fs::path& work, int detail, int frames,
            const std::string& solver, bool keep) {
    Run run;
    const fs::path folder = work / ("detail" + std::to_string(detail));
    auto t0 = std::chrono::steady_clock::now();
    const DemoFiles demo =
        writeDemoFiles(folder.string(), frames, 10.0, false, detail, DemoSubject::Creature);
    run.generateS = secondsSince(t0);
    run.faces = demo.faces;
    run.vertices = demo.vertices;
    run.frames = demo.frames;
    const fs::path out = folder / "solved";
    long peakKb = 0;
    t0 = std::chrono::steady_clock::now();
    const int status =
        runMeasured({cli, "solve", "--mesh", demo.mesh, "--c3d", demo.take, "--map", demo.map,
                     "--out", out.string(), "--format", "pc2", "--solver", solver, "--quiet"},
                    peakKb);
    run.wallS = secondsSince(t0);
    run.peakMb = double(peakKb) / 1024.0;
    if (status != 0) {
        std::fprintf(stderr, "boneless-cli solve failed (status %d) on %d faces\n", status,
                     run.faces);
        return run;
    }
    const auto sidecar = nlohmann::json::parse(std::ifstream(out / "creature.json"));
    const auto& summary = sidecar.at("summary");
    run.frameMsMean = summary.at("ms_per_frame_mean").get<double>();
    run.frameMsWorst = summary.at("ms_per_frame_worst").get<double>();
    double frameS = 0;
    for (const auto& f : sidecar.at("per_frame")) frameS += f.at("ms").get<double>() / 1000.0;
    run.otherS = run.wallS - frameS;
    if (!keep) fs::remove_all(folder);
    return run;
}

void print(const char* name, const Run& r) {
    std::printf(
        "  %-9s %8d faces %7d vertices  peak %7.0f MB  wall %6.1f s  (%5.1f s besides "
        "the frames)  frame mean %7.1f ms, worst %7.1f ms  [generated in %.1f s]\n",
        name, r.faces, r.vertices, r.peakMb, r.wallS, r.otherS, r.frameMsMean, r.frameMsWorst,
        r.generateS);
}

}  // namespace

int main(int argc, char** argv) {
    CLI::App app{"Peak memory and time of boneless-cli solve on a million-face mesh (issue 29)"};
    int baseline = 6, large = 19, frames = 10;
    std::string solver = "local-global";
    std::string cli = BONELESS_CLI;
    std::string work = (fs::temp_directory_path() / "boneless-bench-large").string();
    app.add_option("--baseline-detail", baseline,
                   "creature detail of the baseline (faces = 2,784 x detail^2; 6: 100K)");
    app.add_option("--detail", large, "creature detail of the large mesh (19: 1.0M faces)");
    app.add_option("--frames", frames, "frames of each take")->check(CLI::PositiveNumber);
    app.add_option("--solver", solver, "local-global or exact");
    app.add_option("--cli", cli, "the boneless-cli to measure");
    app.add_option("--work", work,
                   "scratch folder (each mesh's files removed after it unless --keep)");
    bool keep = false;
    app.add_flag("--keep", keep, "keep the generated files and the solved output");
    CLI11_PARSE(app, argc, argv);

    std::printf(
        "boneless-bench-large: the demo creature and its take (%d frames, 30 markers), "
        "boneless-cli solve --solver %s --format pc2\n",
        frames, solver.c_str());
    const Run base = measure(cli, work, baseline, frames, solver, keep);
    print("baseline", base);
    const Run big = measure(cli, work, large, frames, solver, keep);
    print("large", big);
    if (base.peakMb <= 0 || big.peakMb <= 0 || big.frameMsMean <= 0) return 1;
    const double faces = double(big.faces) / base.faces;
    std::printf(
        "  large / baseline: faces %.2f, peak %.2f, frame mean %.2f, worst %.2f, "
        "besides the frames %.2f\n",
        faces, big.peakMb / base.peakMb, big.frameMsMean / base.frameMsMean,
        big.frameMsWorst / base.frameMsWorst, big.otherS / base.otherS);
    std::printf("  memory per face: baseline %.2f KB, large %.2f KB\n",
                base.peakMb * 1024 / base.faces, big.peakMb * 1024 / big.faces);
    const bool pass = big.peakMb <= kTargetPeakMb;
    std::printf("  %s: peak %.0f MB on %d faces (target <= %.0f MB)\n", pass ? "PASS" : "FAIL",
                big.peakMb, big.faces, kTargetPeakMb);
    return pass ? 0 : 1;
}
