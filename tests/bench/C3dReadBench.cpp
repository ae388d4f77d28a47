// C3D read throughput on a generated ~100 MB take (the bar: under one second).

#include <CLI/CLI.hpp>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <random>

#include "boneless/C3dReader.h"
#include "boneless/C3dWriter.h"

using namespace boneless;

namespace {

C3dTake largeTake(std::size_t frames, std::size_t points) {
    C3dTake t;
    t.rate = 240.0;
    t.pointScale = -0.1;
    for (std::size_t k = 0; k < points; ++k) {
        C3dPoint p;
        p.label = "actor:M" + std::to_string(k);
        t.points.push_back(p);
    }
    t.samples = C3dSamples(frames, points);
    std::mt19937 rng(3);
    std::uniform_real_distribution<float> u(-2000.0f, 2000.0f);
    for (std::size_t f = 0; f < frames; ++f)
        for (std::size_t k = 0; k < points; ++k)
            if (rng() % 20 != 0) t.samples.set(f, k, u(rng), u(rng), u(rng), 0.5f);
    return t;
}

struct Timing {
    double mean = 0, worst = 0;  // seconds
};

template <class F>
Timing time(int repeats, F&& f) {
    Timing t;
    for (int i = 0; i < repeats; ++i) {
        const auto t0 = std::chrono::steady_clock::now();
        f();
        const auto t1 = std::chrono::steady_clock::now();
        const double s = std::chrono::duration<double>(t1 - t0).count();
        t.mean += s / repeats;
        t.worst = std::max(t.worst, s);
    }
    return t;
}

}  // namespace

int main(int argc, char** argv) {
    // No options, but --help says what it does, and a mistyped argument is refused, rather than
    // writing 100 MB to the temporary folder and reading it three times.
    CLI::App app{
        "Reads a generated 100 MB C3D take (60,000 frames x 110 points) from memory and from a "
        "file in the temporary folder, 5 times each: the mean and the worst, the file's against "
        "memory's (the same run's baseline), and whether the file reads in under a second"};
    CLI11_PARSE(app, argc, argv);
    const std::size_t frames = 60000, points = 110;  // 60000 x 110 x 16 bytes = 105.6 MB
    const std::vector<std::uint8_t> bytes = encodeC3d(largeTake(frames, points));
    const double mb = double(bytes.size()) / 1e6;
    const std::filesystem::path path =
        std::filesystem::temp_directory_path() / "boneless-bench-c3d.c3d";
    writeC3d(readC3dMemory(bytes.data(), bytes.size(), "bench"), path.string());

    std::size_t frameCount = 0;
    const Timing memory = time(
        5, [&] { frameCount = readC3dMemory(bytes.data(), bytes.size(), "bench").frameCount(); });
    const Timing file = time(5, [&] { frameCount = readC3d(path.string()).frameCount(); });
    std::filesystem::remove(path);

    std::printf("C3D take: %zu frames x %zu points, float, %.1f MB\n", frameCount, points, mb);
    std::printf("                   mean s  worst s  MB/s (mean)  ratio\n");
    std::printf("  read from memory  %6.3f   %6.3f   %10.0f   1.00\n", memory.mean, memory.worst,
                mb / memory.mean);
    std::printf("  read from file    %6.3f   %6.3f   %10.0f   %4.2f\n", file.mean, file.worst,
                mb / file.mean, file.mean / memory.mean);
    const bool ok = file.mean < 1.0 && frameCount == frames;
    std::printf("  %s: a 100 MB take parses in under a second\n", ok ? "PASS" : "FAIL");
    return ok ? 0 : 1;
}
