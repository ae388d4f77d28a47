// Write time and size of each single-file export format for the whole CMU 85_02 take on the
// MakeHuman body (810 frames, 13,380 vertices), measured against PC2 in the same run.
// Usage: boneless-bench-export [REPEATS]   (needs ../shared/data; docs/export.md has the figures)

#include <unistd.h>
#include <CLI/CLI.hpp>
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <functional>
#include <string>

#include "boneless/C3dReader.h"
#include "boneless/GltfWriter.h"
#include "boneless/MddWriter.h"
#include "boneless/MeshReader.h"
#include "boneless/PointCacheWriter.h"
#include "boneless/TakeExport.h"

using namespace boneless;
namespace fs = std::filesystem;

int main(int argc, char** argv) {
    // Read by CLI11, not atoi: "--help" was read as 0 repeats, made 1, and the benchmark ran.
    int repeats = 5;
    CLI::App app{
        "Write time and size of each single-file export format (pc2, mdd, glb) for CMU 85_02 on "
        "the MakeHuman body, needs ../shared/data"};
    app.add_option("REPEATS", repeats, "Runs of each writer, the best kept")
        ->check(CLI::Range(1, 1000));
    CLI11_PARSE(app, argc, argv);
    const fs::path data(BONELESS_SHARED_DATA);
    const fs::path meshPath = data / "meshes" / "makehuman" / "makehuman_base.obj";
    const fs::path takePath = data / "c3d" / "cmu" / "85_02.c3d";
    const fs::path mapPath =
        fs::path(BONELESS_SOURCE_DIR) / "tests" / "data" / "cmu-85_02-makehuman-body.map.json";
    if (!fs::exists(meshPath) || !fs::exists(takePath)) {
        std::printf("skipped: %s or %s is missing\n", meshPath.c_str(), takePath.c_str());
        return 0;
    }
    MeshReadOptions group;
    group.group = "body";
    const TriMesh mesh = readMesh(meshPath.string(), group).mesh;
    const C3dTake take = readC3d(takePath.string());
    const fs::path work =
        fs::temp_directory_path() / ("boneless-bench-export-" + std::to_string(::getpid()));
    // The solved frames once (through PC2: the writers' input is float-exact either way).
    ExportRequest request;
    request.meshPath = meshPath.string();
    request.group = "body";
    request.c3dPath = takePath.string();
    request.mapPath = mapPath.string();
    request.outDir = (work / "solved").string();
    request.format = ExportFormat::Pc2;
    std::printf("solving %s on %s (body) ...\n", takePath.c_str(), meshPath.c_str());
    std::fflush(stdout);
    exportTake(mesh, take, Correspondence::read(mapPath.string()), request);
    const std::vector<Positions> frames = readPointCache((work / "solved" / "body.pc2").string());
    const double period = 1.0 / take.rate;

    struct Format {
        const char* name;
        std::function<void(const std::string&)> write;
    };
    const std::vector<Format> formats = {
        {"pc2",
         [&](const std::string& p) {
             PointCacheWriter w(p, mesh.vertexCount(), 0.0);
             for (const Positions& V : frames) w.append(V);
             w.finish();
         }},
        {"mdd",
         [&](const std::string& p) {
             MddWriter w(p, mesh.vertexCount());
             for (size_t f = 0; f < frames.size(); ++f) w.append(f * period, frames[f]);
             w.finish();
         }},
        {"glb",
         [&](const std::string& p) {
             GltfWriter w(p, mesh, "body");
             for (size_t f = 0; f < frames.size(); ++f)
                 w.append(static_cast<int>(f), f * period, frames[f]);
             w.finish();
         }},
    };
    std::printf("%zu frames, %d vertices, %d repeats; write time per file\n", frames.size(),
                mesh.vertexCount(), repeats);
    double pc2Mean = 0, pc2Worst = 0;
    for (const Format& format : formats) {
        const std::string path = (work / (std::string("body.") + format.name)).string();
        double sum = 0, worst = 0;
        for (int r = 0; r < repeats; ++r) {
            const auto t0 = std::chrono::steady_clock::now();
            format.write(path);
            const double s =
                std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
            sum += s;
            worst = std::max(worst, s);
        }
        const double mean = sum / repeats;
        if (pc2Mean == 0) pc2Mean = mean, pc2Worst = worst;
        std::printf("%s: %.1f MB, mean %.3f s (%.2fx pc2), worst %.3f s (%.2fx pc2)\n", format.name,
                    fs::file_size(path) / 1e6, mean, mean / pc2Mean, worst, worst / pc2Worst);
    }
    fs::remove_all(work);
    return 0;
}
