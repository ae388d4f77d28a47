// A take whose markers are in other units than its POINT:UNITS says (CMU 85_02 in metres under
// "mm"): solve, batch and map suggest refuse it at once, inspect warns.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "CliRunner.h"
#include "boneless/C3dReader.h"
#include "boneless/C3dWriter.h"

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

std::string solveArgs(const fs::path& dir, const std::string& out) {
    return "solve --mesh " + (dir / "walker.obj").string() + " --c3d " +
           (dir / "metres.c3d").string() + " --map " + (dir / "walker.map.json").string() +
           " --out " + (dir / out).string();
}

}  // namespace

TEST(TakeUnits, SolveRefusesATakeInMetresUnderMillimetresBeforePreparingAndSaysHowToFixIt) {
    const fs::path dir = demoInMetres("units-solve");
    const CliResult r = runCli(solveArgs(dir, "out"));
    EXPECT_NE(r.exitCode, 0) << r.out;
    EXPECT_NE(r.out.find("metres.c3d: its markers span"), std::string::npos) << r.out;
    EXPECT_NE(r.out.find("although POINT:UNITS says mm: are they in metres"), std::string::npos)
        << r.out;
    EXPECT_NE(r.out.find("nothing was solved: set the file's POINT:UNITS to m"), std::string::npos)
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
    EXPECT_NE(r.out.find("nothing was written: set the file's POINT:UNITS to m"), std::string::npos)
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
