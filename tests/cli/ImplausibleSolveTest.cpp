// A wrong map solved without calibrating (the binary STL of a body with its OBJ's map) gave a body
// pulled apart with exit 0 and no word: solve now warns of a solve no body's and points at the map.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "CliRunner.h"

using namespace boneless::testing;
namespace fs = std::filesystem;

namespace {

// The demo in a fresh folder, with shuffled.map.json: its map with every vertex renumbered, as a
// mesh file of another vertex order would number them.
fs::path demoWithShuffledMap(const std::string& name) {
    const fs::path dir = freshTestDir(name);
    EXPECT_EQ(runCli("demo --out " + dir.string() + " --frame-count 3").exitCode, 0);
    nlohmann::json map;
    std::ifstream(dir / "walker.map.json") >> map;
    const int vertices = map["mesh"]["vertices"].get<int>();
    for (auto& m : map["markers"]) m["vertex"] = (m["vertex"].get<int>() * 7919 + 13) % vertices;
    std::ofstream(dir / "shuffled.map.json") << map.dump();
    return dir;
}

std::string solveArgs(const fs::path& dir, const std::string& mesh, const std::string& map,
                      const std::string& out) {
    return "solve --mesh " + (dir / mesh).string() + " --c3d " + (dir / "walker.c3d").string() +
           " --map " + (dir / map).string() + " --out " + (dir / out).string();
}

}  // namespace

TEST(ImplausibleSolve, AMapOfAnotherVertexOrderSolvedUncalibratedIsWarnedOfNamingTheMap) {
    const fs::path dir = demoWithShuffledMap("implausible-none");
    const CliResult r =
        runCli(solveArgs(dir, "walker.obj", "shuffled.map.json", "out") + " --calibrate none");
    EXPECT_EQ(r.exitCode, 0) << r.out;
    EXPECT_NE(r.out.find("warning: " + (dir / "walker.c3d").string() + ": the solve is no body's"),
              std::string::npos)
        << r.out;
    EXPECT_NE(r.out.find("check the map first: " + (dir / "shuffled.map.json").string()),
              std::string::npos)
        << r.out;
    // Said with --quiet too, as the take's other warnings are.
    const CliResult quiet = runCli(solveArgs(dir, "walker.obj", "shuffled.map.json", "quiet") +
                                   " --calibrate none --quiet");
    EXPECT_NE(quiet.out.find("the solve is no body's"), std::string::npos) << quiet.out;
}

TEST(ImplausibleSolve, TheReachRefusalPointsAtTheMapBeforeCalibrateNone) {
    const fs::path dir = demoWithShuffledMap("implausible-reach");
    const CliResult r = runCli(solveArgs(dir, "walker.obj", "shuffled.map.json", "out"));
    EXPECT_NE(r.exitCode, 0) << r.out;
    const std::size_t map = r.out.find("check the map first"), none = r.out.find("calibrate none");
    ASSERT_NE(map, std::string::npos) << r.out;
    EXPECT_LT(map, none) << r.out;
    EXPECT_NE(r.out.find("vertices in their order"), std::string::npos) << r.out;
}

TEST(ImplausibleSolve, ARightMapSolvesWithoutTheWarning) {
    const fs::path dir = demoWithShuffledMap("implausible-right");
    for (const char* calibrate : {"none", "shape"}) {
        const CliResult r = runCli(solveArgs(dir, "walker.obj", "walker.map.json", calibrate) +
                                   " --calibrate " + calibrate);
        EXPECT_EQ(r.exitCode, 0) << r.out;
        EXPECT_EQ(r.out.find("no body's"), std::string::npos) << r.out;
        EXPECT_EQ(r.out.find("was made on"), std::string::npos) << r.out;
    }
}

TEST(ImplausibleSolve, AMapMadeOnAnotherMeshFileIsNotedNamingBoth) {
    const fs::path dir = demoWithShuffledMap("implausible-file");
    fs::copy_file(dir / "walker.obj", dir / "walker_export.obj");
    const CliResult r = runCli(solveArgs(dir, "walker_export.obj", "walker.map.json", "out"));
    EXPECT_EQ(r.exitCode, 0) << r.out;
    EXPECT_NE(r.out.find("note: " + (dir / "walker.map.json").string() +
                         " was made on walker.obj, and the mesh is walker_export.obj"),
              std::string::npos)
        << r.out;
}
