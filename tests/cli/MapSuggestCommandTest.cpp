// boneless-cli map suggest as a user runs it: a partial map in, a completed map out, and --check
// measuring the proposals against a map known to be right.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "CliRunner.h"

using namespace boneless::testing;
namespace fs = std::filesystem;

TEST(MapSuggestCommand, CompletesAPartialMapAndChecksItAgainstTheTrueOne) {
    const fs::path dir = freshTestDir("map-suggest");
    ASSERT_EQ(runCli("demo --out " + dir.string() + " --frames 20").exitCode, 0);
    nlohmann::json map;
    std::ifstream(dir / "walker.map.json") >> map;
    nlohmann::json picks = nlohmann::json::array();
    for (const auto& m : map["markers"])
        for (const char* label : {"LFHD", "LASI", "LWRA", "RWRA", "LANK", "RANK"})
            if (m["label"] == label) picks.push_back(m);
    ASSERT_EQ(picks.size(), 6u);
    const int total = static_cast<int>(map["markers"].size());
    map["markers"] = picks;
    std::ofstream(dir / "partial.json") << map.dump();

    const CliResult r = runCli(
        "map suggest --mesh " + (dir / "walker.obj").string() + " --c3d " +
        (dir / "walker.c3d").string() + " --map " + (dir / "partial.json").string() + " --out " +
        (dir / "full.json").string() + " --check " + (dir / "walker.map.json").string());
    ASSERT_EQ(r.exitCode, 0) << r.out;
    const std::string counted = std::to_string(total - 6) + " of " + std::to_string(total - 6);
    EXPECT_NE(r.out.find(counted + " within 30 mm, median 0.0 mm"), std::string::npos) << r.out;
    EXPECT_NE(r.out.find("0 to review"), std::string::npos) << r.out;
    nlohmann::json full;
    std::ifstream(dir / "full.json") >> full;
    ASSERT_EQ(static_cast<int>(full["markers"].size()), total);
    int suggested = 0;
    for (const auto& m : full["markers"]) suggested += m.value("suggested", false) ? 1 : 0;
    EXPECT_EQ(suggested, total - 6);
}

TEST(MapSuggestCommand, MistakesNameTheFileAndTheReason) {
    const fs::path dir = freshTestDir("map-suggest-mistakes");
    ASSERT_EQ(runCli("demo --out " + dir.string() + " --frames 5").exitCode, 0);
    nlohmann::json map;
    std::ifstream(dir / "walker.map.json") >> map;
    map["markers"] =
        nlohmann::json::array({map["markers"][0], map["markers"][1], map["markers"][2]});
    std::ofstream(dir / "three.json") << map.dump();
    auto suggest = [&](const std::string& partial) {
        return runCli("map suggest --mesh " + (dir / "walker.obj").string() + " --c3d " +
                      (dir / "walker.c3d").string() + " --map " + partial + " --out " +
                      (dir / "full.json").string());
    };
    CliResult r = suggest((dir / "three.json").string());
    EXPECT_EQ(r.exitCode, 1) << r.out;
    EXPECT_NE(r.out.find("three.json: suggesting correspondences needs at least 4"),
              std::string::npos)
        << r.out;
    r = suggest((dir / "absent.json").string());
    EXPECT_EQ(r.exitCode, 1) << r.out;
    EXPECT_NE(r.out.find("absent.json: cannot open the correspondence file (No such file"),
              std::string::npos)
        << r.out;
    EXPECT_FALSE(fs::exists(dir / "full.json"));
}
