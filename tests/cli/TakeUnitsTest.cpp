// A take whose markers are in other units than its POINT:UNITS says (CMU 85_02 in metres under
// "mm"): solve, batch and map suggest refuse it at once, offering --take-units first, inspect
// warns; with take_units saying the units, each reads it as a take in them.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "CliRunner.h"
#include "boneless/C3dReader.h"
#include "boneless/C3dWriter.h"
#include "boneless/OutputFolder.h"
#include "boneless/TakeExport.h"

using namespace boneless;
using namespace boneless::testing;
namespace fs = std::filesystem;

namespace {

// The demo in `dir`, and dir/metres.c3d: its take with every coordinate in metres, POINT:UNITS
// still "mm".
fs::path demoInMetres(const std::string& name) {
    const fs::path dir = freshTestDir(name);
    EXPECT_EQ(runCli("demo --out " + dir.string() + " --frame-count 3").exitCode, 0);
    C3dTake take = readC3d((dir / "walker.c3d").string());
    for (std::size_t f = 0; f < take.samples.frames(); ++f)
        for (std::size_t k = 0; k < take.samples.points(); ++k)
            if (const auto p = take.samples.position(f, k)) {
                const Eigen::Vector3d m = *p / 1000.0;
                take.samples.set(f, k, m.x(), m.y(), m.z(), take.samples.residual(f, k) / 1000.0f);
            }
    EXPECT_EQ(take.units, "mm");
    writeC3d(take, (dir / "metres.c3d").string());
    return dir;
}

// Every vertex of the OBJ frames `stem`_NNNN.obj in `dir`, in file order.
std::vector<double> objVertices(const fs::path& dir, int first, int end) {
    std::vector<double> xyz;
    for (int f = first; f < end; ++f) {
        std::ifstream in(dir / objFrameFile("walker", f));
        EXPECT_TRUE(in) << (dir / objFrameFile("walker", f));
        std::string line;
        while (std::getline(in, line))
            if (line.rfind("v ", 0) == 0) {
                std::istringstream v(line.substr(2));
                double x, y, z;
                v >> x >> y >> z;
                xyz.insert(xyz.end(), {x, y, z});
            }
    }
    return xyz;
}

std::string solveArgs(const fs::path& dir, const std::string& out) {
    return "solve --mesh " + (dir / "walker.obj").string() + " --c3d " +
           (dir / "metres.c3d").string() + " --map " + (dir / "walker.map.json").string() +
           " --out " + (dir / out).string();
}

}  // namespace

TEST(TakeUnits, SolveRefusesATakeInMetresUnderMillimetresBeforePreparingAndOffersTakeUnitsFirst) {
    const fs::path dir = demoInMetres("units-solve");
    const CliResult r = runCli(solveArgs(dir, "out"));
    EXPECT_NE(r.exitCode, 0) << r.out;
    EXPECT_NE(r.out.find("metres.c3d: its markers span"), std::string::npos) << r.out;
    EXPECT_NE(r.out.find("although POINT:UNITS says mm: are they in metres"), std::string::npos)
        << r.out;
    EXPECT_NE(r.out.find("nothing was solved: give --take-units m, or set the file's POINT:UNITS "
                         "to m"),
              std::string::npos)
        << r.out;
    EXPECT_EQ(r.out.find("preparing"), std::string::npos) << r.out;
    EXPECT_FALSE(fs::exists(dir / "out" / "walker.json"));
}

TEST(TakeUnits, MapSuggestRefusesItBeforeTheFitAndWritesNothing) {
    const fs::path dir = demoInMetres("units-suggest");
    const std::string args = "map suggest --mesh " + (dir / "walker.obj").string() + " --c3d " +
                             (dir / "metres.c3d").string() + " --map " +
                             (dir / "walker.map.json").string() + " --out " +
                             (dir / "full.json").string();
    const CliResult r = runCli(args);
    EXPECT_NE(r.exitCode, 0) << r.out;
    EXPECT_NE(r.out.find("metres.c3d: its markers span"), std::string::npos) << r.out;
    EXPECT_NE(r.out.find("nothing was written: give --take-units m, or set the file's POINT:UNITS "
                         "to m"),
              std::string::npos)
        << r.out;
    EXPECT_FALSE(fs::exists(dir / "full.json"));
}

TEST(TakeUnits, BatchRefusesTheTakeAndGoesOnWithTheOthers) {
    const fs::path dir = demoInMetres("units-batch");
    nlohmann::json entry = {
        {"c3d", "metres.c3d"}, {"mesh", "walker.obj"}, {"map", "walker.map.json"}, {"out", "out"}};
    nlohmann::json right = entry;
    right["c3d"] = "walker.c3d";
    right["out"] = "right";
    std::ofstream(dir / "m.json") << nlohmann::json({{"takes", {entry, right}}}).dump();
    const CliResult r = runCli("batch " + (dir / "m.json").string());
    EXPECT_NE(r.exitCode, 0) << r.out;
    EXPECT_NE(r.out.find("metres.c3d: its markers span"), std::string::npos) << r.out;
    EXPECT_NE(r.out.find("nothing was solved: give \"take_units\": \"m\", or set the file's"),
              std::string::npos)
        << r.out;
    EXPECT_FALSE(fs::exists(dir / "out" / "walker.json"));
    EXPECT_TRUE(fs::exists(dir / "right" / "walker.json")) << r.out;
}

TEST(TakeUnits, InspectWarnsOfItWithTheSpan) {
    const fs::path dir = demoInMetres("units-inspect");
    const CliResult r = runCli("inspect " + (dir / "metres.c3d").string());
    EXPECT_EQ(r.exitCode, 0) << r.out;
    EXPECT_NE(r.out.find("see the warning"), std::string::npos) << r.out;
    EXPECT_NE(r.out.find("warning   its markers span"), std::string::npos) << r.out;
    const CliResult right = runCli("inspect " + (dir / "walker.c3d").string());
    EXPECT_NE(right.out.find(", markers span "), std::string::npos) << right.out;
    EXPECT_EQ(right.out.find("see the warning"), std::string::npos) << right.out;
    EXPECT_EQ(right.out.find("its markers span"), std::string::npos) << right.out;
}

// Against the take in millimetres: the same frames. Uncalibrated, to 1e-6 of the body's size (the
// float32 coordinates of the two files round apart by 6e-8); calibrated, to 1e-4, the shape fit's
// iterations stopping at a relative tolerance on those inputs (measured: 9e-6).
TEST(TakeUnits, SolveWithTakeUnitsSolvesTheMetresTakeAsTheOneInMillimetresAndTheSidecarSaysSo) {
    const fs::path dir = demoInMetres("units-solve-m");
    for (const auto& [calibrate, tolerance] : {std::pair{"none", 1e-6}, {"shape", 1e-4}}) {
        const std::string options = std::string(" --frames 1:3 --calibrate ") + calibrate;
        const std::string metres = std::string("metres-") + calibrate;
        const std::string millimetres = std::string("millimetres-") + calibrate;
        const CliResult m = runCli(solveArgs(dir, metres) + " --take-units m" + options);
        ASSERT_EQ(m.exitCode, 0) << m.out;
        // solve's line names the units used and what the file says.
        EXPECT_NE(m.out.find("units m (--take-units; the file says mm)"), std::string::npos)
            << m.out;
        EXPECT_EQ(m.out.find("its markers span"), std::string::npos) << m.out;
        const CliResult mm =
            runCli("solve --mesh " + (dir / "walker.obj").string() + " --c3d " +
                   (dir / "walker.c3d").string() + " --map " + (dir / "walker.map.json").string() +
                   " --out " + (dir / millimetres).string() + options);
        ASSERT_EQ(mm.exitCode, 0) << mm.out;
        const std::vector<double> a = objVertices(dir / metres, 1, 3);
        const std::vector<double> b = objVertices(dir / millimetres, 1, 3);
        ASSERT_EQ(a.size(), b.size());
        ASSERT_FALSE(a.empty());
        double scale = 0, worst = 0;
        for (double x : b) scale = std::max(scale, std::abs(x));
        for (std::size_t i = 0; i < a.size(); ++i) worst = std::max(worst, std::abs(a[i] - b[i]));
        EXPECT_LE(worst, tolerance * scale) << calibrate << ": " << worst << " of " << scale;
        const nlohmann::json s = nlohmann::json::parse(std::ifstream(dir / metres / "walker.json"));
        EXPECT_EQ(s["options"]["take_units"], "m");
        EXPECT_EQ(s["units"]["take"], "m");
        EXPECT_EQ(nlohmann::json::parse(
                      std::ifstream(dir / millimetres / "walker.json"))["options"]["take_units"],
                  "file");
    }
}

TEST(TakeUnits, TakeUnitsThatMakeTheTakeNoBodysAreDoubtedNamingTheFlag) {
    const fs::path dir = demoInMetres("units-wrong-flag");
    const CliResult r =
        runCli("solve --mesh " + (dir / "walker.obj").string() + " --c3d " +
               (dir / "walker.c3d").string() + " --map " + (dir / "walker.map.json").string() +
               " --out " + (dir / "out").string() + " --take-units m");
    EXPECT_NE(r.exitCode, 0) << r.out;
    EXPECT_NE(r.out.find("although --take-units says m: are they in millimetres"),
              std::string::npos)
        << r.out;
    EXPECT_NE(r.out.find("nothing was solved: give --take-units mm instead"), std::string::npos)
        << r.out;
    EXPECT_FALSE(fs::exists(dir / "out" / "walker.json"));
}

TEST(TakeUnits, MapSuggestReadsTheTakeInTakeUnits) {
    const fs::path dir = demoInMetres("units-suggest-m");
    const CliResult r =
        runCli("map suggest --mesh " + (dir / "walker.obj").string() + " --c3d " +
               (dir / "metres.c3d").string() + " --map " + (dir / "walker.map.json").string() +
               " --out " + (dir / "full.json").string() + " --take-units m");
    EXPECT_EQ(r.exitCode, 0) << r.out;
    EXPECT_EQ(r.out.find("its markers span"), std::string::npos) << r.out;
    EXPECT_TRUE(fs::exists(dir / "full.json"));
}

TEST(TakeUnits, BatchReadsTakeUnitsFromTheEntryOrTheDefaults) {
    const fs::path dir = demoInMetres("units-batch-m");
    const nlohmann::json entry = {{"c3d", "metres.c3d"},      {"mesh", "walker.obj"},
                                  {"map", "walker.map.json"}, {"frames", "1:3"},
                                  {"out", "entry"},           {"take_units", "m"}};
    nlohmann::json fromDefaults = entry;
    fromDefaults.erase("take_units");
    fromDefaults["out"] = "defaults";
    std::ofstream(dir / "entry.json") << nlohmann::json({{"takes", {entry}}}).dump();
    std::ofstream(dir / "defaults.json")
        << nlohmann::json({{"defaults", {{"take_units", "m"}}}, {"takes", {fromDefaults}}}).dump();
    for (const char* manifest : {"entry.json", "defaults.json"}) {
        const CliResult r = runCli("batch " + (dir / manifest).string());
        EXPECT_EQ(r.exitCode, 0) << manifest << ": " << r.out;
    }
    for (const char* out : {"entry", "defaults"}) {
        const fs::path sidecar = dir / out / "walker.json";
        ASSERT_TRUE(fs::exists(sidecar)) << out;
        EXPECT_EQ(nlohmann::json::parse(std::ifstream(sidecar))["options"]["take_units"], "m");
    }
    // Run again, the takes are done: the key is read as the sidecar recorded it.
    const CliResult again = runCli("batch " + (dir / "entry.json").string());
    EXPECT_NE(again.out.find("0 solved, 1 skipped"), std::string::npos) << again.out;
}

TEST(TakeUnits, AManifestsTakeUnitsMustBeOneOfTheUnitsAndTheMessageNamesTheKey) {
    const fs::path dir = demoInMetres("units-batch-key");
    const nlohmann::json entry = {{"c3d", "metres.c3d"},
                                  {"mesh", "walker.obj"},
                                  {"map", "walker.map.json"},
                                  {"out", "out"},
                                  {"take_units", "yards"}};
    std::ofstream(dir / "m.json") << nlohmann::json({{"takes", {entry}}}).dump();
    const CliResult r = runCli("batch " + (dir / "m.json").string());
    EXPECT_NE(r.exitCode, 0) << r.out;
    EXPECT_NE(r.out.find("\"take_units\" must be one of file, mm, cm, dm, m, in, ft, got "
                         "\"yards\""),
              std::string::npos)
        << r.out;
}

TEST(TakeUnits, InspectShowsTheUnitsUsedAndWhatTheFileSays) {
    const fs::path dir = demoInMetres("units-inspect-m");
    const std::string take = (dir / "metres.c3d").string();
    const CliResult r = runCli("inspect " + take + " --take-units m");
    EXPECT_EQ(r.exitCode, 0) << r.out;
    EXPECT_NE(r.out.find("units     m (--take-units; the file says mm) (x1000 to mm), markers "
                         "span "),
              std::string::npos)
        << r.out;
    EXPECT_EQ(r.out.find("its markers span"), std::string::npos) << r.out;
    const CliResult j = runCli("inspect " + take + " --take-units m --json");
    ASSERT_EQ(j.exitCode, 0) << j.out;
    const nlohmann::json read = nlohmann::json::parse(j.out);
    EXPECT_EQ(read["units"], "m");
    EXPECT_EQ(read["file_units"], "mm");
    EXPECT_EQ(read["unit_to_mm"], 1000.0);
    EXPECT_GT(read["marker_span_mm"].get<double>(), 300.0);
    const CliResult plain = runCli("inspect " + take + " --json");
    EXPECT_EQ(nlohmann::json::parse(plain.out)["units"], "mm");
}
