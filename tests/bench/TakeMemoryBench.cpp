// boneless-bench-take-memory: how much memory a long take costs, per byte of its file, in
// `boneless-cli inspect` (which reads it whole) and in the app opening it with the demo's mesh and
// map and solving a frame (--screenshot). A 25-minute take at 120 Hz (180,000 frames of the
// demo walker's 39 markers, 112 MB) held the app at 825-860 MB: 7.5 bytes per byte of file.
//
// The takes are made here: `boneless-cli demo` writes a short one, and that one repeated to the
// long one's length is written with writeC3d. Each program runs as a user runs it, in a process of
// its own; its resident set is sampled every 50 ms for the mean and read from the kernel's
// high-water mark for the worst (peak). The short take's run is the baseline: the figure is the
// bytes the long take adds per byte its file adds.

#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <CLI/CLI.hpp>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>
#include <thread>
#include <vector>

#include "boneless/C3dReader.h"
#include "boneless/C3dWriter.h"

using namespace boneless;
namespace fs = std::filesystem;

namespace {

struct Run {
    double meanMb = 0, peakMb = 0;
};

long residentKb(pid_t pid) {
    std::ifstream status("/proc/" + std::to_string(pid) + "/status");
    std::string line;
    while (std::getline(status, line))
        if (line.rfind("VmRSS:", 0) == 0) return std::stol(line.substr(6));
    return 0;
}

// Runs args (stdout and stderr to `log`); exits naming the command when it fails.
Run measure(std::vector<std::string> args, const std::string& log) {
    std::vector<char*> argv;
    for (auto& a : args) argv.push_back(a.data());
    argv.push_back(nullptr);
    std::fflush(stdout);  // else the child prints what this process has buffered again
    const pid_t pid = ::fork();
    if (pid == 0) {
        if (std::freopen(log.c_str(), "w", stdout) && std::freopen(log.c_str(), "a", stderr))
            ::execv(args[0].c_str(), argv.data());
        std::perror(args[0].c_str());
        ::_exit(127);
    }
    double sum = 0;
    long samples = 0;
    int status = 0;
    rusage usage{};
    for (;;) {
        if (::wait4(pid, &status, WNOHANG, &usage) == pid) break;
        if (const long kb = residentKb(pid)) sum += kb, ++samples;
        std::this_thread::sleep_for(std::chrono::milliseconds(50));
    }
    if (!WIFEXITED(status) || WEXITSTATUS(status) != 0) {
        std::string command;
        for (const auto& a : args) command += (command.empty() ? "" : " ") + a;
        std::fprintf(stderr, "%s failed (status %d); its output is in %s\n", command.c_str(),
                     status, log.c_str());
        std::exit(1);
    }
    Run r;
    r.peakMb = usage.ru_maxrss / 1024.0;
    r.meanMb = samples ? sum / samples / 1024.0 : r.peakMb;
    return r;
}

void report(const char* what, const Run& base, const Run& big, double addedMb) {
    std::printf("%-8s %14.1f %14.1f %14.1f %14.1f %10.2f %10.2f\n", what, base.meanMb, base.peakMb,
                big.meanMb, big.peakMb, (big.meanMb - base.meanMb) / addedMb,
                (big.peakMb - base.peakMb) / addedMb);
}

}  // namespace

int main(int argc, char** argv) {
    CLI::App app{
        "Memory a long take costs per byte of its file, in boneless-cli inspect and in the app "
        "(the app only when DISPLAY is set, e.g. under Xvfb)"};
    int small = 2000, large = 180000;
    std::string work = (fs::temp_directory_path() / "boneless-bench-take-memory").string();
    std::string cli = BONELESS_CLI, gui = BONELESS_APP;
    bool keep = false;
    app.add_option("--small", small, "Frames of the baseline take (1 to 100000)")
        ->check(CLI::Range(1, 100000));
    app.add_option("--large", large, "Frames of the long take")->check(CLI::PositiveNumber);
    app.add_option("--work", work, "Folder for the takes (emptied)");
    app.add_option("--cli", cli, "The boneless-cli to measure");
    app.add_option("--app", gui, "The boneless app to measure");
    app.add_flag("--keep", keep, "Keep the takes in --work");
    CLI11_PARSE(app, argc, argv);

    fs::remove_all(work);
    fs::create_directories(work);
    const fs::path dir(work);
    const std::string demo = (dir / "demo").string();
    measure({cli, "demo", "--out", demo, "--frame-count", std::to_string(small)},
            (dir / "demo.log").string());
    const std::string shortTake = (fs::path(demo) / "walker.c3d").string();
    const std::string longTake = (dir / "long.c3d").string();
    {
        const C3dTake take = readC3d(shortTake);
        C3dTake repeated = take;
        repeated.samples = C3dSamples(std::size_t(large), take.points.size());
        for (std::size_t f = 0; f < std::size_t(large); ++f)
            for (std::size_t k = 0; k < take.points.size(); ++k)
                if (const auto p = take.samples.position(f % take.frameCount(), k))
                    repeated.samples.set(f, k, p->x(), p->y(), p->z(),
                                         take.samples.residual(f % take.frameCount(), k));
        writeC3d(repeated, longTake);
    }
    const double shortMb = fs::file_size(shortTake) / 1048576.0;
    const double longMb = fs::file_size(longTake) / 1048576.0;
    std::printf("takes: %d frames (%.1f MB) and %d frames (%.1f MB) of the demo walker\n", small,
                shortMb, large, longMb);
    std::printf("%-8s %14s %14s %14s %14s %10s %10s\n", "", "short mean MB", "short peak MB",
                "long mean MB", "long peak MB", "mean B/B", "peak B/B");
    const Run inspectShort = measure({cli, "inspect", shortTake}, (dir / "inspect.log").string());
    const Run inspectLong = measure({cli, "inspect", longTake}, (dir / "inspect.log").string());
    report("inspect", inspectShort, inspectLong, longMb - shortMb);
    if (!gui.empty() && std::getenv("DISPLAY")) {
        auto open = [&](const std::string& take) {
            return measure({gui, (fs::path(demo) / "walker.obj").string(), take,
                            (fs::path(demo) / "walker.map.json").string(), "--frame", "0",
                            "--screenshot", (dir / "frame.png").string(), "--size", "320x240"},
                           (dir / "app.log").string());
        };
        const Run appShort = open(shortTake);
        report("app", appShort, open(longTake), longMb - shortMb);
    } else {
        std::printf("app: not measured (%s)\n", gui.empty() ? "not built: BONELESS_BUILD_GUI is off"
                                                            : "no DISPLAY; run under Xvfb");
    }
    std::printf("B/B: bytes held per byte of file the long take adds (its file's own size: 1)\n");
    if (!keep) fs::remove_all(work);
    return 0;
}
