#include <fcntl.h>
#include <gtest/gtest.h>
#include <sys/file.h>
#include <tiny_gltf.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <regex>
#include <sstream>

#include "CliRunner.h"
#include "TestFiles.h"
#include "TwoActorTake.h"
#include "boneless/C3dReader.h"
#include "boneless/C3dWriter.h"
#include "boneless/MeshReader.h"
#include "boneless/Metrics.h"
#include "boneless/PointCacheWriter.h"
#include "boneless/Text.h"

using namespace boneless;
using namespace boneless::testing;
namespace fs = std::filesystem;

namespace {

fs::path makeDemo(int frames, double offsetMm = 10) {
    const fs::path dir = freshTestDir("demo");
    const CliResult r = runCli("demo --out " + dir.string() + " --frame-count " +
                               std::to_string(frames) + " --offset-mm " + std::to_string(offsetMm));
    EXPECT_EQ(r.exitCode, 0) << r.out;
    return dir;
}

std::string solveArgs(const fs::path& demo, const fs::path& out) {
    return "solve --mesh " + (demo / "walker.obj").string() + " --c3d " +
           (demo / "walker.c3d").string() + " --map " + (demo / "walker.map.json").string() +
           " --out " + out.string();
}

nlohmann::json sidecar(const fs::path& out) {
    return nlohmann::json::parse(std::ifstream(out / "walker.json"));
}

}  // namespace

struct TruthComparison {
    double worstRmsPct = 0;
    int worstFlipped = 0;
};

TruthComparison compareWithTruth(const fs::path& demo, const fs::path& out, int frames) {
    TruthComparison c;
    const TriMesh rest = readMesh((demo / "walker.obj").string()).mesh;
    const double diagonal = boundingBoxDiagonal(rest.V);
    for (int f = 0; f < frames; ++f) {
        char name[32];
        std::snprintf(name, sizeof name, "walker_%04d.obj", f);
        const TriMesh solved = readMesh((out / name).string()).mesh;
        const TriMesh truth = readMesh((demo / "truth" / name).string()).mesh;
        EXPECT_EQ(solved.F, rest.F);  // same faces, same vertex order
        EXPECT_TRUE(solved.V.allFinite());
        c.worstRmsPct = std::max(c.worstRmsPct, 100 * rmsVertexError(solved.V, truth.V) / diagonal);
        c.worstFlipped = std::max(c.worstFlipped, flippedFaceCount(rest.F, solved.V, truth.V));
    }
    return c;
}

TEST(SolveCommand, TheDemoTakeComesBackCloseToItsTruth) {
    const fs::path demo = makeDemo(30), out = demo / "solved";
    const CliResult r = runCli(solveArgs(demo, out) + " --quiet");
    ASSERT_EQ(r.exitCode, 0) << r.out;
    // Measured over these 30 frames of the walker, 39 markers 10 mm off the skin, occlusion gaps:
    // 0.384 % of the diagonal at worst, no flipped face.
    const TruthComparison c = compareWithTruth(demo, out, 30);
    std::printf("worst RMS %.3f %%, worst flipped %d\n", c.worstRmsPct, c.worstFlipped);
    EXPECT_LT(c.worstRmsPct, 0.45);
    EXPECT_LE(c.worstFlipped, 1);
    const auto j = sidecar(out);
    EXPECT_EQ(j["frames_written"], 30);
    EXPECT_NEAR(j["alignment"]["scale"].get<double>(), 0.001, 1e-6);  // metres vs millimetres
    EXPECT_EQ(j["units"]["mesh_guess"], "m");
    EXPECT_EQ(j["up_axis"]["mesh_guess"], "+z");
    EXPECT_EQ(j["per_frame"][18]["visible_markers"], 38);  // LWRB is occluded there
    EXPECT_EQ(j["options"]["solver"], "local-global");
    for (const auto& f : j["per_frame"]) EXPECT_LT(f["residual_rms_mm"].get<double>(), 1.0);
    // No dent around any marker: the curvature there stays within twice the rest's (measured
    // over these 30 frames: 1.81 at worst, at the front of the hip, where the walk creases the
    // body; 2.01 over the 60-frame demo), and the summary gives the worst frame's.
    double dentWorst = 0;
    for (const auto& f : j["per_frame"]) {
        EXPECT_GE(f["dent_ratio"].get<double>(), 0.5);
        dentWorst = std::max(dentWorst, f["dent_ratio"].get<double>());
    }
    EXPECT_LE(dentWorst, 2.0);
    EXPECT_EQ(j["summary"]["dent_ratio_worst_frame"].get<double>(), dentWorst);
}

TEST(SolveCommand, MarkersOnTheSkinMatchTheGroundTruthEvaluation) {
    // With no offset the take route (alignment, soft constraints, gaps) should do
    // what eval does with exact markers: measured 0.369 % worst on the walker.
    const fs::path demo = makeDemo(30, 0.0), out = demo / "solved";
    ASSERT_EQ(runCli(solveArgs(demo, out) + " --quiet").exitCode, 0);
    const TruthComparison c = compareWithTruth(demo, out, 30);
    std::printf("on the skin: worst RMS %.3f %%, worst flipped %d\n", c.worstRmsPct,
                c.worstFlipped);
    EXPECT_LT(c.worstRmsPct, 0.42);
    EXPECT_EQ(c.worstFlipped, 0);
}

TEST(SolveCommand, ObjAndPointCacheHoldTheSamePositions) {
    const fs::path demo = makeDemo(8);
    ASSERT_EQ(runCli(solveArgs(demo, demo / "obj") + " --quiet --frames 2:6").exitCode, 0);
    const CliResult r =
        runCli(solveArgs(demo, demo / "pc2") + " --quiet --frames 2:6 --format pc2");
    ASSERT_EQ(r.exitCode, 0) << r.out;
    double start = -1;
    const auto frames = readPointCache((demo / "pc2" / "walker.pc2").string(), &start);
    ASSERT_EQ(frames.size(), 4u);
    EXPECT_EQ(start, 2.0);
    for (int f = 2; f < 6; ++f) {
        char name[32];
        std::snprintf(name, sizeof name, "walker_%04d.obj", f);
        const TriMesh obj = readMesh((demo / "obj" / name).string()).mesh;
        EXPECT_LT((obj.V - frames[f - 2]).cwiseAbs().maxCoeff(), 1e-5);  // PC2 stores float32
    }
    EXPECT_FALSE(fs::exists(demo / "obj" / "walker_0001.obj"));
    EXPECT_FALSE(fs::exists(demo / "obj" / "walker_0006.obj"));
}

TEST(SolveCommand, ObjFramesKeepTheInputsTextureCoordinatesAndMaterials) {
    const fs::path demo = makeDemo(3);
    // The demo walker as an artist's file: a texture coordinate per corner and a material.
    addTextureCoordinatesAndMaterial((demo / "walker.obj").string(), "walker.mtl", "skin");
    std::ofstream(demo / "walker.mtl") << "newmtl skin\nKd 0.8 0.6 0.5\n";
    const TriMesh input = readMesh((demo / "walker.obj").string()).mesh;
    ASSERT_NE(input.sourceFaces, nullptr);

    const fs::path out = demo / "solved";
    const CliResult r =
        runCli(solveArgs(demo, out) + " --quiet --frames 1:2 --write-calibrated-rest");
    ASSERT_EQ(r.exitCode, 0) << r.out;
    for (const char* name : {"walker_0001.obj", "walker_calibrated_rest.obj"}) {
        const TriMesh frame = readMesh((out / name).string()).mesh;
        ASSERT_NE(frame.sourceFaces, nullptr) << name;
        EXPECT_EQ(frame.sourceFaces->corners, input.sourceFaces->corners) << name;
        EXPECT_EQ(frame.sourceFaces->uvOf, input.sourceFaces->uvOf) << name;
        EXPECT_EQ(frame.sourceFaces->uv, input.sourceFaces->uv) << name;
        EXPECT_EQ(frame.sourceFaces->materials, input.sourceFaces->materials) << name;
        ASSERT_EQ(frame.sourceFaces->materialDefinitions.size(),
                  input.sourceFaces->materialDefinitions.size());
        for (size_t d = 0; d < input.sourceFaces->materialDefinitions.size(); ++d)
            EXPECT_EQ(frame.sourceFaces->materialDefinitions[d].name,
                      input.sourceFaces->materialDefinitions[d].name);
        ASSERT_EQ(frame.sourceFaces->materialLibraries.size(), 1u);  // ../walker.mtl, found
        EXPECT_EQ(fs::path(frame.sourceFaces->materialLibraries[0]),
                  fs::absolute(demo / "walker.mtl"));
    }
}

TEST(SolveCommand, SaysWhatTheMeshsMaterialLibraryLacksAndSolvesAnyway) {
    const fs::path demo = makeDemo(3);
    addTextureCoordinatesAndMaterial((demo / "walker.obj").string(), "walker.mtl", "skin");
    std::ofstream(demo / "walker.mtl") << "newmtl skin\nmap_Kd textures/skin.png\n";
    const fs::path out = demo / "solved";
    const CliResult r = runCli(solveArgs(demo, out) + " --frames 1:2 --format glb");
    ASSERT_EQ(r.exitCode, 0) << r.out;
    EXPECT_NE(r.out.find("note: " + (demo / "walker.obj").string() + ": " +
                         (demo / "walker.mtl").string() + " line 2: texture " +
                         (demo / "textures" / "skin.png").string() + " not found"),
              std::string::npos)
        << r.out;
    EXPECT_TRUE(fs::exists(out / "walker.glb"));
    EXPECT_EQ(runCli(solveArgs(demo, demo / "quiet") + " --frames 1:2 --quiet").out, "");
}

TEST(SolveCommandSignals, CtrlCStopsCleanlyWithCompleteFilesOnly) {
    // Long enough (a few seconds) to be stopped halfway by a SIGINT once the first frame is out.
    const fs::path demo = makeDemo(3000), out = demo / "solved";
    const CliResult r = runCliAndWhenExists(solveArgs(demo, out) + " --quiet",
                                            (out / "walker_0000.obj").string(), "kill -INT $pid");
    EXPECT_EQ(r.exitCode, 130) << r.out;  // 128 + SIGINT, as shells say
    const auto j = sidecar(out);
    // Not "complete", which the sidecar denies.
    EXPECT_NE(r.out.find("interrupted after " + plural(j["frames_written"].get<int>(), "frame") +
                         ": walker.json records the take as incomplete"),
              std::string::npos)
        << r.out;
    EXPECT_FALSE(j["complete"].get<bool>());
    int objs = 0;
    for (const auto& e : fs::directory_iterator(out)) {
        EXPECT_EQ(e.path().string().find(".tmp"), std::string::npos) << e.path();
        if (e.path().extension() == ".obj") ++objs;
    }
    EXPECT_EQ(objs, j["frames_written"].get<int>());
    EXPECT_LT(objs, 3000);
}

// A hand-made map kept beside the mesh as walker.json, and the same folder given as the output:
// the sidecar replaced the map. Refused before solving, in batch entry by entry.
TEST(SolveCommand, AnOutputThatWouldReplaceAnInputIsRefusedBeforeSolvingNamingBoth) {
    const fs::path demo = makeDemo(4);
    fs::rename(demo / "walker.map.json", demo / "walker.json");
    std::ostringstream before;
    before << std::ifstream(demo / "walker.json").rdbuf();
    const std::string args = "solve --mesh " + (demo / "walker.obj").string() + " --c3d " +
                             (demo / "walker.c3d").string() + " --map " +
                             (demo / "walker.json").string() + " --format pc2 --quiet";
    const CliResult r = runCli(args + " --out " + demo.string());
    EXPECT_EQ(r.exitCode, 1) << r.out;
    EXPECT_NE(r.out.find((demo / "walker.json").string() +
                         ": the sidecar this solve writes would replace the map " +
                         (demo / "walker.json").string()),
              std::string::npos)
        << r.out;
    std::ostringstream after;
    after << std::ifstream(demo / "walker.json").rdbuf();
    EXPECT_TRUE(after.str() == before.str()) << "the map was replaced";
    EXPECT_FALSE(fs::exists(demo / "walker.pc2"));
    // The same folder spelled another way is the same file.
    EXPECT_EQ(runCli(args + " --out " + (demo / "truth" / "..").string()).exitCode, 1);

    std::ofstream(demo / "m.json") << nlohmann::json{
        {"defaults", {{"mesh", "walker.obj"}, {"c3d", "walker.c3d"}, {"map", "walker.json"}}},
        {"takes", {{{"out", "."}}, {{"out", "solved"}}}}};
    const CliResult batch = runCli("batch " + (demo / "m.json").string());
    EXPECT_EQ(batch.exitCode, 1) << batch.out;
    EXPECT_NE(batch.out.find("FAILED: " + (demo / "walker.json").string() +
                             ": the sidecar this solve writes would replace the map"),
              std::string::npos)
        << batch.out;
    EXPECT_NE(batch.out.find("1 solved, 0 skipped, 1 failed"), std::string::npos) << batch.out;
    std::ostringstream afterBatch;
    afterBatch << std::ifstream(demo / "walker.json").rdbuf();
    EXPECT_TRUE(afterBatch.str() == before.str()) << "the map was replaced";
}

// A file name from a Latin-1 system ("caf\xe9.c3d") made solve, map suggest and eval die with
// "internal error: [json.exception.type_error.316] invalid UTF-8 byte", leaving no sidecar.
TEST(SolveCommand, FileNamesThatAreNotUtf8AreWrittenIntoTheJsonFilesReadAsLatin1) {
    const fs::path demo = makeDemo(3);
    const fs::path mesh = demo / "m\xe9sh.obj", take = demo / "caf\xe9.c3d";
    fs::copy_file(demo / "walker.obj", mesh);
    fs::copy_file(demo / "walker.c3d", take);
    const CliResult r = runCli("solve --mesh '" + mesh.string() + "' --c3d '" + take.string() +
                               "' --map " + (demo / "walker.map.json").string() + " --out " +
                               (demo / "out").string() + " --format glb --quiet");
    ASSERT_EQ(r.exitCode, 0) << r.out;
    EXPECT_TRUE(fs::file_size(demo / "out" / "m\xe9sh.glb") > 0);
    const auto j = nlohmann::json::parse(std::ifstream(demo / "out" / "m\xe9sh.json"));
    EXPECT_EQ(j["source"]["c3d"], (demo / "caf\u00e9.c3d").string());
    EXPECT_EQ(j["source"]["mesh"], (demo / "m\u00e9sh.obj").string());
    EXPECT_TRUE(j["complete"]);

    nlohmann::json partial = nlohmann::json::parse(std::ifstream(demo / "walker.map.json"));
    partial["markers"] =
        std::vector<nlohmann::json>(partial["markers"].begin(), partial["markers"].begin() + 8);
    partial["mesh"].erase("file");  // so that suggest names the mesh it was given
    std::ofstream(demo / "partial.json") << partial.dump();
    const CliResult s =
        runCli("map suggest --mesh '" + mesh.string() + "' --c3d '" + take.string() + "' --map " +
               (demo / "partial.json").string() + " --out " + (demo / "suggested.json").string());
    ASSERT_EQ(s.exitCode, 0) << s.out;
    EXPECT_EQ(nlohmann::json::parse(std::ifstream(demo / "suggested.json"))["mesh"]["file"],
              "m\u00e9sh.obj");

    const fs::path sequence = demo / "s\xe9quence";
    fs::create_directories(sequence);
    for (const char* frame : {"walker_0000.obj", "walker_0001.obj", "walker_0002.obj"})
        fs::copy_file(demo / "truth" / frame, sequence / frame);
    const CliResult e = runCli("eval --sequence '" + sequence.string() + "' --markers 20 --json");
    ASSERT_EQ(e.exitCode, 0) << e.out;
    EXPECT_NE(e.out.find("s\u00e9quence"), std::string::npos) << e.out;
}

// What `map suggest` flagged and nobody cleared is solved, but not in silence: a proposal on a
// prop pulled the head to it, and nothing said so.
TEST(SolveCommand, WarnsOfTheEntriesStillMarkedForReviewAndSolvesAnyway) {
    const fs::path demo = makeDemo(3);
    nlohmann::json map = nlohmann::json::parse(std::ifstream(demo / "walker.map.json"));
    for (auto& m : map["markers"])
        if (m["label"] == "T10") {
            m["suggested"] = true;
            m["needs_review"] = true;
            m["review_reason"] = "62 mm from the fitted mesh";
        }
    std::ofstream(demo / "walker.map.json") << map.dump(2);
    const CliResult r = runCli(solveArgs(demo, demo / "solved") + " --quiet");
    ASSERT_EQ(r.exitCode, 0) << r.out;
    EXPECT_NE(r.out.find("warning: " + (demo / "walker.map.json").string() +
                         ": 1 suggested entry is still marked for review: T10"),
              std::string::npos)
        << r.out;
    EXPECT_TRUE(sidecar(demo / "solved")["complete"]);
}

// A map entry's subject prefix names its subject: "other:T10" is missing from a take whose only
// subject, walker, wears T10, and the refusal names the take's subjects. It bound walker:T10 in
// silence; the bare name and walker's own prefix still find it.
TEST(SolveCommand, ALabelWhosePrefixNamesNoSubjectOfTheTakeIsNotFoundAndTheSubjectsAreNamed) {
    const fs::path demo = makeDemo(3);
    const fs::path mapFile = demo / "walker.map.json";
    nlohmann::json map = nlohmann::json::parse(std::ifstream(mapFile));
    for (auto& m : map["markers"])
        if (m["label"] == "T10") m["label"] = "other:T10";
    std::ofstream(mapFile) << map.dump(2);
    const CliResult r = runCli(solveArgs(demo, demo / "solved") + " --quiet");
    EXPECT_EQ(r.exitCode, 1) << r.out;
    EXPECT_NE(
        r.out.find(mapFile.string() + ": labels not found in " + (demo / "walker.c3d").string() +
                   ": other:T10; the take's only subject is walker\n"),
        std::string::npos)
        << r.out;
    EXPECT_FALSE(fs::exists(demo / "solved" / "walker.json"));
    for (auto& m : map["markers"])
        if (m["label"] == "other:T10") m["label"] = "walker:T10";
    std::ofstream(mapFile) << map.dump(2);
    EXPECT_EQ(runCli(solveArgs(demo, demo / "solved") + " --quiet --format pc2").exitCode, 0);
}

// The walker as group 'body' of an OBJ that also holds a helper group, and its map made on 'body'.
fs::path makeGroupedDemo() {
    const fs::path demo = makeDemo(3);
    std::ostringstream obj;
    obj << std::ifstream(demo / "walker.obj").rdbuf();
    std::ofstream(demo / "walker.obj")
        << "g body\n"
        << obj.str() << "g helper\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf -3 -2 -1\n";
    nlohmann::json map = nlohmann::json::parse(std::ifstream(demo / "walker.map.json"));
    map["mesh"]["file"] = "walker.obj";
    map["mesh"]["group"] = "body";
    std::ofstream(demo / "walker.map.json") << map.dump(2);
    return demo;
}

TEST(SolveCommand, AMapMadeOnAGroupNamesTheMeshFileAndTheFlagToOpenItWith) {
    const fs::path demo = makeGroupedDemo();
    const CliResult r = runCli(solveArgs(demo, demo / "solved") + " --quiet");
    EXPECT_EQ(r.exitCode, 1) << r.out;
    EXPECT_NE(r.out.find("walker.map.json: was made for group 'body' of walker.obj with 3426 "
                         "vertices, but " +
                         (demo / "walker.obj").string() + " has 3429; open it with --group body"),
              std::string::npos)
        << r.out;
    EXPECT_EQ(r.out.find("the mesh"), std::string::npos) << r.out;
    const CliResult grouped = runCli(solveArgs(demo, demo / "solved") + " --group body --quiet");
    EXPECT_EQ(grouped.exitCode, 0) << grouped.out;
}

TEST(SolveCommand, BadInputIsOneClearLine) {
    const fs::path demo = makeDemo(3);
    std::ofstream(demo / "bad.map.json") << R"({"format": "boneless-correspondence", "version": 1,
        "markers": [{"label": "NOPE", "vertex": 1}, {"label": "LFHD", "vertex": 2}]})";
    const CliResult r =
        runCli("solve --mesh " + (demo / "walker.obj").string() + " --c3d " +
               (demo / "walker.c3d").string() + " --map " + (demo / "bad.map.json").string() +
               " --out " + (demo / "x").string());
    EXPECT_NE(r.exitCode, 0);
    EXPECT_NE(r.out.find("NOPE"), std::string::npos) << r.out;
    EXPECT_NE(r.out.find("bad.map.json"), std::string::npos) << r.out;
}

// A map of fewer than 3 markers cannot align the take, and the error blamed the take: "walker.c3d:
// no frame shows three or more of the mapped markers in general position".
TEST(SolveCommand, AMapOfFewerThanThreeMarkersIsRefusedNamingTheMap) {
    const fs::path demo = makeDemo(3);
    std::ofstream(demo / "empty.json")
        << R"({"format": "boneless-correspondence", "version": 1, "markers": []})";
    std::ofstream(demo / "two.json") << R"({"format": "boneless-correspondence", "version": 1,
        "markers": [{"label": "LFHD", "vertex": 1}, {"label": "RFHD", "vertex": 2}]})";
    for (const auto& [map, count] : {std::pair{"empty.json", "0"}, {"two.json", "2"}}) {
        const CliResult r = runCli("solve --mesh " + (demo / "walker.obj").string() + " --c3d " +
                                   (demo / "walker.c3d").string() + " --map " +
                                   (demo / map).string() + " --out " + (demo / "x").string());
        EXPECT_EQ(r.exitCode, 1) << r.out;
        EXPECT_NE(r.out.find((demo / map).string() + ": maps " + count +
                             " markers; solving needs at least 3"),
                  std::string::npos)
            << r.out;
        EXPECT_EQ(r.out.find("general position"), std::string::npos) << r.out;
    }
    std::ofstream(demo / "m.json") << nlohmann::json{
        {"defaults", {{"mesh", "walker.obj"}, {"c3d", "walker.c3d"}, {"map", "empty.json"}}},
        {"takes", {{{"out", "solved"}}}}};
    const CliResult batch = runCli("batch " + (demo / "m.json").string());
    EXPECT_EQ(batch.exitCode, 1) << batch.out;
    EXPECT_NE(batch.out.find("empty.json: maps 0 markers; solving needs at least 3"),
              std::string::npos)
        << batch.out;
}

TEST(SolveCommand, AFrameRangeWithTrailingCharactersIsRefused) {
    const fs::path demo = makeDemo(3);
    const CliResult r =
        runCli("solve --mesh " + (demo / "walker.obj").string() + " --c3d " +
               (demo / "walker.c3d").string() + " --map " + (demo / "walker.map.json").string() +
               " --out " + (demo / "x").string() + " --frames 0:2:1");
    EXPECT_NE(r.exitCode, 0);
    EXPECT_NE(r.out.find("0:2:1"), std::string::npos) << r.out;
    EXPECT_FALSE(fs::exists(demo / "x" / "walker_0000.obj"));
}

TEST(SolveCommand, ANegativeFrameIsRefusedAsSuch) {
    const fs::path demo = makeDemo(3);
    const CliResult r = runCli(solveArgs(demo, demo / "x") + " --frames -1:2");
    EXPECT_NE(r.exitCode, 0);
    EXPECT_NE(r.out.find("not negative"), std::string::npos) << r.out;
}

TEST(SolveCommand, ACutoffAboveTheTakesRangeIsRefusedInPlainNumbers) {
    const fs::path demo = makeDemo(3);
    const CliResult r = runCli(solveArgs(demo, demo / "x") + " --low-pass-hz 1000");
    EXPECT_EQ(r.exitCode, 1) << r.out;
    EXPECT_NE(r.out.find("low-pass cutoff 1000 Hz must be below "), std::string::npos) << r.out;
    EXPECT_EQ(r.out.find("000000"), std::string::npos) << r.out;
}

TEST(SolveCommand, SaysWhenTheRangeRunsPastTheTakeOrOldFramesStayBeside) {
    const fs::path demo = makeDemo(6);
    const fs::path out = demo / "x";
    CliResult r = runCli(solveArgs(demo, out) + " --quiet --frames 2:100");
    ASSERT_EQ(r.exitCode, 0) << r.out;
    EXPECT_NE(r.out.find("runs past the end"), std::string::npos) << r.out;
    EXPECT_NE(r.out.find("solving 2:6"), std::string::npos) << r.out;
    EXPECT_EQ(sidecar(out)["frame_range"], nlohmann::json::array({2, 6}));
    // An end past int's range is past the take's too (it was refused as "expects A:B").
    r = runCli(solveArgs(demo, out) + " --quiet --frames 2:99999999999");
    ASSERT_EQ(r.exitCode, 0) << r.out;
    EXPECT_NE(r.out.find("--frames 2:99999999999 runs past the end"), std::string::npos) << r.out;
    EXPECT_EQ(sidecar(out)["frame_range"], nlohmann::json::array({2, 6}));
    // Solving fewer frames into the same folder leaves the earlier run's others: say so.
    r = runCli(solveArgs(demo, out) + " --quiet --frames 2:4");
    ASSERT_EQ(r.exitCode, 0) << r.out;
    EXPECT_NE(r.out.find("also holds 2 OBJ frames this run did not write (frames 4 to 5"),
              std::string::npos)
        << r.out;
    EXPECT_TRUE(fs::exists(out / "walker_0005.obj"));  // the user's to remove, not ours
    r = runCli(solveArgs(demo, out) + " --quiet --frames 2:6");
    EXPECT_EQ(r.out.find("also holds"), std::string::npos) << r.out;
}

// Solved as OBJ, then glb, then pc2 into one folder, the folder held all three beside one sidecar
// that described the last alone, and nothing said so.
TEST(SolveCommand, AnEarlierExportOfAnotherFormatLeftBesideIsNamed) {
    const fs::path demo = makeDemo(3);
    const fs::path out = demo / "x";
    ASSERT_EQ(runCli(solveArgs(demo, out) + " --quiet --write-calibrated-rest").exitCode, 0);
    CliResult r = runCli(solveArgs(demo, out) + " --quiet --format glb");
    ASSERT_EQ(r.exitCode, 0) << r.out;
    EXPECT_NE(r.out.find("also holds an earlier export's walker_calibrated_rest.obj and 3 OBJ "
                         "frames (walker_*.obj), which walker.json no longer describes; remove "
                         "them"),
              std::string::npos)
        << r.out;
    r = runCli(solveArgs(demo, out) + " --quiet --format pc2");
    EXPECT_NE(
        r.out.find("earlier export's walker_calibrated_rest.obj, walker.glb and 3 OBJ frames"),
        std::string::npos)
        << r.out;
    for (const char* name : {"walker.glb", "walker_calibrated_rest.obj", "walker_0002.obj"})
        EXPECT_TRUE(fs::exists(out / name)) << name;  // the user's to remove, not ours
    r = runCli(solveArgs(demo, out) + " --quiet --format pc2 --write-calibrated-rest");
    EXPECT_NE(r.out.find("earlier export's walker.glb and 3 OBJ frames"), std::string::npos)
        << r.out;
    // The same export again names nothing.
    const fs::path alone = demo / "alone";
    ASSERT_EQ(runCli(solveArgs(demo, alone) + " --quiet --format mdd").exitCode, 0);
    r = runCli(solveArgs(demo, alone) + " --quiet --format mdd");
    EXPECT_EQ(r.out.find("earlier export"), std::string::npos) << r.out;
}

// Frames 3:6 solved into a folder that held 0..9 said "frames 0 to 9" were left, naming the three
// it had just written; and a single frame was "1 frames".
TEST(SolveCommand, TheNoteOfEarlierFramesSaysWhichAreLeftAndCountsReadRight) {
    const fs::path demo = makeDemo(10);
    const fs::path out = demo / "x";
    ASSERT_EQ(runCli(solveArgs(demo, out) + " --quiet").exitCode, 0);
    CliResult r = runCli(solveArgs(demo, out) + " --quiet --frames 3:6");
    ASSERT_EQ(r.exitCode, 0) << r.out;
    EXPECT_NE(r.out.find("also holds 7 OBJ frames this run did not write (frames 0 to 2 and 6 to 9 "
                         "of walker_*.obj"),
              std::string::npos)
        << r.out;
    fs::remove(out / "walker_0000.obj");
    fs::remove(out / "walker_0001.obj");
    r = runCli(solveArgs(demo, out) + " --frames 3:10");
    ASSERT_EQ(r.exitCode, 0) << r.out;
    EXPECT_NE(r.out.find("also holds 1 OBJ frame this run did not write (frame 2 of"),
              std::string::npos)
        << r.out;
    r = runCli(solveArgs(demo, out) + " --frames 2:3");
    EXPECT_NE(r.out.find("walker_*.obj: 1 frame, "), std::string::npos) << r.out;
}

// Solved into the demo's truth/, whose frames share the walker's stem, solve replaced the true
// motion with its answer, noting nothing (every frame was one it wrote). Files of the outputs'
// names that no Boneless export wrote are refused, named, until --force; an earlier export's,
// its sidecar gone or not, are replaced as before.
TEST(SolveCommand, FramesNoBonelessExportWroteAreReplacedOnlyWithForce) {
    const fs::path demo = makeDemo(4);
    const fs::path truth = demo / "truth";
    const auto firstLine = [](const fs::path& file) {
        std::string line;
        std::getline(std::ifstream(file), line);
        return line;
    };
    const std::string trueFrame = firstLine(truth / "walker_0001.obj");
    CliResult r = runCli(solveArgs(demo, truth) + " --quiet");
    EXPECT_EQ(r.exitCode, 1) << r.out;
    EXPECT_NE(r.out.find(truth.string() +
                         ": walker_0000.obj, walker_0001.obj, walker_0002.obj and 1 more file "
                         "were not written by a Boneless export, and this solve would replace "
                         "them; nothing was written: give --force to replace them, or another "
                         "output folder\n"),
              std::string::npos)
        << r.out;
    EXPECT_EQ(firstLine(truth / "walker_0001.obj"), trueFrame);
    EXPECT_FALSE(fs::exists(truth / "walker.json"));
    // Frames outside the range are not replaced: only those inside are named.
    r = runCli(solveArgs(demo, truth) + " --quiet --frames 3:4");
    EXPECT_EQ(r.exitCode, 1) << r.out;
    EXPECT_NE(r.out.find(": walker_0003.obj was not written by a Boneless export, and this solve "
                         "would replace it"),
              std::string::npos)
        << r.out;

    // A point cache of the stem that no sidecar records is another's too.
    const fs::path caches = demo / "caches";
    fs::create_directories(caches);
    std::ofstream(caches / "walker.pc2") << "mine";
    r = runCli(solveArgs(demo, caches) + " --quiet --format pc2");
    EXPECT_EQ(r.exitCode, 1) << r.out;
    EXPECT_NE(r.out.find(": walker.pc2 was not written by a Boneless export"), std::string::npos)
        << r.out;
    r = runCli(solveArgs(demo, caches) + " --quiet --format pc2 --force");
    EXPECT_EQ(r.exitCode, 0) << r.out;
    r = runCli(solveArgs(demo, caches) + " --quiet --format pc2");  // its own, now
    EXPECT_EQ(r.exitCode, 0) << r.out;

    // An earlier export is replaced without --force, its sidecar there or not.
    const fs::path out = demo / "x";
    ASSERT_EQ(runCli(solveArgs(demo, out) + " --quiet").exitCode, 0);
    fs::remove(out / "walker.json");
    r = runCli(solveArgs(demo, out) + " --quiet");
    EXPECT_EQ(r.exitCode, 0) << r.out;

    r = runCli(solveArgs(demo, truth) + " --quiet --force");
    EXPECT_EQ(r.exitCode, 0) << r.out;
    EXPECT_EQ(firstLine(truth / "walker_0001.obj").rfind("# Boneless: ", 0), 0u);
}

// A version 1 map whose entry has a face number solved with the entry on its vertex, and nothing
// said so; solve, batch and map suggest now warn, naming the map and the entry.
TEST(SolveCommand, WarnsOfAVersion1EntrysFaceThatOnlyVersion2Reads) {
    const fs::path demo = makeDemo(2);
    nlohmann::json map = nlohmann::json::parse(std::ifstream(demo / "walker.map.json"));
    ASSERT_EQ(map["version"], 1);
    map["markers"][0]["face"] = 5;
    const std::string label = map["markers"][0]["label"];
    std::ofstream(demo / "walker.map.json") << map.dump(2);
    const CliResult r = runCli(solveArgs(demo, demo / "x") + " --quiet");
    EXPECT_EQ(r.exitCode, 0) << r.out;
    EXPECT_NE(r.out.find("warning: " + (demo / "walker.map.json").string() + ": marker " + label +
                         " has \"face\": 5, which only \"version\": 2 reads: this file says "
                         "\"version\": 1, so it sits on its \"vertex\""),
              std::string::npos)
        << r.out;
    std::ofstream(demo / "m.json") << nlohmann::json{{"takes",
                                                      {{{"mesh", "walker.obj"},
                                                        {"c3d", "walker.c3d"},
                                                        {"map", "walker.map.json"},
                                                        {"out", "y"}}}}};
    const CliResult batch = runCli("batch " + (demo / "m.json").string());
    EXPECT_EQ(batch.exitCode, 0) << batch.out;
    EXPECT_NE(batch.out.find("  warning: " + (demo / "walker.map.json").string() + ": marker " +
                             label + " has \"face\": 5"),
              std::string::npos)
        << batch.out;
}

// A range wholly past the take's end is refused; the note that the range was cut to the take must
// not come first, saying it would solve "9:6".
TEST(SolveCommand, ARangeStartingPastTheTakesEndIsRefusedWithoutANoteOfSolvingIt) {
    const fs::path demo = makeDemo(6);
    const CliResult r = runCli(solveArgs(demo, demo / "x") + " --quiet --frames 9:20");
    EXPECT_EQ(r.exitCode, 1) << r.out;
    EXPECT_NE(r.out.find("frames 9:20 select no frame of " + (demo / "walker.c3d").string() +
                         " (6 frames)"),
              std::string::npos)
        << r.out;
    EXPECT_EQ(r.out.find("runs past the end"), std::string::npos) << r.out;
    EXPECT_FALSE(fs::exists(demo / "x" / "walker.json"));
}

// A take cut short (a copy interrupted) solves the frames it holds; the run says so, naming the
// file, and the sidecar's range says which. Before, only `inspect` told.
TEST(SolveCommand, SaysATakeIsTruncatedAndSolvesTheFramesItHolds) {
    const fs::path demo = makeDemo(10);
    const fs::path take = demo / "walker.c3d";
    fs::resize_file(take, fs::file_size(take) * 2 / 3);
    const CliResult r = runCli(solveArgs(demo, demo / "x") + " --quiet");
    ASSERT_EQ(r.exitCode, 0) << r.out;
    EXPECT_NE(r.out.find("warning: " + take.string() + ": file is truncated: 10 frames declared"),
              std::string::npos)
        << r.out;
    const nlohmann::json s = sidecar(demo / "x");
    EXPECT_TRUE(s["complete"].get<bool>());
    EXPECT_LT(s["frame_range"][1].get<int>(), 10);
    // An intact take has nothing to say.
    const fs::path whole = makeDemo(3);
    const CliResult clean = runCli(solveArgs(whole, whole / "x"));
    ASSERT_EQ(clean.exitCode, 0) << clean.out;
    EXPECT_EQ(clean.out.find("warning"), std::string::npos) << clean.out;
}

// The actor leaves the volume for frames 5 to 7: those frames hold a neighbour's pose, say so,
// and have no residual to pull the take's mean down (they were the rest mesh at the origin,
// with a residual of 0).
TEST(SolveCommand, FramesThatShowNoMarkerHoldANeighboursPoseAndAreNamed) {
    const fs::path demo = makeDemo(12);
    const fs::path take = demo / "walker.c3d";
    C3dTake t = readC3d(take.string());
    for (std::size_t f : {5, 6, 7})
        for (std::size_t k = 0; k < t.points.size(); ++k) t.samples.setMissing(f, k);
    writeC3d(t, take.string());
    const CliResult r = runCli(solveArgs(demo, demo / "x") + " --fill-gaps-s 0 --quiet");
    ASSERT_EQ(r.exitCode, 0) << r.out;
    EXPECT_NE(r.out.find("warning: " + take.string() +
                         ": frames 5 to 7 show no marker; each holds the pose of the nearest "
                         "frame that shows one"),
              std::string::npos)
        << r.out;
    const nlohmann::json s = sidecar(demo / "x");
    EXPECT_EQ(s["summary"]["frames_held"], nlohmann::json::parse("[[5, 7]]"));
    for (int f : {5, 6, 7}) {
        EXPECT_TRUE(s["per_frame"][f]["residual_rms_mm"].is_null());
        EXPECT_EQ(s["per_frame"][f]["held_from"], f == 7 ? 8 : 4);
    }
    EXPECT_FALSE(s["per_frame"][4].contains("held_from"));
    const TriMesh held = readMesh((demo / "x" / "walker_0006.obj").string()).mesh;
    const TriMesh seen = readMesh((demo / "x" / "walker_0004.obj").string()).mesh;
    EXPECT_EQ(held.V, seen.V);
}

// The calibration frame is chosen from the whole take, not the frames solved: a range solved
// alone fits the rest the take's other ranges are solved against, and its sidecar says so. The
// rest pose (frame 0) is hidden, so that the choice falls between the ranges.
TEST(SolveCommand, TheCalibrationFrameIsTheSameWhicheverFramesAreSolved) {
    const fs::path demo = makeDemo(60);
    const fs::path take = demo / "walker.c3d";
    C3dTake t = readC3d(take.string());
    for (std::size_t f = 0; f < 5; ++f) t.samples.setMissing(f, 0);
    writeC3d(t, take.string());
    std::vector<int> frames;
    for (const std::string range : {"", "0:3", "57:60", "20:22"}) {
        const fs::path out = demo / ("x" + std::to_string(frames.size()));
        const CliResult r = runCli(solveArgs(demo, out) + " --quiet --format pc2" +
                                   (range.empty() ? "" : " --frames " + range));
        ASSERT_EQ(r.exitCode, 0) << r.out;
        frames.push_back(sidecar(out)["calibration"]["frame"].get<int>());
        EXPECT_EQ(frames.back(), frames.front()) << "--frames " << range;
    }
    EXPECT_GE(frames.front(), 5) << "frame 0 shows every marker";
}

// The glb's morph targets carry the take's frame numbers, as the OBJ files of the same range do:
// before, frames 2:4 were frame_0000 and frame_0001.
TEST(SolveCommand, GlbMorphTargetsAreNamedByTheTakesFrameNumbersAsObjFramesAre) {
    const fs::path demo = makeDemo(6);
    const CliResult r = runCli(solveArgs(demo, demo / "x") + " --quiet --format glb --frames 2:4");
    ASSERT_EQ(r.exitCode, 0) << r.out;
    tinygltf::Model m;
    tinygltf::TinyGLTF loader;
    std::string error, warning;
    ASSERT_TRUE(
        loader.LoadBinaryFromFile(&m, &error, &warning, (demo / "x" / "walker.glb").string()))
        << error;
    ASSERT_EQ(m.meshes.size(), 1u);
    const tinygltf::Value& names = m.meshes[0].extras.Get("targetNames");
    ASSERT_EQ(names.ArrayLen(), 2u);
    EXPECT_EQ(names.Get(0).Get<std::string>(), "frame_0002");
    EXPECT_EQ(names.Get(1).Get<std::string>(), "frame_0003");
}

TEST(SolveCommand, RunningOutOfAddressSpaceEndsWithAMessageNotAHang) {
    // 120 MB of address space is less than the program and its BLAS threads take. Before, the run
    // printed "internal error: std::bad_alloc" and then waited for ever on a BLAS thread. The
    // memory estimate now refuses such a limit up front (exit 1), when the BLAS threads leave the
    // program the room to read the mesh.
    const fs::path demo = makeDemo(3);
    const CliResult r = runShell("ulimit -v 120000; timeout 60 " + std::string(BONELESS_CLI) + " " +
                                 solveArgs(demo, demo / "x") + " --quiet 2>&1");
    ASSERT_NE(r.exitCode, 124) << r.out;  // the timeout
    const bool refused = r.exitCode == 1 && r.out.find("would need about") != std::string::npos;
    EXPECT_TRUE(refused || r.exitCode == 3) << r.out;
    EXPECT_TRUE(refused || r.out.find("out of memory") != std::string::npos ||
                r.out.find("the system refused") != std::string::npos)
        << r.out;
    EXPECT_EQ(r.out.find("internal error"), std::string::npos) << r.out;
}

// --help offered PC2 for Maya, which docs/export.md says cannot read it without a plug-in.
TEST(SolveCommand, HelpOffersEachFormatForTheApplicationsTheExportGuideNames) {
    const CliResult help = runCli("solve --help");
    const std::size_t pc2 = help.out.find("pc2: "), mdd = help.out.find("mdd: ");
    ASSERT_NE(pc2, std::string::npos) << help.out;
    const std::string offered = help.out.substr(pc2, mdd - pc2);
    EXPECT_NE(offered.find("3ds Max"), std::string::npos) << offered;
    EXPECT_EQ(offered.find("Maya"), std::string::npos) << offered;
}

// solve and batch read "3:" and ":3" as eval does; only eval's help said so.
TEST(SolveCommand, HelpSaysAFrameRangeMayLeaveOutEitherEnd) {
    for (const char* command : {"solve --help", "eval --help"}) {
        const CliResult help = runCli(command);
        EXPECT_NE(help.out.find("(0-based, B excluded; A: or :B)"), std::string::npos) << help.out;
    }
}

TEST(DemoCommand, DetailRefinesTheSameWalker) {
    const fs::path dir = freshTestDir("demo-detail");
    const CliResult r = runCli("demo --out " + dir.string() + " --frame-count 2 --detail 2");
    ASSERT_EQ(r.exitCode, 0) << r.out;
    const TriMesh fine = readMesh((dir / "walker.obj").string()).mesh;
    // One more Catmull–Clark step: 4 times the quads, each two triangles.
    const TriMesh coarse = readMesh((makeDemo(2) / "walker.obj").string()).mesh;
    EXPECT_EQ(fine.faceCount(), 4 * coarse.faceCount());
    EXPECT_NE(r.out.find(std::to_string(fine.faceCount()) + " faces"), std::string::npos) << r.out;
    // The same walker: the bounding box hardly depends on the resolution.
    EXPECT_NEAR(boundingBoxDiagonal(fine.V), boundingBoxDiagonal(coarse.V),
                0.01 * boundingBoxDiagonal(coarse.V));
    const CliResult bad = runCli("demo --out " + dir.string() + " --detail 0");
    EXPECT_NE(bad.exitCode, 0);
    EXPECT_NE(bad.out.find("--detail"), std::string::npos) << bad.out;
}

// Before, nan and inf wrote a take with every sample missing and a map of null offsets, and 1e308
// ended in an internal error of the C3D writer.
TEST(DemoCommand, AnOffsetThatIsNoSensibleDistanceIsRefusedNamingTheFlag) {
    const fs::path dir = freshTestDir("demo-offset");
    for (const char* offset : {"nan", "inf", "1e308", "-5", "101"}) {
        const CliResult r =
            runCli("demo --out " + (dir / "x").string() + " --frame-count 2 --offset-mm " + offset);
        EXPECT_EQ(r.exitCode, 1) << offset;  // bad input, as a bad file is
        EXPECT_NE(
            r.out.find("--offset-mm: must be a number from 0 to 100, got " + std::string(offset)),
            std::string::npos)
            << r.out;
        EXPECT_FALSE(fs::exists(dir / "x")) << offset;
    }
    EXPECT_EQ(
        runCli("demo --out " + (dir / "x").string() + " --frame-count 2 --offset-mm 100").exitCode,
        0);
}

// "--frames INT:INT in [1 - 100000]" read like a range, and "--frames 10:20" was refused with
// "Value 10:20 not in range": it is a count (now --frame-count).
TEST(DemoCommand, TheFrameCountIsACountInItsHelpAndItsRefusal) {
    const CliResult help = runCli("demo --help");
    EXPECT_EQ(help.out.find("INT:INT"), std::string::npos) << help.out;
    EXPECT_NE(help.out.find("How many frames the take has (1 to 100000)"), std::string::npos)
        << help.out;
    const fs::path dir = freshTestDir("demo-frames");
    const CliResult r = runCli("demo --out " + (dir / "x").string() + " --frame-count 10:20");
    EXPECT_EQ(r.exitCode, 1) << r.out;
    EXPECT_NE(r.out.find("--frame-count: must be a whole number from 1 to 100000, got \"10:20\""),
              std::string::npos)
        << r.out;
    EXPECT_FALSE(fs::exists(dir / "x"));
}

// 100,000 frames at detail 4 need about 2,200 GB. Before, the demo made every frame in memory and
// wrote until the disk was full: 100,000 frames at detail 1 wrote 31 GB without a word. Under
// ulimit -v, so that a demo that does not check runs out of its own memory, not the machine's.
TEST(DemoCommand, ADemoItsFileSystemHasNoRoomForIsRefusedBeforeAnythingIsWritten) {
    const fs::path dir = freshTestDir("demo-no-room"), out = dir / "x";
    std::error_code ec;
    const fs::space_info space = fs::space(dir, ec);
    ASSERT_FALSE(ec) << ec.message();
    if (space.available > (std::uintmax_t(2000) << 30)) GTEST_SKIP() << "2,000 GB free";
    const CliResult r =
        runShell("ulimit -v 1000000; " + std::string(BONELESS_CLI) + " demo --out " + out.string() +
                 " --frame-count 100000 --detail 4 2>&1");
    EXPECT_EQ(r.exitCode, 1) << r.out;
    EXPECT_NE(r.out.find(out.string() + ": the demo needs about "), std::string::npos) << r.out;
    EXPECT_NE(r.out.find("(100000 frames, each with its true pose as an OBJ), and its file system "
                         "has "),
              std::string::npos)
        << r.out;
    EXPECT_NE(r.out.find(" GB free\n"), std::string::npos) << r.out;
    EXPECT_FALSE(fs::exists(out));
}

// Every exported frame holds a neighbour's pose: no frame has a residual, so there is no mean.
// The summary said 0.00 mm, a perfect fit.
TEST(SolveCommand, ARangeOfHeldFramesOnlyHasNoResidualMeanRatherThanZero) {
    const fs::path demo = makeDemo(40);
    const fs::path take = demo / "walker.c3d";
    C3dTake t = readC3d(take.string());
    for (std::size_t f = 20; f < 32; ++f)
        for (std::size_t k = 0; k < t.points.size(); ++k) t.samples.setMissing(f, k);
    writeC3d(t, take.string());
    const CliResult r =
        runCli(solveArgs(demo, demo / "x") + " --format pc2 --frames 22:28 --fill-gaps-s 0");
    ASSERT_EQ(r.exitCode, 0) << r.out;
    EXPECT_NE(r.out.find("marker residual RMS none (no frame shows a marker)"), std::string::npos)
        << r.out;
    EXPECT_EQ(r.out.find("0.00 mm mean"), std::string::npos) << r.out;
    const nlohmann::json summary = sidecar(demo / "x")["summary"];
    EXPECT_TRUE(summary["residual_rms_mm_mean"].is_null()) << summary;
    EXPECT_TRUE(summary["residual_rms_mm_worst_frame"].is_null()) << summary;
}

// A take whose POINT:RATE and header rate are 0 has no time per frame. glb and MDD key frames by
// time: every key was written at 0 (glTF wants them increasing; Blender collapsed the animation),
// and --low-pass-hz 5 said "below 0 Hz at a frame rate of 0 Hz". OBJ and PC2 number frames.
TEST(SolveCommand, ATakeWithoutAFrameRateIsRefusedAsGlbOrMddAndForLowPassButSolvesAsObjOrPc2) {
    const fs::path demo = makeDemo(3);
    const fs::path take = demo / "walker.c3d";
    C3dTake t = readC3d(take.string());
    t.rate = 0;
    writeC3d(t, take.string());
    for (const std::string format : {"glb", "mdd"}) {
        const CliResult r = runCli(solveArgs(demo, demo / format) + " --format " + format);
        EXPECT_EQ(r.exitCode, 1) << r.out;
        EXPECT_NE(r.out.find(take.string() + ": its frame rate is 0"), std::string::npos) << r.out;
        EXPECT_NE(r.out.find("obj or pc2"), std::string::npos) << r.out;
        EXPECT_FALSE(fs::exists(demo / format / ("walker." + format)));
    }
    const CliResult lowPass = runCli(solveArgs(demo, demo / "lp") + " --low-pass-hz 5");
    EXPECT_EQ(lowPass.exitCode, 1) << lowPass.out;
    EXPECT_NE(lowPass.out.find(take.string() + ": the take has no frame rate"), std::string::npos)
        << lowPass.out;
    EXPECT_EQ(lowPass.out.find("below 0 Hz"), std::string::npos) << lowPass.out;
    for (const std::string format : {"obj", "pc2"}) {
        const CliResult r = runCli(solveArgs(demo, demo / format) + " --quiet --format " + format);
        ASSERT_EQ(r.exitCode, 0) << r.out;
        EXPECT_TRUE(sidecar(demo / format)["fps"].is_null()) << "not 0 frames a second";
    }
}

// A take whose POINT:Y_SCREEN says +Y is up (many systems but Vicon's) is the same capture as the
// Z-up take turned a quarter about X: it solves to the same mesh, and the sidecar says which axis
// was the take's up. Before, its +Z (then horizontal) was levelled onto the mesh's up: the guess
// said "mesh up axis -y" and the sidecar "+z", and --mesh-up +z laid the body down.
TEST(SolveCommand, ATakeWhoseYScreenSaysPlusYSolvesToTheSameMeshAsItsZUpTwin) {
    const fs::path demo = makeDemo(4);
    C3dTake t = readC3d((demo / "walker.c3d").string());
    for (std::size_t f = 0; f < t.frameCount(); ++f)
        for (std::size_t k = 0; k < t.points.size(); ++k)
            if (const auto p = t.samples.position(f, k))
                t.samples.set(f, k, p->x(), p->z(), -p->y(), t.samples.residual(f, k));
    t.parameters.set("POINT", C3dParameter::chars("X_SCREEN", {"+X"}));
    t.parameters.set("POINT", C3dParameter::chars("Y_SCREEN", {"+Y"}));
    const fs::path yUp = demo / "walker_y_up.c3d";
    writeC3d(t, yUp.string());
    EXPECT_NE(runCli("inspect " + yUp.string()).out.find("  up        +y\n"), std::string::npos);
    const std::string args = " --mesh " + (demo / "walker.obj").string() + " --map " +
                             (demo / "walker.map.json").string() + " --format pc2";
    for (const std::string up : {"", " --mesh-up +z"}) {
        const CliResult z = runCli("solve --c3d " + (demo / "walker.c3d").string() + args + up +
                                   " --out " + (demo / "z").string());
        ASSERT_EQ(z.exitCode, 0) << z.out;
        const CliResult y =
            runCli("solve --c3d " + yUp.string() + args + up + " --out " + (demo / "y").string());
        ASSERT_EQ(y.exitCode, 0) << y.out;
        EXPECT_NE(y.out.find("mesh up axis +z"), std::string::npos) << y.out;
        EXPECT_EQ(sidecar(demo / "y")["up_axis"]["take"], "+y");
        EXPECT_EQ(sidecar(demo / "y")["up_axis"]["mesh_guess"], "+z");
        EXPECT_EQ(sidecar(demo / "z")["up_axis"]["take"], "+z");
        const auto fromZ = readPointCache((demo / "z" / "walker.pc2").string());
        const auto fromY = readPointCache((demo / "y" / "walker.pc2").string());
        ASSERT_EQ(fromZ.size(), fromY.size());
        const double diagonal = boundingBoxDiagonal(fromZ[0]);
        for (std::size_t f = 0; f < fromZ.size(); ++f)
            EXPECT_LT((fromZ[f] - fromY[f]).rowwise().norm().maxCoeff(), 1e-5 * diagonal)
                << "frame " << f << up;
    }
}

TEST(SolveCommand, SaysWhenItPreparesAndTimesFramesFromTheFirstFramesStart) {
    const fs::path demo = makeDemo(6);
    const CliResult r = runCli(solveArgs(demo, demo / "solved") + " --format pc2");
    ASSERT_EQ(r.exitCode, 0) << r.out;
    const std::size_t preparing = r.out.find(
        "preparing: aligning the take to the mesh, "
        "calibrating the rest to the actor, factorising (");
    const std::size_t prepared = r.out.find("\nprepared in ");
    const std::size_t firstFrame = r.out.find(" frames  ");
    ASSERT_NE(preparing, std::string::npos) << r.out;
    ASSERT_NE(prepared, std::string::npos) << r.out;
    EXPECT_LT(preparing, prepared);
    EXPECT_LT(prepared, firstFrame) << r.out;
    // The last progress line's s/frame times its frames is the frames' time alone: the whole run
    // less the preparation (each rounded to 0.1 s).
    std::smatch m;
    const std::string tail = r.out.substr(r.out.rfind("6/6 frames"));
    ASSERT_TRUE(std::regex_search(tail, m, std::regex(R"(6/6 frames  ([0-9.]+) s/frame)")));
    const double frames = 6 * std::stod(m[1]);
    const std::string rest = r.out.substr(prepared);
    ASSERT_TRUE(std::regex_search(rest, m, std::regex(R"(prepared in ([0-9.]+) s)")));
    const double preparation = std::stod(m[1]);
    ASSERT_TRUE(std::regex_search(rest, m, std::regex(R"(, [0-9.]+ MB in ([0-9.]+) s)")));
    EXPECT_LE(frames, std::stod(m[1]) - preparation + 0.11) << r.out;
}

// Stopped by Ctrl-C, an OBJ run said nothing of the frames an earlier run left past the stop,
// which a tool reading walker_*.obj plays as part of this take; a run that finished names them.
TEST(SolveCommand, AStoppedRunNamesTheEarlierRunsFramesLeftBesideAsAFinishedOneDoes) {
    const fs::path demo = makeDemo(3000), out = demo / "solved";
    ASSERT_EQ(runCli(solveArgs(demo, out) + " --quiet --frames 2990:3000").exitCode, 0);
    const CliResult r = runShell("timeout --preserve-status -s INT 1 " + std::string(BONELESS_CLI) +
                                 " " + solveArgs(demo, out) + " --quiet 2>&1");
    EXPECT_EQ(r.exitCode, 130) << r.out;
    ASSERT_LT(sidecar(out)["frames_written"].get<int>(), 2990);
    EXPECT_NE(r.out.find("note: " + out.string() +
                         " also holds 10 OBJ frames this run did not write (frames 2990 to 2999 "
                         "of walker_*.obj, from an earlier run)"),
              std::string::npos)
        << r.out;
}

// "the 78 frames written are valid" read as kept, while a run again solves the take from its
// first frame: the message says what was written and what a run again does.
TEST(SolveCommand, AStopSaysARunAgainSolvesTheTakeFromItsFirstFrame) {
    const fs::path demo = makeDemo(3000), out = demo / "solved";
    const CliResult r = runShell("timeout --preserve-status -s INT 1 " + std::string(BONELESS_CLI) +
                                 " " + solveArgs(demo, out) + " --quiet 2>&1");
    EXPECT_EQ(r.exitCode, 130) << r.out;
    const int n = sidecar(out)["frames_written"].get<int>();
    EXPECT_NE(r.out.find("interrupted after " + plural(n, "frame") +
                         ": walker.json records the take as incomplete, and solving it "
                         "again starts from its first frame"),
              std::string::npos)
        << r.out;
    EXPECT_EQ(r.out.find("valid"), std::string::npos) << r.out;
}

// `solve --calibration-frame 300` aligned CMU 85_02 at 256.3 mm, against 104.6 mm at the automatic
// frame 171, and said the figure alone; with a wrong --mesh-up, 743.6 mm and then a summary that
// looked fine. The app's rule (docs/calibration.md) now warns in solve and batch alike.
TEST(SolveCommand, AnAlignmentMuchWorseThanTheAutomaticChoiceIsWarnedOfNamingBothFigures) {
    const fs::path demo = makeDemo(20), out = demo / "x";
    const std::string c3d = (demo / "walker.c3d").string();
    CliResult r = runCli(solveArgs(demo, out) + " --quiet --frames 0:2 --calibration-frame 10");
    EXPECT_EQ(r.exitCode, 0) << r.out;
    EXPECT_NE(r.out.find("warning: " + c3d + ": the alignment at frame 10 leaves "),
              std::string::npos)
        << r.out;
    EXPECT_NE(r.out.find(" mm (RMS), over 1.5 times and 50 mm more than the automatic choice's "),
              std::string::npos)
        << r.out;
    EXPECT_NE(r.out.find(" mm at frame 0; try without --calibration-frame"), std::string::npos)
        << r.out;
    r = runCli(solveArgs(demo, out) + " --quiet --frames 0:2 --mesh-up -y");
    EXPECT_NE(r.out.find("warning: " + c3d + ": the alignment at frame 0 with mesh up -y leaves "),
              std::string::npos)
        << r.out;
    EXPECT_NE(r.out.find(" mm at frame 0 with mesh up +z; try without --mesh-up"),
              std::string::npos)
        << r.out;
    // A frame that aligns about as well is the user's choice to make.
    r = runCli(solveArgs(demo, out) + " --quiet --frames 0:2 --calibration-frame 1 --mesh-up +z");
    EXPECT_EQ(r.out.find("warning"), std::string::npos) << r.out;

    // A manifest sets them too: said under the take's line, naming the keys.
    std::ofstream(demo / "m.json") << nlohmann::json{
        {"takes",
         {{{"mesh", "walker.obj"},
           {"c3d", "walker.c3d"},
           {"map", "walker.map.json"},
           {"out", "b"},
           {"frames", "0:2"},
           {"calibration_frame", 10},
           {"mesh_up", "-y"}}}}}.dump();
    r = runCli("batch " + (demo / "m.json").string());
    EXPECT_EQ(r.exitCode, 0) << r.out;
    EXPECT_NE(r.out.find("2 frames in "), std::string::npos) << r.out;
    EXPECT_NE(
        r.out.find("\n  warning: " + c3d + ": the alignment at frame 10 with mesh up -y leaves "),
        std::string::npos)
        << r.out;
    EXPECT_NE(r.out.find("; try without \"calibration_frame\" and \"mesh_up\""), std::string::npos)
        << r.out;
}

// The OBJ frames' first line named the take as typed (`demo/walker.c3d`), so the same solve run
// from another folder, or by the app, wrote other bytes; it names the take in full, as the
// sidecar does.
TEST(SolveCommand, ObjFramesNameTheirInputsInFullWhicheverFolderSolveRanIn) {
    const fs::path demo = makeDemo(2);
    const std::string name = demo.filename().string();
    const CliResult r =
        runShell("cd " + demo.parent_path().string() + " && " + BONELESS_CLI + " solve --mesh " +
                 name + "/walker.obj --c3d " + name + "/walker.c3d --map " + name +
                 "/walker.map.json --out " + name + "/x --write-calibrated-rest --quiet 2>&1");
    ASSERT_EQ(r.exitCode, 0) << r.out;
    const auto firstLine = [](const fs::path& file) {
        std::string line;
        std::getline(std::ifstream(file), line);
        return line;
    };
    const std::string take = (demo / "walker.c3d").string();
    EXPECT_EQ(firstLine(demo / "x" / "walker_0000.obj"), "# Boneless: " + take + " frame 0");
    EXPECT_EQ(firstLine(demo / "x" / "walker_calibrated_rest.obj")
                  .rfind("# Boneless: " + (demo / "walker.obj").string() + " fitted to " + take, 0),
              0u);
}

// Two runs solving into one folder at once (two batch runs, a shard started twice) interleaved
// their frames under the sidecar of whichever finished last, which said complete: a later run
// skipped the mixture. A run that finds the take's files being written leaves them.
TEST(SolveCommand, ARunIntoFilesAnotherRunIsWritingIsRefusedNamingThem) {
    const fs::path demo = makeDemo(3), out = demo / "out";
    fs::create_directories(out);
    // What a run solving into out/walker.* holds while it writes, played by the test.
    const int held = ::open((out / ".walker.lock").c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0644);
    ASSERT_GE(held, 0);
    ASSERT_EQ(::flock(held, LOCK_EX | LOCK_NB), 0);
    CliResult r = runCli(solveArgs(demo, out) + " --quiet");
    ::close(held);
    EXPECT_EQ(r.exitCode, 1) << r.out;
    EXPECT_NE(r.out.find((out / "walker.json").string() +
                         ": another run is solving into this take's files now; nothing was "
                         "written"),
              std::string::npos)
        << r.out;
    EXPECT_FALSE(fs::exists(out / "walker_0000.obj"));
    // Once that run has let go the take solves, and leaves no lock behind.
    r = runCli(solveArgs(demo, out) + " --quiet");
    EXPECT_EQ(r.exitCode, 0) << r.out;
    EXPECT_TRUE(fs::exists(out / "walker_0002.obj"));
    EXPECT_FALSE(fs::exists(out / ".walker.lock"));
}

// `for t in takes/*.c3d; do solve --c3d $t --out solved; done` left only the last take's solve:
// each run replaced the one before, whose sidecar named another take, and said nothing of it.
TEST(SolveCommand, ASolveOfAnotherTakeInOutIsNotReplacedUnlessForced) {
    const fs::path demo = makeDemo(3), out = demo / "solved";
    fs::copy_file(demo / "walker.c3d", demo / "walk_a.c3d");
    fs::copy_file(demo / "walker.c3d", demo / "walk_b.c3d");
    const auto solve = [&](const std::string& take) {
        return runCli("solve --quiet --format pc2 --mesh " + (demo / "walker.obj").string() +
                      " --map " + (demo / "walker.map.json").string() + " --out " + out.string() +
                      " --c3d " + (demo / take).string());
    };
    ASSERT_EQ(solve("walk_a.c3d").exitCode, 0);
    CliResult r = solve("walk_b.c3d");
    EXPECT_EQ(r.exitCode, 1) << r.out;
    EXPECT_NE(r.out.find((out / "walker.json").string() + " is the solve of " +
                         (demo / "walk_a.c3d").string() + ", another take"),
              std::string::npos)
        << r.out;
    EXPECT_EQ(sidecar(out)["source"]["c3d"], (demo / "walk_a.c3d").string());
    // The same take again is replaced, as ever; another with --force too.
    EXPECT_EQ(solve("walk_a.c3d").exitCode, 0);
    r = runCli("solve --quiet --force --format pc2 --mesh " + (demo / "walker.obj").string() +
               " --map " + (demo / "walker.map.json").string() + " --out " + out.string() +
               " --c3d " + (demo / "walk_b.c3d").string());
    EXPECT_EQ(r.exitCode, 0) << r.out;
    EXPECT_EQ(sidecar(out)["source"]["c3d"], (demo / "walk_b.c3d").string());
}

// The demo's take worn by two actors, walker: and other: (1.5 m beside it), and a map of each.
fs::path makeTwoActorDemo() {
    const fs::path demo = makeDemo(3);
    const C3dTake one = readC3d((demo / "walker.c3d").string());
    const C3dTake two = taketest::wornByTwoActors(one);
    writeC3d(two, (demo / "two.c3d").string());
    const nlohmann::json bare = nlohmann::json::parse(std::ifstream(demo / "walker.map.json"));
    for (const std::string subject : {"walker", "other"}) {
        nlohmann::json map = bare;
        for (auto& m : map["markers"]) m["label"] = subject + ":" + m["label"].get<std::string>();
        std::ofstream(demo / (subject + ".map.json")) << map.dump(2);
    }
    return demo;
}

// Solving a second actor of a take into the folder of the first's solve replaced the first in
// silence: the sidecar named the same take, and only another take was refused.
TEST(SolveCommand, AnotherActorsSolveOfTheSameTakeInOutIsNotReplacedUnlessForced) {
    const fs::path demo = makeTwoActorDemo(), out = demo / "solved";
    const auto solve = [&](const std::string& subject, const std::string& more = "") {
        return runCli("solve --quiet --format pc2 --mesh " + (demo / "walker.obj").string() +
                      " --c3d " + (demo / "two.c3d").string() + " --map " +
                      (demo / (subject + ".map.json")).string() + " --out " + out.string() + more);
    };
    CliResult r = solve("other");
    ASSERT_EQ(r.exitCode, 0) << r.out;
    EXPECT_EQ(sidecar(out)["subjects"], nlohmann::json({"other"}));
    r = solve("walker");
    EXPECT_EQ(r.exitCode, 1) << r.out;
    EXPECT_NE(r.out.find((out / "walker.json").string() + " is the solve of subject other of " +
                         (demo / "two.c3d").string() + ", and solving subject walker into " +
                         out.string() + " would replace it; nothing was written"),
              std::string::npos)
        << r.out;
    EXPECT_EQ(sidecar(out)["subjects"], nlohmann::json({"other"}));
    // The same actor again is replaced, as ever; the other with --force too.
    EXPECT_EQ(solve("other").exitCode, 0);
    r = solve("walker", " --force");
    EXPECT_EQ(r.exitCode, 0) << r.out;
    EXPECT_EQ(sidecar(out)["subjects"], nlohmann::json({"walker"}));
}

// A calibration frame that misses a mapped marker fits the rest to the actor without it (the limb
// keeps the mesh's length in every frame), and nothing said so: the alignment's residual looked
// fine.
TEST(SolveCommand, ACalibrationFrameMissingAMappedMarkerIsSaidToFitTheRestWithoutIt) {
    const fs::path demo = makeDemo(3), out = demo / "solved";
    const std::string c3d = (demo / "walker.c3d").string();
    C3dTake take = readC3d(c3d);
    take.samples.setMissing(1, *take.findPoint("LKNE"));
    writeC3d(take, c3d);
    CliResult r = runCli(solveArgs(demo, out) +
                         " --quiet --format pc2 --fill-gaps-s 0 --calibration-frame 1");
    EXPECT_EQ(r.exitCode, 0) << r.out;
    EXPECT_NE(r.out.find("warning: " + c3d +
                         ": calibration frame 1 does not show LKNE (1 of the 39 mapped markers), "
                         "so the rest is fitted to the actor without it"),
              std::string::npos)
        << r.out;
    // The automatic choice is a frame that shows every one.
    r = runCli(solveArgs(demo, out) + " --quiet --format pc2 --fill-gaps-s 0");
    EXPECT_EQ(r.exitCode, 0) << r.out;
    EXPECT_EQ(r.out.find("does not show"), std::string::npos) << r.out;
}

// A rest asked for without calibration was refused only once the solver was prepared, after the
// earlier run's sidecar had gone: its complete solve was then solved again by the next batch run.
TEST(SolveCommand, ACalibratedRestWithoutCalibrationIsRefusedBeforeTheEarlierSolveIsTouched) {
    const fs::path demo = makeDemo(3), out = demo / "out";
    ASSERT_EQ(runCli(solveArgs(demo, out) + " --quiet --format pc2").exitCode, 0);
    const CliResult r = runCli(solveArgs(demo, out) +
                               " --quiet --format pc2 --calibrate none --write-calibrated-rest");
    EXPECT_EQ(r.exitCode, 1) << r.out;
    EXPECT_NE(r.out.find("writing the calibrated rest needs calibration"), std::string::npos)
        << r.out;
    EXPECT_TRUE(sidecar(out)["complete"].get<bool>());
}

// The second of two runs into one take found the lock only once its solver was prepared (the
// alignment, the calibration, the factorisation: seconds to minutes on a large mesh) and then
// threw that work away. A calibration frame past the take's end is refused by that preparation
// alone, so which refusal comes says which was checked first.
TEST(SolveCommand, ARunIntoFilesAnotherRunIsWritingIsRefusedBeforeItsSolverIsPrepared) {
    const fs::path demo = makeDemo(3), out = demo / "out";
    fs::create_directories(out);
    const int held = ::open((out / ".walker.lock").c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0644);
    ASSERT_GE(held, 0);
    ASSERT_EQ(::flock(held, LOCK_EX | LOCK_NB), 0);
    const CliResult r = runCli(solveArgs(demo, out) + " --quiet --calibration-frame 99");
    ::close(held);
    EXPECT_EQ(r.exitCode, 1) << r.out;
    EXPECT_NE(r.out.find("another run is solving into this take's files now"), std::string::npos)
        << r.out;
    EXPECT_EQ(r.out.find("calibration frame 99"), std::string::npos) << r.out;
}

// A run whose solver cannot be prepared leaves no folder behind that it made to hold the lock.
TEST(SolveCommand, ARunThatFailsBeforeWritingLeavesNoFolderItMade) {
    const fs::path demo = makeDemo(3), out = demo / "new" / "out";
    const CliResult r = runCli(solveArgs(demo, out) + " --quiet --calibration-frame 99");
    EXPECT_EQ(r.exitCode, 1) << r.out;
    EXPECT_NE(r.out.find("calibration frame 99"), std::string::npos) << r.out;
    EXPECT_FALSE(fs::exists(out)) << r.out;
}

namespace {
// The pid of a process that has run and is gone.
std::string deadPid() {
    const CliResult r = runShell("sh -c 'echo $$'");
    return r.out.substr(0, r.out.find('\n'));
}
}  // namespace

// kill -9 (the OOM killer, a node lost) leaves a writer's <output>.tmp<pid> beside its outputs; it
// was removed only when that very output was written again, so a take solved again as OBJ kept a
// killed pc2 run's cache of hundreds of megabytes for ever. A run removes every such file of its
// take's outputs whose process is gone, and nothing else.
TEST(SolveCommand, ARunRemovesItsTakesTemporariesLeftByKilledRunsAndNothingElse) {
    const fs::path demo = makeDemo(3), out = demo / "out";
    fs::create_directories(out);
    const std::string dead = deadPid(), alive = std::to_string(::getpid());
    const std::vector<std::string> leftovers = {
        "walker.pc2.tmp" + dead, "walker.mdd.frames.tmp" + dead, "walker.glb.tmp" + dead,
        "walker_0007.obj.tmp" + dead, "walker_calibrated_rest.obj.tmp" + dead};
    const std::vector<std::string> kept = {"walker.pc2.tmp" + alive,  // a run still writing it
                                           "walker.pc2.tmpnotes",     // not a writer's name
                                           "other.pc2.tmp" + dead,    // not this take's output
                                           "walker.txt.tmp" + dead};
    for (const auto& name : leftovers) std::ofstream(out / name) << "partial";
    for (const auto& name : kept) std::ofstream(out / name) << "someone's";
    const CliResult r = runCli(solveArgs(demo, out) + " --quiet --frames 0:2");
    ASSERT_EQ(r.exitCode, 0) << r.out;
    for (const auto& name : leftovers) EXPECT_FALSE(fs::exists(out / name)) << name;
    for (const auto& name : kept) EXPECT_TRUE(fs::exists(out / name)) << name;
}

// On a full disk an OBJ take failed part-way and its frames stayed, filling the disk for every
// take after it. A failed take's frames that this run wrote are removed; a file this run did not
// write (another run's frame, what stood in its way) is left.
TEST(SolveCommand, AFailedObjTakeRemovesTheFramesThisRunWroteAndNothingElse) {
    const fs::path demo = makeDemo(12), out = demo / "out";
    ASSERT_EQ(runCli(solveArgs(demo, out) + " --quiet --frames 9:10").exitCode, 0);
    fs::create_directories(out / "walker_0002.obj");  // frame 2 cannot be written
    const CliResult r = runCli(solveArgs(demo, out) + " --quiet --force --frames 0:4");
    EXPECT_EQ(r.exitCode, 1) << r.out;
    EXPECT_NE(r.out.find("walker_0002.obj"), std::string::npos) << r.out;
    EXPECT_NE(r.out.find("the 2 OBJ frames this run wrote were removed"), std::string::npos)
        << r.out;
    EXPECT_FALSE(fs::exists(out / "walker_0000.obj"));
    EXPECT_FALSE(fs::exists(out / "walker_0001.obj"));
    EXPECT_TRUE(fs::is_directory(out / "walker_0002.obj"));
    EXPECT_TRUE(fs::exists(out / "walker_0009.obj"));  // the earlier run's
    EXPECT_FALSE(sidecar(out)["complete"].get<bool>());
}

// Ctrl-C while the solver was prepared was noticed after the first frame, written over an earlier
// complete export, whose sidecar then called the take incomplete: a user stopping a run started
// by mistake lost the export before it. Now nothing is written.
TEST(SolveCommandSignals, CtrlCWhileTheSolverIsPreparedLeavesAnEarlierExportWhole) {
    const fs::path dir = freshTestDir("demo-detail"), out = dir / "solved";
    ASSERT_EQ(runCli("demo --out " + dir.string() + " --frame-count 3 --detail 2").exitCode, 0);
    const std::string args = solveArgs(dir, out) + " --format pc2";
    ASSERT_EQ(runCli(args + " --quiet").exitCode, 0);
    const auto bytes = [&](const char* name) {
        std::ostringstream s;
        s << std::ifstream(out / name, std::ios::binary).rdbuf();
        return s.str();
    };
    const std::string pc2 = bytes("walker.pc2"), json = bytes("walker.json");
    // The run's lock is taken before the solver is prepared (about a second at this detail).
    const CliResult r =
        runCliAndWhenExists(args + " --quiet", (out / ".walker.lock").string(), "kill -INT $pid");
    EXPECT_EQ(r.exitCode, 130) << r.out;
    EXPECT_NE(
        r.out.find("interrupted before any frame was written: the output folder is as it was"),
        std::string::npos)
        << r.out;
    EXPECT_EQ(bytes("walker.pc2"), pc2);
    EXPECT_EQ(bytes("walker.json"), json);
    EXPECT_TRUE(sidecar(out)["complete"].get<bool>());
}
