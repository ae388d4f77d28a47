// boneless-cli map suggest as a user runs it: a partial map in, a completed map out, and --check
// measuring the proposals against a map known to be right.
#include <gtest/gtest.h>

#include <cctype>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <set>
#include <sstream>

#include "CliRunner.h"

using namespace boneless::testing;
namespace fs = std::filesystem;

namespace {

// The demo in `dir` and `dir`/partial.json, its map cut to six picks as an animator clicks them
// first; the demo map's marker count.
int demoWithSixPicks(const fs::path& dir) {
    EXPECT_EQ(runCli("demo --out " + dir.string() + " --frame-count 20").exitCode, 0);
    nlohmann::json map;
    std::ifstream(dir / "walker.map.json") >> map;
    nlohmann::json picks = nlohmann::json::array();
    for (const auto& m : map["markers"])
        for (const char* label : {"LFHD", "LASI", "LWRA", "RWRA", "LANK", "RANK"})
            if (m["label"] == label) picks.push_back(m);
    EXPECT_EQ(picks.size(), 6u);
    const int total = static_cast<int>(map["markers"].size());
    map["markers"] = picks;
    std::ofstream(dir / "partial.json") << map.dump();
    return total;
}

}  // namespace

TEST(MapSuggestCommand, CompletesAPartialMapAndChecksItAgainstTheTrueOne) {
    const fs::path dir = freshTestDir("map-suggest");
    const int total = demoWithSixPicks(dir);

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

// --check matched entries by their labels' text: a right reference written with the take's
// full labels ("walker:C7") or in other case compared nothing, and printed "0 of 0 within 30 mm,
// median 0.0 mm" with exit 0. Labels name the take's points as solve resolves them; a reference
// that names none of the proposals is an error, naming it.
TEST(MapSuggestCommand, CheckMatchesLabelsAsTheTakeNamesThemAndSaysWhenItComparedNothing) {
    const fs::path dir = freshTestDir("map-suggest-check-labels");
    const int total = demoWithSixPicks(dir);
    nlohmann::json reference, none;
    std::ifstream(dir / "walker.map.json") >> reference;
    none = reference;
    for (auto& m : reference["markers"]) {
        std::string label = "walker:" + m["label"].get<std::string>();
        for (char& c : label) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
        m["label"] = label;
    }
    for (auto& m : none["markers"]) m["label"] = "X" + m["label"].get<std::string>();
    std::ofstream(dir / "prefixed.json") << reference.dump();
    std::ofstream(dir / "none.json") << none.dump();
    const std::string command = "map suggest --mesh " + (dir / "walker.obj").string() + " --c3d " +
                                (dir / "walker.c3d").string() + " --map " +
                                (dir / "partial.json").string() + " --force --out " +
                                (dir / "full.json").string() + " --check ";
    const CliResult r = runCli(command + (dir / "prefixed.json").string());
    ASSERT_EQ(r.exitCode, 0) << r.out;
    const std::string counted = std::to_string(total - 6) + " of " + std::to_string(total - 6);
    EXPECT_NE(r.out.find(counted + " within 30 mm, median 0.0 mm"), std::string::npos) << r.out;
    const CliResult n = runCli(command + (dir / "none.json").string());
    EXPECT_EQ(n.exitCode, 1) << n.out;
    EXPECT_NE(n.out.find((dir / "none.json").string() + ": names none of the " +
                         std::to_string(total - 6) + " suggested markers"),
              std::string::npos)
        << n.out;
    EXPECT_EQ(n.out.find("0 of 0"), std::string::npos) << n.out;
}

TEST(MapSuggestCommand, MistakesNameTheFileAndTheReason) {
    const fs::path dir = freshTestDir("map-suggest-mistakes");
    ASSERT_EQ(runCli("demo --out " + dir.string() + " --frame-count 5").exitCode, 0);
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

namespace {

// `map suggest` on a fresh demo, completing its own map (the command line without --check).
std::string suggestOnDemo(const fs::path& dir) {
    EXPECT_EQ(runCli("demo --out " + dir.string() + " --frame-count 5").exitCode, 0);
    return "map suggest --mesh " + (dir / "walker.obj").string() + " --c3d " +
           (dir / "walker.c3d").string() + " --map " + (dir / "walker.map.json").string() +
           " --out " + (dir / "full.json").string();
}

}  // namespace

// --check's map is read before the completed map is written: a run that fails leaves nothing.
TEST(MapSuggestCommand, AMapMadeOnAGroupNamesTheMeshFileAndTheFlagToOpenItWith) {
    const fs::path dir = freshTestDir("map-suggest-group");
    ASSERT_EQ(runCli("demo --out " + dir.string() + " --frame-count 3").exitCode, 0);
    std::ostringstream obj;
    obj << std::ifstream(dir / "walker.obj").rdbuf();
    std::ofstream(dir / "walker.obj")
        << "g body\n"
        << obj.str() << "g helper\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf -3 -2 -1\n";
    nlohmann::json map;
    std::ifstream(dir / "walker.map.json") >> map;
    map["mesh"]["group"] = "body";
    std::ofstream(dir / "walker.map.json") << map.dump();
    const CliResult r =
        runCli("map suggest --mesh " + (dir / "walker.obj").string() + " --c3d " +
               (dir / "walker.c3d").string() + " --map " + (dir / "walker.map.json").string() +
               " --out " + (dir / "full.json").string());
    EXPECT_EQ(r.exitCode, 1) << r.out;
    EXPECT_NE(
        r.out.find("but " + (dir / "walker.obj").string() + " has 3429; open it with --group body"),
        std::string::npos)
        << r.out;
}

// A map made on a group of another file names that group as the way out, but only when the mesh
// has such a group: the koala (no groups) was told "open it with --group body", which then failed.
TEST(MapSuggestCommand, AMapOfAGroupTheMeshLacksGetsNoGroupHint) {
    const fs::path dir = freshTestDir("map-suggest-no-group");
    ASSERT_EQ(runCli("demo --out " + dir.string() + " --frame-count 3").exitCode, 0);
    nlohmann::json map;
    std::ifstream(dir / "walker.map.json") >> map;
    map["mesh"]["group"] = "body";
    map["mesh"]["vertices"] = 13380;
    std::ofstream(dir / "body.map.json") << map.dump();
    const CliResult r =
        runCli("map suggest --mesh " + (dir / "walker.obj").string() + " --c3d " +
               (dir / "walker.c3d").string() + " --map " + (dir / "body.map.json").string() +
               " --out " + (dir / "full.json").string());
    EXPECT_EQ(r.exitCode, 1) << r.out;
    EXPECT_NE(r.out.find("with 13380 vertices"), std::string::npos) << r.out;
    EXPECT_EQ(r.out.find("--group"), std::string::npos) << r.out;
}

// --check compared the vertex numbers of a reference made for another mesh, which name other
// places (or none: those were dropped), and printed a score that meant nothing.
TEST(MapSuggestCommand, ACheckMapMadeForAnotherMeshIsRefusedBeforeTheMapIsWritten) {
    const fs::path dir = freshTestDir("map-suggest-check-other");
    const std::string command = suggestOnDemo(dir);
    nlohmann::json map;
    std::ifstream(dir / "walker.map.json") >> map;
    map["mesh"]["vertices"] = 13380;
    std::ofstream(dir / "other.json") << map.dump();
    const CliResult r = runCli(command + " --check " + (dir / "other.json").string());
    EXPECT_EQ(r.exitCode, 1) << r.out;
    EXPECT_NE(r.out.find("other.json"), std::string::npos) << r.out;
    EXPECT_NE(r.out.find("13380 vertices"), std::string::npos) << r.out;
    EXPECT_EQ(r.out.find("within 30 mm"), std::string::npos) << r.out;
    EXPECT_FALSE(fs::exists(dir / "full.json"));
}

// --tolerance-mm says how near counts for --check; without it, it was taken and did nothing.
TEST(MapSuggestCommand, AToleranceWithoutACheckIsRefused) {
    const fs::path dir = freshTestDir("map-suggest-tolerance");
    const CliResult r = runCli(suggestOnDemo(dir) + " --tolerance-mm 5");
    EXPECT_NE(r.exitCode, 0) << r.out;
    EXPECT_NE(r.out.find("--tolerance-mm requires --check"), std::string::npos) << r.out;
    EXPECT_FALSE(fs::exists(dir / "full.json"));
}

TEST(MapSuggestCommand, AMissingCheckMapFailsBeforeTheMapIsWritten) {
    const fs::path dir = freshTestDir("map-suggest-check");
    const CliResult r = runCli(suggestOnDemo(dir) + " --check " + (dir / "nosuch.json").string());
    EXPECT_EQ(r.exitCode, 1) << r.out;
    EXPECT_NE(r.out.find("nosuch.json: cannot open the correspondence file"), std::string::npos)
        << r.out;
    EXPECT_FALSE(fs::exists(dir / "full.json"));
}

// `--out take.c3d` replaced the take with the map, and `--out ref.json --check ref.json` the map it
// was to be checked against. An output that is an input, however it is spelled (a symbolic or hard
// link), is refused before anything is read, naming both, and the input is left as it was.
TEST(MapSuggestCommand, AnOutputThatWouldReplaceAnInputIsRefusedBeforeAnyWorkNamingBoth) {
    const fs::path dir = freshTestDir("map-suggest-over-input");
    ASSERT_EQ(runCli("demo --out " + dir.string() + " --frame-count 3").exitCode, 0);
    const fs::path mesh = dir / "walker.obj", take = dir / "walker.c3d",
                   map = dir / "walker.map.json", ref = dir / "ref.json";
    fs::copy_file(map, ref);
    fs::create_symlink(take, dir / "link.json");
    fs::create_hard_link(ref, dir / "hard.json");
    auto contents = [](const fs::path& file) {
        std::ostringstream s;
        s << std::ifstream(file, std::ios::binary).rdbuf();
        return s.str();
    };
    const std::string before[] = {contents(mesh), contents(take), contents(map), contents(ref)};
    const std::string args = "map suggest --mesh " + mesh.string() + " --c3d " + take.string() +
                             " --map " + map.string() + " --check " + ref.string() + " --out ";
    const std::pair<fs::path, std::string> cases[] = {
        {take, "take " + take.string()},
        {mesh, "mesh " + mesh.string()},
        {map, "map " + map.string()},
        {ref, "reference map " + ref.string()},
        {dir / "link.json", "take " + take.string()},
        {dir / "hard.json", "reference map " + ref.string()}};
    for (const auto& [out, input] : cases) {
        const CliResult r = runCli(args + out.string());
        EXPECT_EQ(r.exitCode, 1) << r.out;
        EXPECT_EQ(r.out, "boneless-cli: " + out.string() +
                             ": the completed map would replace the " + input +
                             "; give --out another file\n");
    }
    EXPECT_TRUE(contents(mesh) == before[0] && contents(take) == before[1] &&
                contents(map) == before[2] && contents(ref) == before[3])
        << "an input was replaced";
    // Before any work: a take that cannot be read is not what the refusal waits on.
    const CliResult r =
        runCli("map suggest --mesh " + mesh.string() + " --c3d " + (dir / "absent.c3d").string() +
               " --map " + map.string() + " --out " + map.string());
    EXPECT_NE(r.out.find(map.string() + ": the completed map would replace the map"),
              std::string::npos)
        << r.out;
}

// An --out in a folder that does not exist failed only once the fit was done (a minute on a large
// mesh); it is refused before anything is read, as an output over an input is.
TEST(MapSuggestCommand, AnOutputThatCannotBeWrittenIsRefusedBeforeAnyWork) {
    const fs::path dir = freshTestDir("map-suggest-unwritable");
    ASSERT_EQ(runCli("demo --out " + dir.string() + " --frame-count 3").exitCode, 0);
    const fs::path out = dir / "no-such-folder" / "full.json";
    const CliResult r = runCli("map suggest --mesh " + (dir / "walker.obj").string() + " --c3d " +
                               (dir / "absent.c3d").string() + " --map " +
                               (dir / "walker.map.json").string() + " --out " + out.string());
    EXPECT_EQ(r.exitCode, 1) << r.out;
    EXPECT_EQ(r.out, "boneless-cli: " + out.string() +
                         ": cannot be written (No such file or directory)\n");
}

// Before, a NaN tolerance printed "0 of 33 within nan mm".
TEST(MapSuggestCommand, AToleranceThatIsNoSensibleDistanceIsRefusedNamingTheFlag) {
    const fs::path dir = freshTestDir("map-suggest-tolerance");
    const std::string args =
        suggestOnDemo(dir) + " --check " + (dir / "walker.map.json").string() + " --tolerance-mm ";
    for (const char* tolerance : {"nan", "inf", "0", "1001"}) {
        const CliResult r = runCli(args + tolerance);
        EXPECT_NE(r.exitCode, 0) << tolerance;
        EXPECT_NE(r.out.find("--tolerance-mm: must be a number from 0.1 to 1000, got " +
                             std::string(tolerance)),
                  std::string::npos)
            << r.out;
    }
    EXPECT_EQ(runCli(args + "1000").exitCode, 0);
}

// The box of ezc3d's Vicon.c3d (boite:*) was given body vertices 429 to 706 mm from the fitted
// mesh, flagged for review only, and a solve then pulled the head to the box. It is a subject of
// its own, which none of the picks names.
TEST(MapSuggestCommand, LeavesUnmappedAndNamesThePropsMarkers) {
    const fs::path data = BONELESS_SHARED_DATA;
    const fs::path mesh = data / "meshes" / "makehuman" / "makehuman_base.obj";
    const fs::path take = data / "c3d" / "ezc3d" / "Vicon.c3d";
    if (!fs::exists(mesh) || !fs::exists(take)) GTEST_SKIP() << "no " << data;
    const fs::path dir = freshTestDir("map-suggest-prop");
    nlohmann::json map = {{"format", "boneless-correspondence"},
                          {"version", 1},
                          {"mesh", {{"file", "makehuman_base.obj"}, {"group", "body"}}},
                          {"markers", nlohmann::json::array()}};
    for (const auto& [label, vertex] : {std::pair{"ASISr", 4327},
                                        {"ASISl", 10955},
                                        {"PSISr", 4200},
                                        {"PSISl", 10838},
                                        {"STER", 1893},
                                        {"T1", 1492}})
        map["markers"].push_back({{"label", label}, {"vertex", vertex}, {"offset_mm", 10}});
    std::ofstream(dir / "partial.json") << map.dump();
    const CliResult r = runCli("map suggest --mesh " + mesh.string() + " --group body --c3d " +
                               take.string() + " --map " + (dir / "partial.json").string() +
                               " --out " + (dir / "full.json").string());
    ASSERT_EQ(r.exitCode, 0) << r.out;
    const std::string line = "left unmapped, worn by a subject no mapped marker names: ";
    const size_t at = r.out.find(line);
    ASSERT_NE(at, std::string::npos) << r.out;
    const size_t from = at + line.size();
    const std::string listed = r.out.substr(from, r.out.find('\n', from) - from);
    const std::set<std::string> box{"gauche_ext",    "gauche_int",    "droite_int",
                                    "droite_ext",    "avant_gauche",  "avant_droit",
                                    "arriere_droit", "arriere_gauche"};
    for (const std::string& name : box)
        EXPECT_NE(listed.find("boite:" + name), std::string::npos) << listed;
    nlohmann::json full;
    std::ifstream(dir / "full.json") >> full;
    for (const auto& m : full["markers"]) EXPECT_EQ(box.count(m["label"]), 0u) << m;
    EXPECT_EQ(full["markers"].size(), 43u);  // 51 points, the 8 of the box left out
}

// A map of the box's markers alone left nothing to suggest, and the command printed "aligned at
// frame -1 (0 markers visible), RMS residual 0 mesh units, scale 1, fitted best at frame -1".
TEST(MapSuggestCommand, AMapOfThePropsMarkersAloneSaysPlainlyThatNothingIsSuggestedAndWhy) {
    const fs::path data = BONELESS_SHARED_DATA;
    const fs::path mesh = data / "meshes" / "makehuman" / "makehuman_base.obj";
    const fs::path take = data / "c3d" / "ezc3d" / "Vicon.c3d";
    if (!fs::exists(mesh) || !fs::exists(take)) GTEST_SKIP() << "no " << data;
    const fs::path dir = freshTestDir("map-suggest-prop-only");
    nlohmann::json map = {{"format", "boneless-correspondence"},
                          {"version", 1},
                          {"mesh", {{"file", "makehuman_base.obj"}, {"group", "body"}}},
                          {"markers", nlohmann::json::array()}};
    int vertex = 100;
    for (const char* name : {"gauche_ext", "gauche_int", "droite_int", "droite_ext", "avant_gauche",
                             "avant_droit", "arriere_droit", "arriere_gauche"})
        map["markers"].push_back({{"label", std::string("boite:") + name},
                                  {"vertex", vertex += 100},
                                  {"offset_mm", 10}});
    std::ofstream(dir / "partial.json") << map.dump();
    const CliResult r = runCli("map suggest --mesh " + mesh.string() + " --group body --c3d " +
                               take.string() + " --map " + (dir / "partial.json").string() +
                               " --out " + (dir / "full.json").string());
    ASSERT_EQ(r.exitCode, 0) << r.out;
    EXPECT_NE(r.out.find((dir / "full.json").string() +
                         ": 8 markers, nothing to suggest: every marker of the mapped markers' "
                         "subject is mapped, and the take's others are worn by another subject"),
              std::string::npos)
        << r.out;
    EXPECT_NE(r.out.find("left unmapped, worn by a subject no mapped marker names: "),
              std::string::npos)
        << r.out;
    EXPECT_EQ(r.out.find("frame -1"), std::string::npos) << r.out;
}

// Every other figure the command prints is in millimetres; the residual was in mesh units.
TEST(MapSuggestCommand, GivesTheAlignmentResidualInMillimetres) {
    const fs::path dir = freshTestDir("map-suggest-residual");
    ASSERT_EQ(runCli("demo --out " + dir.string() + " --frame-count 5").exitCode, 0);
    nlohmann::json map;
    std::ifstream(dir / "walker.map.json") >> map;
    map["markers"] = nlohmann::json::array(
        {map["markers"][0], map["markers"][5], map["markers"][10], map["markers"][20]});
    std::ofstream(dir / "partial.json") << map.dump();
    const CliResult r =
        runCli("map suggest --mesh " + (dir / "walker.obj").string() + " --c3d " +
               (dir / "walker.c3d").string() + " --map " + (dir / "partial.json").string() +
               " --out " + (dir / "full.json").string());
    ASSERT_EQ(r.exitCode, 0) << r.out;
    EXPECT_NE(r.out.find(" mm, scale "), std::string::npos) << r.out;
    EXPECT_EQ(r.out.find("mesh units"), std::string::npos) << r.out;
}

// "map suggest --out MAP.json" replaced an existing MAP.json without a word: a map reviewed by
// hand, given by mistake, was lost. As demo keeps an edited map, it is kept unless --force, naming
// it; the same map again is written, and a file that is no map is refused before the fit.
TEST(MapSuggestCommand, AnExistingOutThatDiffersIsKeptUnlessForced) {
    const fs::path dir = freshTestDir("map-suggest-keep");
    ASSERT_EQ(runCli("demo --out " + dir.string() + " --frame-count 5").exitCode, 0);
    nlohmann::json map;
    std::ifstream(dir / "walker.map.json") >> map;
    map["markers"] = nlohmann::json::array(
        {map["markers"][0], map["markers"][5], map["markers"][12], map["markers"][20]});
    std::ofstream(dir / "partial.json") << map.dump();
    const fs::path out = dir / "full.json";
    const std::string suggest = "map suggest --mesh " + (dir / "walker.obj").string() + " --c3d " +
                                (dir / "walker.c3d").string() + " --map " +
                                (dir / "partial.json").string() + " --out " + out.string();
    ASSERT_EQ(runCli(suggest).exitCode, 0);
    CliResult r = runCli(suggest);
    EXPECT_EQ(r.exitCode, 0) << "the same map again: " << r.out;
    nlohmann::json reviewed;
    std::ifstream(out) >> reviewed;
    reviewed["markers"][7]["vertex"] = reviewed["markers"][7]["vertex"].get<int>() + 1;
    reviewed["markers"][7].erase("suggested");
    const std::string edited = reviewed.dump(2);
    std::ofstream(out) << edited;
    r = runCli(suggest);
    EXPECT_EQ(r.exitCode, 1) << r.out;
    EXPECT_NE(r.out.find(out.string() +
                         ": differs from the map this run suggests (reviewed by hand, or suggested "
                         "from other inputs); nothing was written: give --force to replace it, or "
                         "another --out\n"),
              std::string::npos)
        << r.out;
    std::ostringstream kept;
    kept << std::ifstream(out).rdbuf();
    EXPECT_EQ(kept.str(), edited);
    r = runCli(suggest + " --force");
    EXPECT_EQ(r.exitCode, 0) << r.out;
    std::ostringstream replaced;
    replaced << std::ifstream(out).rdbuf();
    EXPECT_NE(replaced.str(), edited);
    // No map at all: refused before the fit, which prints the map's line.
    const fs::path notes = dir / "notes.txt";
    std::ofstream(notes) << "review LKNE\n";
    r = runCli(suggest.substr(0, suggest.find(" --out ")) + " --out " + notes.string());
    EXPECT_EQ(r.exitCode, 1) << r.out;
    EXPECT_NE(r.out.find(notes.string() + ": differs from the map this run suggests"),
              std::string::npos)
        << r.out;
    EXPECT_EQ(r.out.find("markers ("), std::string::npos) << r.out;
}

// solve took --mesh-up and map suggest refused it ("The following arguments were not expected"),
// though the suggestions are made on fits solved as solve solves them.
TEST(MapSuggestCommand, TakesTheMeshsUpAxisAsSolveDoesAndRefusesOneSolveRefuses) {
    const fs::path dir = freshTestDir("map-suggest-up");
    demoWithSixPicks(dir);
    const std::string args = "map suggest --mesh " + (dir / "walker.obj").string() + " --c3d " +
                             (dir / "walker.c3d").string() + " --map " +
                             (dir / "partial.json").string() + " --check " +
                             (dir / "walker.map.json").string() + " --out ";
    const CliResult up = runCli(args + (dir / "up.json").string() + " --mesh-up +y");
    ASSERT_EQ(up.exitCode, 0) << up.out;
    EXPECT_NE(up.out.find("0 to review"), std::string::npos) << up.out;

    const CliResult bad = runCli(args + (dir / "bad.json").string() + " --mesh-up up");
    const CliResult solve =
        runCli("solve --mesh " + (dir / "walker.obj").string() + " --c3d " +
               (dir / "walker.c3d").string() + " --map " + (dir / "walker.map.json").string() +
               " --out " + (dir / "solved").string() + " --mesh-up up");
    EXPECT_EQ(bad.exitCode, solve.exitCode);
    ASSERT_NE(solve.out.find("--mesh-up"), std::string::npos) << solve.out;
    EXPECT_EQ(bad.out.substr(0, bad.out.find('\n')), solve.out.substr(0, solve.out.find('\n')));
    EXPECT_FALSE(fs::exists(dir / "bad.json"));
}

// The map records the mesh it was suggested on, not the one the partial map names: it kept
// "walker.obj" for a run on a re-exported copy, and every solve of it then said the map was made on
// another file.
TEST(MapSuggestCommand, TheMapWrittenNamesTheMeshItWasSuggestedOn) {
    const fs::path dir = freshTestDir("map-suggest-mesh-name");
    demoWithSixPicks(dir);
    fs::copy_file(dir / "walker.obj", dir / "re-exported.obj");
    nlohmann::json partial;
    std::ifstream(dir / "partial.json") >> partial;
    partial["mesh"]["group"] = "Walker";  // as a map made on another file's group says
    std::ofstream(dir / "partial.json") << partial.dump();
    const CliResult r =
        runCli("map suggest --mesh " + (dir / "re-exported.obj").string() + " --c3d " +
               (dir / "walker.c3d").string() + " --map " + (dir / "partial.json").string() +
               " --out " + (dir / "full.json").string());
    ASSERT_EQ(r.exitCode, 0) << r.out;
    nlohmann::json full;
    std::ifstream(dir / "full.json") >> full;
    EXPECT_EQ(full["mesh"]["file"], "re-exported.obj");
    EXPECT_EQ(full["mesh"].value("group", ""), "");
    EXPECT_EQ(full["mesh"]["vertices"], 3426);  // the demo walker's
}
