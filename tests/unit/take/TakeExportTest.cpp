// exportTake's sidecar: what was solved, traceable afterwards.
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <vector>

#include "boneless/C3dReader.h"
#include "boneless/Correspondence.h"
#include "boneless/DemoFiles.h"
#include "boneless/Error.h"
#include "boneless/MeshReader.h"
#include "boneless/OutputFolder.h"
#include "boneless/Parallel.h"
#include "boneless/TakeExport.h"

using namespace boneless;
using nlohmann::json;

// The app solves a map edited since it was read, or kept only in the project: its export's
// sidecar said "map": "" and fingerprinted that as "unreadable". It now holds the map solved.
TEST(TakeExport, AMapThatIsInNoFileIsKeptInTheSidecar) {
    const DemoFiles files = writeDemoFiles(freshTestDir("export-map"), 3, 10.0, false);
    const TriMesh mesh = readMesh(files.mesh).mesh;
    const C3dTake take = readC3d(files.take);
    Correspondence edited = Correspondence::read(files.map);
    edited.markers[0].offsetMm = 14.5;  // as the app's offset box leaves it
    auto sidecarOf = [&](const std::string& mapPath, const std::string& dir) {
        ExportRequest request;
        request.meshPath = files.mesh;
        request.c3dPath = files.take;
        request.mapPath = mapPath;
        request.outDir = freshTestDir(dir);
        request.format = ExportFormat::Pc2;
        return json::parse(std::ifstream(exportTake(mesh, take, edited, request).sidecarPath));
    };

    const json inNoFile = sidecarOf("", "export-map-none");
    EXPECT_TRUE(inNoFile["source"]["map"].is_null());
    EXPECT_TRUE(inNoFile["source_fingerprints"]["map"].is_null());
    ASSERT_TRUE(inNoFile.contains("map"));
    const Correspondence kept = Correspondence::fromJson(inNoFile["map"].dump(), "sidecar");
    EXPECT_EQ(kept.toJson(), edited.toJson());

    const json inAFile = sidecarOf(files.map, "export-map-file");
    EXPECT_EQ(inAFile["source"]["map"], files.map);
    EXPECT_TRUE(inAFile["source_fingerprints"]["map"].is_string());
    EXPECT_FALSE(inAFile.contains("map")) << "a map in a file is named, not copied";
}

// A take held in memory (the app's) may carry a rate that is not a number: a glb of it is
// refused as one of rate 0 is, saying so.
TEST(TakeExport, AGlbOfATakeWhoseRateIsNotANumberIsRefusedSayingSo) {
    const DemoFiles files = writeDemoFiles(freshTestDir("export-nan-rate"), 3, 10.0, false);
    const TriMesh mesh = readMesh(files.mesh).mesh;
    C3dTake take = readC3d(files.take);
    take.rate = std::nan("");
    ExportRequest request;
    request.meshPath = files.mesh;
    request.c3dPath = files.take;
    request.mapPath = files.map;
    request.outDir = freshTestDir("export-nan-rate-out");
    request.format = ExportFormat::Glb;
    try {
        exportTake(mesh, take, Correspondence::read(files.map), request);
        FAIL() << "exported";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find(files.take + ": its frame rate is not a number"),
                  std::string::npos)
            << e.what();
    }
}

// Blender names a mesh's copies "Body.001" and "Body.002": the group's stem made both "Body", so
// two groups solved into one folder replaced each other's files. A group is a name, not a path.
TEST(TakeExport, AGroupNamesItsFilesWholeAndKeepsThemInTheFolder) {
    ExportRequest request;
    request.meshPath = "/data/two.obj";
    EXPECT_EQ(exportStem(request), "two");
    request.group = "Body.001";
    EXPECT_EQ(exportStem(request), "Body.001");
    request.group = "Body.002";
    EXPECT_EQ(exportStem(request), "Body.002");
    request.group = "../../evil";
    EXPECT_EQ(exportStem(request), ".._.._evil");
    request.group = "..";
    EXPECT_EQ(exportStem(request), "__");
    request.group = "pCube1|body?";  // Maya's path names: Windows holds no '|' or '?'
    EXPECT_EQ(exportStem(request), "pCube1_body_");
}

// On the 100K-face koala a 2-frame export had both frames written at 10.1 s but ended at 13.6 s:
// a second worker was still preparing a solver that would never solve a frame.
TEST(TakeExport, AShortTakeIsSolvedByOneWorkerAndALongerOneByOnePerCore) {
    if (solverThreadCount() < 2) GTEST_SKIP() << "one core: one worker whatever the take";
    const DemoFiles files = writeDemoFiles(freshTestDir("export-workers"), 24, 10.0, false);
    const TriMesh mesh = readMesh(files.mesh).mesh;
    const C3dTake take = readC3d(files.take);
    const Correspondence map = Correspondence::read(files.map);
    auto workersFor = [&](int frames) {
        ExportRequest request;
        request.meshPath = files.mesh;
        request.c3dPath = files.take;
        request.mapPath = files.map;
        request.outDir = freshTestDir("export-workers-" + std::to_string(frames));
        request.format = ExportFormat::Pc2;
        request.end = frames;
        return exportTake(mesh, take, map, request).workers;
    };
    EXPECT_EQ(workersFor(2), 1);
    EXPECT_EQ(workersFor(24), solverThreadCount());
}

// A run solving a take again removed the earlier sidecar as it began: when it then failed (a full
// disk), the earlier export's cache was named by no sidecar, and every later run refused it as no
// Boneless export's until --force. A sidecar saying "complete": false stands in while it runs.
TEST(TakeExport, ARunThatFailsPartWayLeavesTheEarlierCacheTheToolsOwn) {
    const DemoFiles files = writeDemoFiles(freshTestDir("export-fails"), 3, 10.0, false);
    const TriMesh mesh = readMesh(files.mesh).mesh;
    const C3dTake take = readC3d(files.take);
    const Correspondence map = Correspondence::read(files.map);
    ExportRequest request;
    request.meshPath = files.mesh;
    request.c3dPath = files.take;
    request.mapPath = files.map;
    request.outDir = freshTestDir("export-fails-out");
    request.format = ExportFormat::Pc2;
    exportTake(mesh, take, map, request);
    const std::filesystem::path out(request.outDir);
    const std::string cache = (out / (exportStem(request) + ".pc2")).string();
    // The cache's temporary cannot be made, as on a full disk: a folder has its name.
    const std::string temporary = cache + ".tmp" + std::to_string(::getpid());
    ASSERT_TRUE(std::filesystem::create_directory(temporary));
    EXPECT_THROW(exportTake(mesh, take, map, request), Error);
    std::error_code ec;
    std::filesystem::remove(temporary, ec);
    ASSERT_TRUE(std::filesystem::exists(cache));
    EXPECT_EQ(filesNoExportWrote(request, 3), std::vector<std::string>{});
    const std::filesystem::path sidecar = out / (exportStem(request) + ".json");
    ASSERT_TRUE(std::filesystem::exists(sidecar));
    EXPECT_FALSE(json::parse(std::ifstream(sidecar))["complete"].get<bool>());
}

// The sidecar's ms_per_frame_median took the upper of the two middle frames of an even count,
// where eval and boneless-bench average them: one key, two figures for the same frames (the CMU
// take's 810 frames: 182.398 ms in the sidecar, 182.325 the median of its own per_frame).
TEST(TakeExport, TheSidecarsMedianTimeIsTheMedianOfItsFramesTimes) {
    const DemoFiles files = writeDemoFiles(freshTestDir("export-median"), 4, 10.0, false);
    const TriMesh mesh = readMesh(files.mesh).mesh;
    const C3dTake take = readC3d(files.take);
    const Correspondence map = Correspondence::read(files.map);
    for (const int frames : {3, 4}) {
        ExportRequest request;
        request.meshPath = files.mesh;
        request.c3dPath = files.take;
        request.mapPath = files.map;
        request.outDir = freshTestDir("export-median-" + std::to_string(frames));
        request.format = ExportFormat::Pc2;
        request.end = frames;
        const json sidecar =
            json::parse(std::ifstream(exportTake(mesh, take, map, request).sidecarPath));
        std::vector<double> ms;
        for (const json& f : sidecar["per_frame"]) ms.push_back(f["ms"].get<double>());
        ASSERT_EQ(ms.size(), static_cast<size_t>(frames));
        std::sort(ms.begin(), ms.end());
        const size_t m = ms.size() / 2;
        const double median = ms.size() % 2 ? ms[m] : 0.5 * (ms[m - 1] + ms[m]);
        EXPECT_DOUBLE_EQ(sidecar["summary"]["ms_per_frame_median"].get<double>(), median)
            << frames << " frames";
    }
}
