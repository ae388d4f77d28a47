#include <gtest/gtest.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <sstream>

#include "CliRunner.h"
#include "TestFiles.h"

using namespace boneless::testing;
namespace fs = std::filesystem;
using nlohmann::json;

namespace {

// Three takes of different lengths in DIR/takes, one mesh and map in DIR.
fs::path makeLibrary() {
    const fs::path dir = freshTestDir("library");
    fs::create_directories(dir / "takes");
    const char* names[] = {"walk_a", "walk_b", "walk_c"};
    for (int i = 0; i < 3; ++i) {
        const fs::path demo = dir / ("demo" + std::to_string(i));
        const CliResult r =
            runCli("demo --out " + demo.string() + " --frame-count " + std::to_string(4 + i));
        EXPECT_EQ(r.exitCode, 0) << r.out;
        fs::copy_file(demo / "walker.c3d", dir / "takes" / (std::string(names[i]) + ".c3d"));
        if (i == 0) {
            fs::copy_file(demo / "walker.obj", dir / "walker.obj");
            fs::copy_file(demo / "walker.map.json", dir / "walker.map.json");
        }
    }
    return dir;
}

fs::path writeManifest(const fs::path& dir, const std::string& name, const json& manifest) {
    const fs::path path = dir / name;
    std::ofstream(path) << manifest.dump(2);
    return path;
}

// The demo at --detail 2 in `dir` (its solver takes about a second to prepare, time enough to act
// once the run's lock appears) and a manifest solving it into `dir`/out as pc2.
fs::path slowDemoManifest(const fs::path& dir) {
    EXPECT_EQ(runCli("demo --out " + dir.string() + " --frame-count 3 --detail 2").exitCode, 0);
    return writeManifest(dir, "m.json",
                         {{"takes",
                           {{{"mesh", "walker.obj"},
                             {"c3d", "walker.c3d"},
                             {"map", "walker.map.json"},
                             {"format", "pc2"},
                             {"out", "out"}}}}});
}

json folderManifest(const std::string& out) {
    return {
        {"defaults", {{"format", "obj"}}},
        {"folders",
         {{{"c3d", "takes"}, {"mesh", "walker.obj"}, {"map", "walker.map.json"}, {"out", out}}}}};
}

// `dir`'s folder manifest (into "out"), written and run once; its path.
fs::path solvedOnce(const fs::path& dir) {
    const fs::path manifest = writeManifest(dir, "m.json", folderManifest("out"));
    const CliResult r = runCli("batch " + manifest.string());
    EXPECT_EQ(r.exitCode, 0) << r.out;
    return manifest;
}

// Every file under `root` by relative path; sidecars without their timings (they differ run to
// run), everything else byte for byte.
std::map<std::string, std::string> contents(const fs::path& root) {
    std::map<std::string, std::string> files;
    for (const auto& e : fs::recursive_directory_iterator(root)) {
        if (!e.is_regular_file()) continue;
        std::ostringstream bytes;
        bytes << std::ifstream(e.path(), std::ios::binary).rdbuf();
        std::string text = bytes.str();
        if (e.path().extension() == ".json") {
            json j = json::parse(text);
            for (json& f : j["per_frame"]) f.erase("ms");
            for (const char* k : {"ms_per_frame_mean", "ms_per_frame_worst", "ms_per_frame_median"})
                j["summary"].erase(k);
            text = j.dump();
        }
        files[fs::relative(e.path(), root).string()] = text;
    }
    return files;
}

// One take, its first 3 frames, into "one": a run that a manifest edited after it solves again.
json firstFramesOfWalkC() {
    return {{"defaults", {{"format", "pc2"}}},
            {"takes",
             {{{"mesh", "walker.obj"},
               {"map", "walker.map.json"},
               {"c3d", "takes/walk_c.c3d"},
               {"out", "one"},
               {"frames", "0:3"}}}}};
}

}  // namespace

TEST(Batch, TwoShardsTogetherWriteExactlyWhatOneRunWrites) {
    const fs::path dir = makeLibrary();
    const fs::path whole = writeManifest(dir, "whole.json", folderManifest("whole"));
    const fs::path split = writeManifest(dir, "split.json", folderManifest("split"));
    const CliResult one = runCli("batch " + whole.string());
    ASSERT_EQ(one.exitCode, 0) << one.out;
    EXPECT_NE(one.out.find("3 of 3 takes in shard 1/1: 3 solved, 0 skipped, 0 failed"),
              std::string::npos)
        << one.out;
    const CliResult first = runCli("batch " + split.string() + " --shard 1/2");
    const CliResult second = runCli("batch " + split.string() + " --shard 2/2");
    ASSERT_EQ(first.exitCode, 0) << first.out;
    ASSERT_EQ(second.exitCode, 0) << second.out;
    EXPECT_NE(first.out.find("2 of 3 takes in shard 1/2: 2 solved"), std::string::npos)
        << first.out;
    EXPECT_NE(second.out.find("1 of 3 takes in shard 2/2: 1 solved"), std::string::npos)
        << second.out;

    const auto a = contents(dir / "whole"), b = contents(dir / "split");
    EXPECT_EQ(a.size(), 3u + 4u + 5u + 6u);  // a sidecar and the OBJ frames per take
    ASSERT_EQ(a.size(), b.size());
    for (const auto& [name, bytes] : a) {
        ASSERT_TRUE(b.count(name)) << name;
        EXPECT_TRUE(b.at(name) == bytes) << name << " differs";
    }
    EXPECT_TRUE(json::parse(std::ifstream(dir / "whole" / "walk_b" / "walker.json"))["complete"]);
}

TEST(Batch, ARunAgainSkipsTheTakesItFinished) {
    const fs::path dir = makeLibrary();
    const fs::path manifest = solvedOnce(dir);
    // A take whose run did not finish has a sidecar saying so: it is solved again.
    const fs::path sidecar = dir / "out" / "walk_c" / "walker.json";
    json j = json::parse(std::ifstream(sidecar));
    j["complete"] = false;
    std::ofstream(sidecar) << j.dump();
    const auto before = fs::last_write_time(dir / "out" / "walk_a" / "walker_0000.obj");
    const CliResult again = runCli("batch " + manifest.string());
    ASSERT_EQ(again.exitCode, 0) << again.out;
    EXPECT_NE(again.out.find("3 of 3 takes in shard 1/1: 1 solved, 2 skipped, 0 failed"),
              std::string::npos)
        << again.out;
    EXPECT_NE(again.out.find("its sidecar says its run did not finish, solving again"),
              std::string::npos)
        << again.out;
    EXPECT_EQ(fs::last_write_time(dir / "out" / "walk_a" / "walker_0000.obj"), before);
    EXPECT_TRUE(json::parse(std::ifstream(sidecar))["complete"]);
}

TEST(Batch, ATakeAskedForOtherFramesOrOptionsIsSolvedAgain) {
    const fs::path dir = makeLibrary();
    json manifest = firstFramesOfWalkC();
    const fs::path path = writeManifest(dir, "m.json", manifest);
    ASSERT_EQ(runCli("batch " + path.string()).exitCode, 0);
    const fs::path sidecar = dir / "one" / "walker.json";
    auto range = [&] { return json::parse(std::ifstream(sidecar))["frame_range"]; };
    EXPECT_EQ(range(), json::array({0, 3}));
    // The manifest now asks for the whole take (6 frames): the 3 written are not the take.
    manifest["takes"][0].erase("frames");
    writeManifest(dir, "m.json", manifest);
    CliResult r = runCli("batch " + path.string());
    ASSERT_EQ(r.exitCode, 0) << r.out;
    EXPECT_NE(r.out.find("other frames or options (frames 0:3, now 0:6), solving again"),
              std::string::npos)
        << r.out;
    EXPECT_EQ(range(), json::array({0, 6}));
    // The same again is done; another marker weight is not.
    r = runCli("batch " + path.string());
    EXPECT_NE(r.out.find("0 solved, 1 skipped"), std::string::npos) << r.out;
    manifest["defaults"]["marker_weight"] = 5;
    writeManifest(dir, "m.json", manifest);
    r = runCli("batch " + path.string());
    EXPECT_NE(r.out.find("1 solved, 0 skipped"), std::string::npos) << r.out;
    EXPECT_EQ(json::parse(std::ifstream(sidecar))["options"]["marker_weight"], 5.0);
}

// With stdout and stderr in one log (a cluster's default), the note on a range cut at the take's
// end landed in the middle of the take's line, between its name and "6 frames in 0.4 s".
TEST(Batch, ARangePastTheTakesEndIsNotedUnderTheTakesLine) {
    const fs::path dir = makeLibrary();
    const fs::path path = writeManifest(dir, "m.json",
                                        {{"defaults", {{"format", "pc2"}}},
                                         {"takes",
                                          {{{"mesh", "walker.obj"},
                                            {"map", "walker.map.json"},
                                            {"c3d", "takes/walk_c.c3d"},
                                            {"out", "one"},
                                            {"frames", "2:100"}}}}});
    const CliResult r = runCli("batch " + path.string());
    ASSERT_EQ(r.exitCode, 0) << r.out;
    const std::string line = ": 4 frames in ";
    ASSERT_NE(r.out.find(line), std::string::npos) << r.out;
    const std::size_t note = r.out.find(" runs past the end of ");
    ASSERT_NE(note, std::string::npos) << r.out;
    EXPECT_GT(note, r.out.find(line)) << r.out;
}

// batch said "  warning: walk_c.c3d: frames 2:100 run past its end (6 frames): solving 2:6" where
// solve said "note: --frames 2:100 runs past the end of walk_c.c3d (6 frames): solving 2:6" of
// the same range: a range cut to the take is no fault of the take. Both say it as a note, in the
// same words, each naming the range as it was given.
TEST(Batch, ARangePastTheTakesEndIsANoteInSolvesWords) {
    const fs::path dir = makeLibrary();
    const std::string take = (dir / "takes" / "walk_c.c3d").string();
    const fs::path path = writeManifest(dir, "m.json",
                                        {{"takes",
                                          {{{"mesh", "walker.obj"},
                                            {"map", "walker.map.json"},
                                            {"c3d", "takes/walk_c.c3d"},
                                            {"out", "one"},
                                            {"frames", "2:100"}}}}});
    const CliResult batch = runCli("batch " + path.string());
    ASSERT_EQ(batch.exitCode, 0) << batch.out;
    EXPECT_NE(batch.out.find("\n  note: \"frames\" 2:100 runs past the end of " + take +
                             " (6 frames): solving 2:6\n"),
              std::string::npos)
        << batch.out;
    EXPECT_EQ(batch.out.find("warning"), std::string::npos) << batch.out;
    const CliResult solve = runCli("solve --quiet --mesh " + (dir / "walker.obj").string() +
                                   " --map " + (dir / "walker.map.json").string() + " --c3d " +
                                   take + " --out " + (dir / "two").string() + " --frames 2:100");
    ASSERT_EQ(solve.exitCode, 0) << solve.out;
    EXPECT_EQ(solve.out,
              "note: --frames 2:100 runs past the end of " + take + " (6 frames): solving 2:6\n");
}

// As solve: an entry whose "out" holds frames of its stem that no Boneless export wrote (the
// demo's truth/) fails naming them, the others solved, until --force; then it is a take like the
// others, skipped once complete.
TEST(Batch, AnOutHoldingFramesNoBonelessExportWroteFailsItsTakeUntilForce) {
    const fs::path dir = makeLibrary();
    const fs::path path =
        writeManifest(dir, "m.json",
                      {{"defaults", {{"mesh", "walker.obj"}, {"map", "walker.map.json"}}},
                       {"takes",
                        {{{"c3d", "takes/walk_a.c3d"}, {"out", "demo0/truth"}},
                         {{"c3d", "takes/walk_b.c3d"}, {"out", "b"}}}}});
    const CliResult r = runCli("batch " + path.string());
    EXPECT_EQ(r.exitCode, 1) << r.out;
    EXPECT_NE(r.out.find("FAILED: " + (dir / "demo0" / "truth").string() +
                         ": walker_0000.obj, walker_0001.obj, walker_0002.obj and 1 more file "
                         "were not written by a Boneless export"),
              std::string::npos)
        << r.out;
    EXPECT_NE(r.out.find("1 solved, 0 skipped, 1 failed"), std::string::npos) << r.out;
    const CliResult forced = runCli("batch --force " + path.string());
    EXPECT_EQ(forced.exitCode, 0) << forced.out;
    EXPECT_NE(forced.out.find("1 solved, 1 skipped, 0 failed"), std::string::npos) << forced.out;
    const CliResult again = runCli("batch " + path.string());
    EXPECT_EQ(again.exitCode, 0) << again.out;
    EXPECT_NE(again.out.find("0 solved, 2 skipped, 0 failed"), std::string::npos) << again.out;
}

// A file of the sidecar's name that is another program's is not a sidecar that "cannot be read":
// the take fails saying the file is not Boneless's, and is not called a solve to repeat.
TEST(Batch, AnOutHoldingAnotherProgramsJsonOfTheSidecarsNameFailsSayingSo) {
    const fs::path dir = makeLibrary();
    fs::create_directories(dir / "b");
    std::ofstream(dir / "b" / "walker.json") << R"({"notes": "the user's own"})";
    const fs::path path =
        writeManifest(dir, "m.json",
                      {{"defaults", {{"mesh", "walker.obj"}, {"map", "walker.map.json"}}},
                       {"takes", {{{"c3d", "takes/walk_b.c3d"}, {"out", "b"}}}}});
    const CliResult r = runCli("batch " + path.string());
    EXPECT_EQ(r.exitCode, 1) << r.out;
    EXPECT_EQ(r.out.find("solving again"), std::string::npos) << r.out;
    EXPECT_NE(r.out.find(": walker.json was not written by a Boneless export"), std::string::npos)
        << r.out;
    EXPECT_EQ(json::parse(std::ifstream(dir / "b" / "walker.json")).value("notes", ""),
              "the user's own");
}

// The user corrects the map and runs the manifest again: before, every take was skipped, since
// its sidecar said complete, and the frames solved with the wrong map stayed.
TEST(Batch, ATakeWhoseMapMeshOrFileChangedIsSolvedAgainSayingWhich) {
    const fs::path dir = makeLibrary();
    const fs::path manifest = solvedOnce(dir);
    const fs::path sidecar = dir / "out" / "walk_b" / "walker.json";
    EXPECT_TRUE(json::parse(std::ifstream(sidecar))["source_fingerprints"]["map"].is_string());

    json map = json::parse(std::ifstream(dir / "walker.map.json"));
    map["markers"][0]["offset_mm"] = 12.0;
    std::ofstream(dir / "walker.map.json") << map.dump(2);
    CliResult r = runCli("batch " + manifest.string());
    ASSERT_EQ(r.exitCode, 0) << r.out;
    EXPECT_NE(r.out.find("walker.map.json changed since it was solved, solving again"),
              std::string::npos)
        << r.out;
    EXPECT_NE(r.out.find("3 solved, 0 skipped"), std::string::npos) << r.out;
    r = runCli("batch " + manifest.string());  // as solved now: done
    EXPECT_NE(r.out.find("0 solved, 3 skipped"), std::string::npos) << r.out;

    // The same bytes again are the same map; a mesh edited and a take rewritten are not.
    std::ofstream(dir / "walker.obj", std::ios::app) << "# edited\n";
    const fs::path take = dir / "takes" / "walk_a.c3d";
    fs::last_write_time(take, fs::last_write_time(take) + std::chrono::seconds(5));
    r = runCli("batch " + manifest.string());
    ASSERT_EQ(r.exitCode, 0) << r.out;
    EXPECT_NE(r.out.find("walker.obj and walk_a.c3d changed since they were solved"),
              std::string::npos)
        << r.out;
    EXPECT_NE(r.out.find("walk_b.c3d -> " + (dir / "out" / "walk_b").string() +
                         ": walker.obj changed since it was solved"),
              std::string::npos)
        << r.out;
}

// A sidecar from before the fingerprints cannot say its inputs are unchanged.
TEST(Batch, ASidecarThatRecordsNoFingerprintsIsSolvedAgain) {
    const fs::path dir = makeLibrary();
    const fs::path manifest = solvedOnce(dir);
    const fs::path sidecar = dir / "out" / "walk_c" / "walker.json";
    json j = json::parse(std::ifstream(sidecar));
    j.erase("source_fingerprints");
    std::ofstream(sidecar) << j.dump();
    const CliResult r = runCli("batch " + manifest.string());
    ASSERT_EQ(r.exitCode, 0) << r.out;
    EXPECT_NE(r.out.find("its sidecar does not record what its inputs held, solving again"),
              std::string::npos)
        << r.out;
    EXPECT_NE(r.out.find("1 solved, 2 skipped"), std::string::npos) << r.out;
}

// mesh_up came after these sidecars: they were solved with the up guessed, as "auto" is, and
// every take of a library was solved again "from other frames or options".
TEST(Batch, ASidecarFromBeforeMeshUpIsSkippedAsAnAutoOne) {
    const fs::path dir = makeLibrary();
    const fs::path manifest = solvedOnce(dir);
    const fs::path sidecar = dir / "out" / "walk_c" / "walker.json";
    json j = json::parse(std::ifstream(sidecar));
    ASSERT_EQ(j["options"]["mesh_up"], "auto");
    j["options"].erase("mesh_up");
    std::ofstream(sidecar) << j.dump();
    CliResult r = runCli("batch " + manifest.string());
    EXPECT_NE(r.out.find("0 solved, 3 skipped"), std::string::npos) << r.out;
    // A take asked for another up is not the one solved.
    json m = json::parse(std::ifstream(manifest));
    m["defaults"]["mesh_up"] = "+y";
    writeManifest(dir, "m.json", m);
    r = runCli("batch " + manifest.string());
    EXPECT_NE(r.out.find("3 solved, 0 skipped"), std::string::npos) << r.out;
}

// take_units came after these sidecars: they were solved in the file's units, as "file" is.
TEST(Batch, ASidecarFromBeforeTakeUnitsIsSkippedAsAFileOne) {
    const fs::path dir = makeLibrary();
    const fs::path manifest = solvedOnce(dir);
    const fs::path sidecar = dir / "out" / "walk_c" / "walker.json";
    json j = json::parse(std::ifstream(sidecar));
    ASSERT_EQ(j["options"]["take_units"], "file");
    j["options"].erase("take_units");
    std::ofstream(sidecar) << j.dump();
    CliResult r = runCli("batch " + manifest.string());
    EXPECT_NE(r.out.find("0 solved, 3 skipped"), std::string::npos) << r.out;
    // Takes asked for other units are not the ones solved.
    json m = json::parse(std::ifstream(manifest));
    m["defaults"]["take_units"] = "mm";
    writeManifest(dir, "m.json", m);
    r = runCli("batch " + manifest.string());
    EXPECT_NE(r.out.find("3 solved, 0 skipped"), std::string::npos) << r.out;
}

// The morning's reader had "2 of 3 takes failed" and had to search the log for which.
TEST(Batch, TheLastLineOfAFailedRunNamesTheTakesThatFailed) {
    const fs::path dir = makeLibrary();
    std::ofstream(dir / "takes" / "broken.c3d") << "not a c3d file";
    std::ofstream(dir / "takes" / "empty.c3d");
    const json manifest = {
        {"defaults", {{"mesh", "walker.obj"}, {"map", "walker.map.json"}, {"format", "pc2"}}},
        {"takes",
         {{{"c3d", "takes/broken.c3d"}, {"out", "out/broken"}},
          {{"c3d", "takes/walk_a.c3d"}, {"out", "out/walk_a"}},
          {{"c3d", "takes/empty.c3d"}, {"out", "out/empty"}}}}};
    const CliResult r = runCli("batch " + writeManifest(dir, "m.json", manifest).string());
    EXPECT_EQ(r.exitCode, 1) << r.out;
    EXPECT_NE(r.out.find("2 of 3 takes failed: " + (dir / "takes" / "broken.c3d").string() + ", " +
                         (dir / "takes" / "empty.c3d").string()),
              std::string::npos)
        << r.out;
}

TEST(Batch, AFailingTakeDoesNotStopTheOthersButFailsTheRun) {
    const fs::path dir = makeLibrary();
    std::ofstream(dir / "takes" / "broken.c3d") << "not a c3d file";
    const json manifest = {
        {"defaults", {{"mesh", "walker.obj"}, {"map", "walker.map.json"}, {"format", "pc2"}}},
        {"takes",
         {{{"c3d", "takes/broken.c3d"}, {"out", "out/broken"}},
          {{"c3d", "takes/walk_a.c3d"}, {"out", "out/walk_a"}}}}};
    const CliResult r = runCli("batch " + writeManifest(dir, "m.json", manifest).string());
    EXPECT_EQ(r.exitCode, 1) << r.out;
    EXPECT_NE(r.out.find("FAILED: "), std::string::npos) << r.out;
    EXPECT_NE(r.out.find("broken.c3d"), std::string::npos) << r.out;
    EXPECT_NE(r.out.find("2 of 2 takes in shard 1/1: 1 solved, 0 skipped, 1 failed"),
              std::string::npos)
        << r.out;
    EXPECT_TRUE(fs::exists(dir / "out" / "walk_a" / "walker.pc2"));
}

TEST(Batch, AManifestMistakeNamesTheFileAndTheEntry) {
    const fs::path dir = freshTestDir("bad");
    const json manifest = {{"takes", {{{"c3d", "a.c3d"}, {"mesh", "m.obj"}, {"ouput", "x"}}}}};
    const CliResult r = runCli("batch " + writeManifest(dir, "m.json", manifest).string());
    EXPECT_EQ(r.exitCode, 1) << r.out;
    EXPECT_NE(r.out.find("m.json: takes[0]: unknown key \"ouput\""), std::string::npos) << r.out;
    // Quoted as flags and option keys are ("fill_gaps_s" must be ...), not 'so'.
    const std::pair<json, std::string> quoted[] = {
        {{{"takes", {{{"c3d", "a.c3d"}, {"mesh", "m.obj"}, {"map", "x"}}}}},
         "m.json: takes[0]: \"out\" is missing\n"},
        {{{"takes", {{{"c3d", "a.c3d"}, {"mesh", 3}}}}},
         "m.json: takes[0]: \"mesh\" has the wrong type (3): it wants a string\n"},
        {{{"takes",
           {{{"c3d", "a.c3d"},
             {"mesh", "m.obj"},
             {"out", "x"},
             {"write_calibrated_rest", "yes"}}}}},
         "m.json: takes[0]: \"write_calibrated_rest\" has the wrong type (\"yes\"): it wants true "
         "or false\n"},
        // As a path flag refuses "": it named the manifest's folder, and solved into it.
        {{{"takes", {{{"c3d", "a.c3d"}, {"mesh", "m.obj"}, {"map", "x"}, {"out", ""}}}}},
         "m.json: takes[0]: \"out\" must be a path, got \"\"\n"},
        {{{"take", json::array()}},
         "m.json: unknown key \"take\" (expected defaults, takes, folders)\n"}};
    for (const auto& [wrong, message] : quoted) {
        const CliResult q = runCli("batch " + writeManifest(dir, "m.json", wrong).string());
        EXPECT_EQ(q.exitCode, 1) << q.out;
        EXPECT_NE(q.out.find(message), std::string::npos) << q.out;
    }
    EXPECT_NE(runCli("batch " + (dir / "m.json").string() + " --shard 3/2").out.find("--shard"),
              std::string::npos);
    // An unset job-array variable: every task ran every take.
    const CliResult empty = runCli("batch " + (dir / "m.json").string() + " --shard ''");
    EXPECT_EQ(empty.exitCode, 1) << empty.out;
    EXPECT_NE(empty.out.find("--shard expects I/N with 1 <= I <= N, got \"\""), std::string::npos)
        << empty.out;
}

// Options go under their JSON keys (core's table), checked before anything is solved; the dashed
// keys and old names of the first manifests still read.
TEST(Batch, AnOptionOutOfItsRangeIsNamedBeforeAnythingIsSolved) {
    const fs::path dir = freshTestDir("bad-option");
    const json manifest = {{"defaults", {{"fill_gaps_s", -1}}},
                           {"takes", {{{"c3d", "a.c3d"}, {"mesh", "m.obj"}, {"map", "x"}}}}};
    const CliResult r = runCli("batch " + writeManifest(dir, "m.json", manifest).string());
    EXPECT_EQ(r.exitCode, 1) << r.out;
    EXPECT_NE(r.out.find("m.json: defaults: \"fill_gaps_s\" must be a number (s) from 0 to 3600"),
              std::string::npos)
        << r.out;
}

// A key the exact solver alone reads ("exact only" in docs/options.md), given without "solver":
// "exact", changed nothing yet was recorded, and a take was solved again whenever it changed. It is
// refused as solve's flag is, named as written, before anything is solved; with the exact solver
// it is taken.
TEST(Batch, AnExactOnlyKeyWithoutTheExactSolverIsNamedBeforeAnythingIsSolved) {
    const fs::path dir = makeLibrary();
    const json take = {{"c3d", "takes/walk_a.c3d"},
                       {"mesh", "walker.obj"},
                       {"map", "walker.map.json"},
                       {"format", "pc2"}};
    json first = take, second = take;
    first["out"] = "first";
    second["out"] = "second";
    second["rigidity"] = 0.5;
    json manifest = {{"defaults", {{"max_iterations", 4}}}, {"takes", {first, second}}};
    CliResult r = runCli("batch " + writeManifest(dir, "m.json", manifest).string());
    EXPECT_EQ(r.exitCode, 1) << r.out;
    EXPECT_NE(
        r.out.find("m.json: takes[0]: \"max_iterations\" 4 (from defaults) changes nothing "
                   "with the local-global solver: it applies to \"solver\": \"exact\" only\n"),
        std::string::npos)
        << r.out;
    manifest["takes"][0]["solver"] = "exact";
    r = runCli("batch " + writeManifest(dir, "m.json", manifest).string());
    EXPECT_EQ(r.exitCode, 1) << r.out;
    EXPECT_NE(r.out.find("m.json: takes[1]: \"rigidity\" 0.5 and \"max_iterations\" 4 (from "
                         "defaults) change nothing"),
              std::string::npos)
        << r.out;
    EXPECT_FALSE(fs::exists(dir / "first")) << r.out;
    manifest["defaults"]["solver"] = "exact";
    r = runCli("batch " + writeManifest(dir, "m.json", manifest).string());
    ASSERT_EQ(r.exitCode, 0) << r.out;
    const json options = json::parse(std::ifstream(dir / "second" / "walker.json"))["options"];
    EXPECT_EQ(options["fold_guard"], 0.5);
    EXPECT_EQ(options["max_iterations"], 4);
}

TEST(Batch, TheOldDashedKeysOfAManifestStillRead) {
    const fs::path dir = makeLibrary();
    const json manifest = {{"defaults", {{"fill-gaps", 0.1}, {"weight", 60}, {"lowpass", 9}}},
                           {"takes",
                            {{{"c3d", "takes/walk_a.c3d"},
                              {"mesh", "walker.obj"},
                              {"map", "walker.map.json"},
                              {"calibration-frame", 2},
                              {"write-calibrated-rest", true},
                              {"out", "old"}}}}};
    const CliResult r = runCli("batch " + writeManifest(dir, "old.json", manifest).string());
    ASSERT_EQ(r.exitCode, 0) << r.out;
    const json options = json::parse(std::ifstream(dir / "old" / "walker.json"))["options"];
    EXPECT_EQ(options["fill_gaps_s"], 0.1);
    EXPECT_EQ(options["marker_weight"], 60.0);
    EXPECT_EQ(options["low_pass_hz"], 9.0);
    EXPECT_EQ(options["calibration_frame"], 2);
    EXPECT_TRUE(fs::exists(dir / "old" / "walker_calibrated_rest.obj"));
}

TEST(Batch, SaysOnceWhatTheTakesSharedMeshLacks) {
    const fs::path dir = makeLibrary();
    std::ostringstream obj;
    obj << std::ifstream(dir / "walker.obj").rdbuf();
    std::ofstream(dir / "walker.obj") << "mtllib gone.mtl\nusemtl skin\n" << obj.str();
    // The first take fails after the mesh is read: its note is still said, and only once.
    std::ofstream(dir / "takes" / "walk_a.c3d", std::ios::binary | std::ios::trunc) << "not a take";
    const fs::path manifest = writeManifest(dir, "m.json", folderManifest("out"));
    const CliResult r = runCli("batch " + manifest.string());
    EXPECT_EQ(r.exitCode, 1) << r.out;
    EXPECT_NE(r.out.find("2 solved, 0 skipped, 1 failed"), std::string::npos) << r.out;
    const std::string note = "gone.mtl: material library cannot be read";
    const size_t first = r.out.find(note);
    EXPECT_NE(first, std::string::npos) << r.out;
    EXPECT_LT(first, r.out.find("walk_b")) << r.out;  // under the take that failed
    EXPECT_EQ(r.out.find(note, first + 1), std::string::npos) << r.out;  // three takes, one note
}

// A take cut short solves the frames it holds, but the log says so under its entry, naming the
// file: before, the run reported success and only `inspect` told.
TEST(Batch, SaysUnderItsEntryThatATakeIsTruncated) {
    const fs::path dir = makeLibrary();
    const fs::path take = dir / "takes" / "walk_c.c3d";
    fs::resize_file(take, fs::file_size(take) * 2 / 3);
    const CliResult r =
        runCli("batch " + writeManifest(dir, "m.json", folderManifest("out")).string());
    ASSERT_EQ(r.exitCode, 0) << r.out;
    const size_t warning = r.out.find("warning: " + take.string() + ": file is truncated");
    ASSERT_NE(warning, std::string::npos) << r.out;
    EXPECT_GT(warning, r.out.find("walk_c.c3d -> ")) << r.out;
    EXPECT_EQ(r.out.find("walk_a.c3d: file is truncated"), std::string::npos) << r.out;
}

// Every sidecar has "calibrated_rest" (null when none was written): its presence is not the rest.
TEST(Batch, ACalibratedRestAskedForAfterTheTakeWasSolvedIsWritten) {
    const fs::path dir = makeLibrary();
    json manifest = {{"takes",
                      {{{"mesh", "walker.obj"},
                        {"map", "walker.map.json"},
                        {"c3d", "takes/walk_a.c3d"},
                        {"out", "one"},
                        {"format", "pc2"}}}}};
    const fs::path path = writeManifest(dir, "m.json", manifest);
    ASSERT_EQ(runCli("batch " + path.string()).exitCode, 0);
    manifest["takes"][0]["write_calibrated_rest"] = true;
    writeManifest(dir, "m.json", manifest);
    const fs::path rest = dir / "one" / "walker_calibrated_rest.obj";
    CliResult r = runCli("batch " + path.string());
    ASSERT_EQ(r.exitCode, 0) << r.out;
    EXPECT_NE(r.out.find("1 solved, 0 skipped"), std::string::npos) << r.out;
    EXPECT_TRUE(fs::exists(rest));
    r = runCli("batch " + path.string());
    EXPECT_NE(r.out.find("0 solved, 1 skipped"), std::string::npos) << r.out;
    // A rest its sidecar names but that is gone is written again.
    fs::remove(rest);
    r = runCli("batch " + path.string());
    EXPECT_NE(r.out.find("1 solved, 0 skipped"), std::string::npos) << r.out;
    EXPECT_TRUE(fs::exists(rest));
}

// docs/batch.md: resubmitting the same manifest only solves what is missing, however the
// manifest is named and from whichever folder.
TEST(Batch, TheSameManifestNamedByAnotherPathSkipsTheTakesItFinished) {
    const fs::path dir = makeLibrary();
    const fs::path manifest = writeManifest(dir, "m.json", folderManifest("out"));
    const std::string cli = BONELESS_CLI;
    CliResult r = runShell("cd " + dir.string() + " && " + cli + " batch m.json 2>&1");
    ASSERT_EQ(r.exitCode, 0) << r.out;
    EXPECT_NE(r.out.find("3 solved, 0 skipped"), std::string::npos) << r.out;
    for (const std::string& named :
         {manifest.string(), (dir / "takes" / ".." / "m.json").string()}) {
        r = runCli("batch " + named);
        ASSERT_EQ(r.exitCode, 0) << r.out;
        EXPECT_NE(r.out.find("0 solved, 3 skipped"), std::string::npos) << named << "\n" << r.out;
    }
    r = runShell("cd " + dir.parent_path().string() + " && " + cli + " batch " +
                 (dir.filename() / "m.json").string() + " 2>&1");
    EXPECT_NE(r.out.find("0 solved, 3 skipped"), std::string::npos) << r.out;
}

// Before, {"takes": {...}} ended in "internal error: [json.exception.type_error.305]".
TEST(Batch, AManifestOfTheWrongShapeNamesTheFileAndTheKey) {
    const fs::path dir = freshTestDir("shape");
    const std::pair<json, std::string> cases[] = {
        {{{"takes", {{"c3d", "a"}}}}, "m.json: \"takes\" is an array of entries, not an object"},
        {{{"folders", "takes"}}, "m.json: \"folders\" is an array of entries, not a string"},
        {{{"takes", {1}}}, "m.json: takes[0]: an entry is a JSON object"},
        {{{"defaults", json::array()}, {"takes", {{{"c3d", "a"}}}}},
         "m.json: defaults: an entry is a JSON object"}};
    for (const auto& [manifest, message] : cases) {
        const CliResult r = runCli("batch " + writeManifest(dir, "m.json", manifest).string());
        EXPECT_EQ(r.exitCode, 1) << r.out;
        EXPECT_NE(r.out.find(message), std::string::npos) << r.out;
        EXPECT_EQ(r.out.find("internal error"), std::string::npos) << r.out;
    }
}

// docs/batch.md: a bad value is refused naming the manifest and the entry before anything is
// solved. Before, an unknown format or a bad range failed its own entry after the others ran.
TEST(Batch, ABadFormatOrFrameRangeIsNamedBeforeAnythingIsSolved) {
    const fs::path dir = makeLibrary();
    const json good = {{"c3d", "takes/walk_a.c3d"}, {"out", "a"}};
    const std::pair<json, std::string> cases[] = {
        {{{"c3d", "takes/walk_b.c3d"}, {"out", "b"}, {"format", "fbx"}},
         "m.json: takes[1]: unknown format \"fbx\" (expected obj, pc2, mdd, glb)"},
        {{{"c3d", "takes/walk_b.c3d"}, {"out", "b"}, {"frames", "2-4"}},
         "m.json: takes[1]: \"frames\" expects A:B (0-based, not negative, B excluded), got "
         "\"2-4\""}};
    for (const auto& [bad, message] : cases) {
        const json manifest = {{"defaults", {{"mesh", "walker.obj"}, {"map", "walker.map.json"}}},
                               {"takes", {good, bad}}};
        const CliResult r = runCli("batch " + writeManifest(dir, "m.json", manifest).string());
        EXPECT_EQ(r.exitCode, 1) << r.out;
        EXPECT_NE(r.out.find(message), std::string::npos) << r.out;
        EXPECT_FALSE(fs::exists(dir / "a")) << r.out;
    }
}

// A suggested entry still marked for review may sit on a prop or the wrong limb: the run says so,
// once for the map its takes share, and solves anyway (the user may have accepted them).
TEST(Batch, SaysOnceWhichEntriesOfTheSharedMapAreStillMarkedForReview) {
    const fs::path dir = makeLibrary();
    json map = json::parse(std::ifstream(dir / "walker.map.json"));
    for (json& m : map["markers"])
        if (m["label"] == "LFHD" || m["label"] == "RBHD") m["needs_review"] = true;
    std::ofstream(dir / "walker.map.json") << map.dump(2);
    const CliResult r =
        runCli("batch " + writeManifest(dir, "m.json", folderManifest("out")).string());
    ASSERT_EQ(r.exitCode, 0) << r.out;
    EXPECT_NE(r.out.find("3 solved, 0 skipped, 0 failed"), std::string::npos) << r.out;
    const std::string warning = "warning: " + (dir / "walker.map.json").string() +
                                ": 2 suggested entries are still marked for review: LFHD, RBHD";
    const size_t first = r.out.find(warning);
    ASSERT_NE(first, std::string::npos) << r.out;
    EXPECT_EQ(r.out.find(warning, first + 1), std::string::npos) << r.out;  // three takes, once
}

// sessA/walk.c3d and sessB/walk.c3d with one "out" both said solved while the second overwrote the
// first, and every run solved both again.
TEST(Batch, TwoEntriesThatWriteTheSameFilesAreRefusedBeforeAnythingIsSolved) {
    const fs::path dir = makeLibrary();
    for (const char* session : {"sessA", "sessB"}) {
        fs::create_directories(dir / session);
        fs::copy_file(dir / "takes" / "walk_a.c3d", dir / session / "walk.c3d");
    }
    const json defaults = {{"mesh", "walker.obj"}, {"map", "walker.map.json"}};
    const fs::path takes =
        writeManifest(dir, "takes.json",
                      {{"defaults", defaults},
                       {"takes",
                        {{{"c3d", "sessA/walk.c3d"}, {"out", "out"}},
                         {{"c3d", "sessB/walk.c3d"}, {"out", "out/../out"}, {"format", "pc2"}}}}});
    const CliResult r = runCli("batch " + takes.string());
    EXPECT_EQ(r.exitCode, 1) << r.out;
    EXPECT_NE(r.out.find(takes.string() + ": takes[0] (" + (dir / "sessA" / "walk.c3d").string() +
                         ") and takes[1] (" + (dir / "sessB" / "walk.c3d").string() +
                         ") both write " + (dir / "out" / "walker.json").string()),
              std::string::npos)
        << r.out;
    EXPECT_FALSE(fs::exists(dir / "out"));
    // Two folders with one "out" put their takes of the same name in one folder.
    const fs::path folders = writeManifest(
        dir, "folders.json",
        {{"defaults", defaults},
         {"folders", {{{"c3d", "sessA"}, {"out", "out"}}, {{"c3d", "sessB"}, {"out", "out"}}}}});
    const CliResult f = runCli("batch " + folders.string());
    EXPECT_EQ(f.exitCode, 1) << f.out;
    EXPECT_NE(
        f.out.find("folders[0] (" + (dir / "sessA" / "walk.c3d").string() + ") and folders[1] (" +
                   (dir / "sessB" / "walk.c3d").string() + ") both write"),
        std::string::npos)
        << f.out;
    EXPECT_FALSE(fs::exists(dir / "out"));
}

// One entry's sidecar is another entry's map: solving the first replaced the user's map before the
// second read it. The manifest is refused before anything is solved.
TEST(Batch, AnEntryWhoseSidecarWouldReplaceAnotherEntrysMapIsRefusedBeforeAnythingIsSolved) {
    const fs::path dir = makeLibrary();
    fs::create_directories(dir / "maps");
    fs::copy_file(dir / "walker.map.json", dir / "maps" / "walker.json");
    auto readText = [](const fs::path& path) {
        std::ostringstream text;
        text << std::ifstream(path).rdbuf();
        return text.str();
    };
    const std::string before = readText(dir / "maps" / "walker.json");
    const fs::path manifest = writeManifest(
        dir, "takes.json",
        {{"defaults", {{"mesh", "walker.obj"}}},
         {"takes",
          {{{"c3d", "takes/walk_a.c3d"}, {"map", "walker.map.json"}, {"out", "maps"}},
           {{"c3d", "takes/walk_b.c3d"}, {"map", "maps/walker.json"}, {"out", "out"}}}}});
    const CliResult r = runCli("batch " + manifest.string());
    EXPECT_EQ(r.exitCode, 1) << r.out;
    EXPECT_NE(r.out.find("the sidecar of takes[0] (" + (dir / "takes" / "walk_a.c3d").string() +
                         "), " + (dir / "maps" / "walker.json").string() +
                         ", would replace the map of takes[1] (" +
                         (dir / "takes" / "walk_b.c3d").string() + ")"),
              std::string::npos)
        << r.out;
    EXPECT_EQ(readText(dir / "maps" / "walker.json"), before);
    EXPECT_FALSE(fs::exists(dir / "out"));
}

// A take named in Latin-1 ("caf\xe9.c3d") ended the whole run with an internal error; it is
// solved, its sidecar names it read as Latin-1, and the next run finds it finished.
TEST(Batch, ATakeWhoseNameIsNotUtf8IsSolvedAndThenSkippedLikeTheOthers) {
    const fs::path dir = makeLibrary();
    fs::copy_file(dir / "takes" / "walk_a.c3d", dir / "takes" / "caf\xe9.c3d");
    const fs::path manifest = writeManifest(dir, "m.json", folderManifest("out"));
    const CliResult first = runCli("batch " + manifest.string());
    EXPECT_EQ(first.exitCode, 0) << first.out;
    EXPECT_NE(first.out.find("4 of 4 takes in shard 1/1: 4 solved, 0 skipped, 0 failed"),
              std::string::npos)
        << first.out;
    const json sidecar = json::parse(std::ifstream(dir / "out" / "caf\xe9" / "walker.json"));
    EXPECT_EQ(sidecar["source"]["c3d"], (dir / "takes" / "caf\u00e9.c3d").string());
    const CliResult again = runCli("batch " + manifest.string());
    EXPECT_NE(again.out.find("4 of 4 takes in shard 1/1: 0 solved, 4 skipped, 0 failed"),
              std::string::npos)
        << again.out;
}

// A take whose point cache was deleted or cut to nothing was skipped because its sidecar said it
// was complete; so was one with an OBJ frame gone.
TEST(Batch, ATakeWhoseOutputIsMissingOrEmptyIsSolvedAgain) {
    const fs::path dir = makeLibrary();
    json caches = folderManifest("caches");
    caches["defaults"]["format"] = "pc2";
    const fs::path manifest = writeManifest(dir, "caches.json", caches);
    ASSERT_EQ(runCli("batch " + manifest.string()).exitCode, 0);
    fs::remove(dir / "caches" / "walk_a" / "walker.pc2");
    fs::resize_file(dir / "caches" / "walk_b" / "walker.pc2", 0);
    const CliResult again = runCli("batch " + manifest.string());
    ASSERT_EQ(again.exitCode, 0) << again.out;
    EXPECT_NE(again.out.find("walker.pc2 is missing or empty, solving again: 4 frames"),
              std::string::npos)
        << again.out;
    EXPECT_NE(again.out.find("3 of 3 takes in shard 1/1: 2 solved, 1 skipped, 0 failed"),
              std::string::npos)
        << again.out;
    EXPECT_GT(fs::file_size(dir / "caches" / "walk_b" / "walker.pc2"), 0u);

    const fs::path frames = writeManifest(dir, "frames.json", folderManifest("frames"));
    ASSERT_EQ(runCli("batch " + frames.string()).exitCode, 0);
    fs::remove(dir / "frames" / "walk_c" / "walker_0001.obj");
    fs::remove(dir / "frames" / "walk_c" / "walker_0003.obj");
    const CliResult objs = runCli("batch " + frames.string());
    EXPECT_NE(objs.out.find("2 of its files are missing or empty (walker_0001.obj, "
                            "walker_0003.obj), solving again: 6 frames"),
              std::string::npos)
        << objs.out;
    EXPECT_TRUE(fs::exists(dir / "frames" / "walk_c" / "walker_0003.obj"));
}

// SIGTERM, what Slurm, timeout and systemd send, killed the run outright: no sidecar, and the
// MDD's spool file (megabytes) left for good. It stops the take as Ctrl-C does.
TEST(Batch, SigtermStopsTheTakeAsCtrlCDoesLeavingNoSpoolFile) {
    const fs::path dir = freshTestDir("sigterm");
    ASSERT_EQ(runCli("demo --out " + dir.string() + " --frame-count 3000").exitCode, 0);
    const fs::path manifest = writeManifest(dir, "m.json",
                                            {{"takes",
                                              {{{"mesh", "walker.obj"},
                                                {"c3d", "walker.c3d"},
                                                {"map", "walker.map.json"},
                                                {"format", "mdd"},
                                                {"out", "out"}}}}});
    const CliResult r =
        runShell("timeout --preserve-status -s TERM 2 " + std::string(BONELESS_CLI) + " batch " +
                 manifest.string() + " 2>&1");
    EXPECT_EQ(r.exitCode, 143) << r.out;  // 128 + SIGTERM
    EXPECT_NE(r.out.find("stopped by SIGTERM after "), std::string::npos) << r.out;
    for (const auto& e : fs::directory_iterator(dir / "out"))
        EXPECT_EQ(e.path().string().find(".tmp"), std::string::npos) << e.path();
    const json sidecar = json::parse(std::ifstream(dir / "out" / "walker.json"));
    EXPECT_FALSE(sidecar["complete"].get<bool>());
    EXPECT_LT(sidecar["frames_written"].get<int>(), 3000);
    EXPECT_GT(fs::file_size(dir / "out" / "walker.mdd"), 0u);
}

// macOS leaves ._walk_a.c3d (Finder's metadata) beside each take on a shared drive: the scan took
// it, and .hidden.c3d, for takes, while a link to a take that is gone was dropped in silence.
TEST(Batch, AFolderScanLeavesOutDotFilesAndFailsALinkToATakeThatIsGone) {
    const fs::path dir = makeLibrary();
    fs::copy_file(dir / "takes" / "walk_a.c3d", dir / "takes" / ".hidden.c3d");
    std::ofstream(dir / "takes" / "._walk_a.c3d") << "Mac OS X        ATTR";
    fs::create_symlink(dir / "moved" / "walk_d.c3d", dir / "takes" / "walk_d.c3d");
    // A loop of links threw as the folder was listed, and stopped the run before its first take
    // with "the system refused ... is ulimit -v or -u low?": one that is no take is left out, one
    // named as a take fails on its own line.
    fs::create_symlink("cycle.lnk", dir / "takes" / "cycle.lnk");
    fs::create_symlink("walk_e.c3d", dir / "takes" / "walk_e.c3d");
    const fs::path manifest = writeManifest(dir, "m.json", folderManifest("out"));
    const CliResult r = runCli("batch " + manifest.string());
    EXPECT_EQ(r.exitCode, 1) << r.out;
    EXPECT_NE(r.out.find("5 of 5 takes in shard 1/1: 3 solved, 0 skipped, 2 failed"),
              std::string::npos)
        << r.out;
    for (const char* take : {"walk_d", "walk_e"})
        EXPECT_NE(r.out.find((dir / "takes" / (std::string(take) + ".c3d")).string() + " -> " +
                             (dir / "out" / take).string() + ": FAILED: "),
                  std::string::npos)
            << r.out;
    EXPECT_EQ(r.out.find("cycle"), std::string::npos) << r.out;
    EXPECT_EQ(r.out.find("hidden"), std::string::npos) << r.out;
    EXPECT_EQ(r.out.find("._walk_a"), std::string::npos) << r.out;
}

// A glb embeds the OBJ's material library and its textures: before, only the mesh, take and map
// were fingerprinted, so a texture or a Kd changed after the run left the glb skipped, old inside.
TEST(Batch, AGlbWhoseMaterialLibraryOrTextureChangedIsSolvedAgainSayingWhich) {
    const fs::path dir = makeLibrary();
    addTextureCoordinatesAndMaterial((dir / "walker.obj").string(), "walker.mtl", "skin");
    std::ofstream(dir / "walker.mtl") << "newmtl skin\nKd 0.8 0.6 0.5\nmap_Kd tex/skin.png\n";
    fs::create_directories(dir / "tex");
    std::ofstream(dir / "tex" / "skin.png", std::ios::binary) << twoByTwoPng();
    const json entry = {{"mesh", "walker.obj"}, {"map", "walker.map.json"}};
    json glb = entry, pc2 = entry;
    glb.update({{"c3d", "takes/walk_a.c3d"}, {"out", "glb"}, {"format", "glb"}});
    pc2.update({{"c3d", "takes/walk_b.c3d"}, {"out", "pc2"}, {"format", "pc2"}});
    const fs::path manifest = writeManifest(dir, "m.json", {{"takes", {glb, pc2}}});
    ASSERT_EQ(runCli("batch " + manifest.string()).exitCode, 0);
    auto bytes = [](const fs::path& path) {
        std::ostringstream text;
        text << std::ifstream(path, std::ios::binary).rdbuf();
        return text.str();
    };
    const std::string before = bytes(dir / "glb" / "walker.glb");

    // Another image: the glb now embeds it; a point cache embeds no texture and stays done.
    std::ofstream(dir / "tex" / "skin.png", std::ios::binary | std::ios::app) << "repainted";
    CliResult r = runCli("batch " + manifest.string());
    ASSERT_EQ(r.exitCode, 0) << r.out;
    EXPECT_NE(r.out.find("skin.png changed since it was solved, solving again"), std::string::npos)
        << r.out;
    EXPECT_NE(r.out.find("1 solved, 1 skipped"), std::string::npos) << r.out;
    EXPECT_NE(bytes(dir / "glb" / "walker.glb"), before);
    r = runCli("batch " + manifest.string());
    EXPECT_NE(r.out.find("0 solved, 2 skipped"), std::string::npos) << r.out;

    std::ofstream(dir / "walker.mtl") << "newmtl skin\nKd 0.2 0.6 0.5\nmap_Kd tex/skin.png\n";
    r = runCli("batch " + manifest.string());
    EXPECT_NE(r.out.find("walker.mtl changed since it was solved, solving again"),
              std::string::npos)
        << r.out;
    fs::remove(dir / "tex" / "skin.png");
    r = runCli("batch " + manifest.string());
    EXPECT_NE(r.out.find("skin.png changed since it was solved, solving again"), std::string::npos)
        << r.out;
    // A texture the library names but that was missing when solved is an input too, once there.
    std::ofstream(dir / "tex" / "skin.png", std::ios::binary) << twoByTwoPng();
    r = runCli("batch " + manifest.string());
    EXPECT_NE(r.out.find("skin.png changed since it was solved, solving again"), std::string::npos)
        << r.out;
    EXPECT_NE(r.out.find("1 solved, 1 skipped"), std::string::npos) << r.out;

    // A glb's sidecar from before cannot say what its materials held.
    const fs::path sidecar = dir / "glb" / "walker.json";
    json j = json::parse(std::ifstream(sidecar));
    EXPECT_EQ(j["source_fingerprints"]["materials"].size(), 2u) << j["source_fingerprints"];
    j["source_fingerprints"].erase("materials");
    std::ofstream(sidecar) << j.dump();
    r = runCli("batch " + manifest.string());
    EXPECT_NE(r.out.find("its sidecar does not record what the glb's material files held, solving "
                         "again"),
              std::string::npos)
        << r.out;
    EXPECT_NE(r.out.find("1 solved, 1 skipped"), std::string::npos) << r.out;
}

// An old name beside today's in one object: the keys were read in alphabetical order, each
// erasing the other, so "weight" beat "marker_weight" and "lowpass" beat "low_pass_hz". Today's
// name wins, as in projects and sidecars; an entry's own key, old or not, still beats the
// defaults'.
TEST(Batch, TodaysOptionNameWinsOverItsOldNameGivenInTheSameEntryOrDefaults) {
    const fs::path dir = makeLibrary();
    const json both = {{"weight", 5}, {"marker_weight", 7}, {"low_pass_hz", 6}, {"lowpass", 0}};
    const json entry = {{"mesh", "walker.obj"}, {"map", "walker.map.json"}, {"format", "pc2"}};
    json own = entry, defaulted = entry, old = entry;
    own.update(both);
    own.update({{"c3d", "takes/walk_a.c3d"}, {"out", "own"}});
    defaulted.update({{"c3d", "takes/walk_b.c3d"}, {"out", "defaulted"}});
    old.update({{"c3d", "takes/walk_c.c3d"}, {"out", "old"}, {"weight", 9}});
    const json defaults = {
        {"weight", 50}, {"marker_weight", 70}, {"low_pass_hz", 8}, {"lowpass", 0}};
    const fs::path manifest =
        writeManifest(dir, "m.json", {{"defaults", defaults}, {"takes", {own, defaulted, old}}});
    const CliResult r = runCli("batch " + manifest.string());
    ASSERT_EQ(r.exitCode, 0) << r.out;
    auto options = [&](const char* out) {
        return json::parse(std::ifstream(dir / out / "walker.json"))["options"];
    };
    EXPECT_EQ(options("own")["marker_weight"], 7.0);
    EXPECT_EQ(options("own")["low_pass_hz"], 6.0);
    EXPECT_EQ(options("defaulted")["marker_weight"], 70.0);
    EXPECT_EQ(options("defaulted")["low_pass_hz"], 8.0);
    EXPECT_EQ(options("old")["marker_weight"], 9.0);
}

// solve recorded its inputs as typed, relative to the folder it ran in: a batch of the same take
// (which names them in full) solved it again, and said nothing of why.
TEST(Batch, ATakeSolvedFromAnyFolderIsSkippedAndOneFromOtherFilesIsSolvedAgainSayingSo) {
    const fs::path dir = makeLibrary();
    const std::string lib = dir.filename().string();
    const CliResult solved =
        runShell("cd " + dir.parent_path().string() + " && " + BONELESS_CLI + " solve --mesh " +
                 lib + "/walker.obj --c3d " + lib + "/takes/walk_a.c3d --map " + lib +
                 "/walker.map.json --out " + lib + "/cliexp --format pc2 --quiet 2>&1");
    ASSERT_EQ(solved.exitCode, 0) << solved.out;
    const fs::path sidecar = dir / "cliexp" / "walker.json";
    json j = json::parse(std::ifstream(sidecar));
    EXPECT_EQ(j["source"]["mesh"], (dir / "walker.obj").string());
    EXPECT_EQ(j["source"]["c3d"], (dir / "takes" / "walk_a.c3d").string());
    const json entry = {{"mesh", "walker.obj"},
                        {"c3d", "takes/walk_a.c3d"},
                        {"map", "walker.map.json"},
                        {"out", "cliexp"},
                        {"format", "pc2"}};
    const fs::path manifest = writeManifest(dir, "m.json", {{"takes", {entry}}});
    CliResult r = runCli("batch " + manifest.string());
    ASSERT_EQ(r.exitCode, 0) << r.out;
    EXPECT_NE(r.out.find("0 solved, 1 skipped"), std::string::npos) << r.out;

    // A sidecar from before, with the paths as typed in another folder, cannot say which files
    // it names (walk.c3d of another session has its size, and a copy its time): it is solved
    // once more, and from then on names them in full.
    j["source"]["c3d"] = lib + "/takes/walk_a.c3d";
    std::ofstream(sidecar) << j.dump();
    r = runCli("batch " + manifest.string());
    EXPECT_NE(r.out.find("its sidecar is from another take (" + lib + "/takes/walk_a.c3d)"),
              std::string::npos)
        << r.out;
    r = runCli("batch " + manifest.string());
    EXPECT_NE(r.out.find("0 solved, 1 skipped"), std::string::npos) << r.out;
    j = json::parse(std::ifstream(sidecar));
    // One naming another mesh is solved again, and the line says so.
    j["source"]["mesh"] = "elsewhere/walker.obj";
    std::ofstream(sidecar) << j.dump();
    r = runCli("batch " + manifest.string());
    EXPECT_NE(r.out.find("its sidecar is from another mesh (elsewhere/walker.obj), solving again"),
              std::string::npos)
        << r.out;
    EXPECT_NE(r.out.find("1 solved, 0 skipped"), std::string::npos) << r.out;
}

// A folder entry with no take (a wrong path, a disk not mounted) said only "the manifest lists no
// take", or nothing when another entry had takes. It is named, with the folder it read.
TEST(Batch, AFolderWithNoTakeIsNamedWithItsPath) {
    const fs::path dir = makeLibrary();
    fs::create_directories(dir / "empty");
    json manifest = folderManifest("out");
    manifest["folders"][0]["c3d"] = "empty";
    CliResult r = runCli("batch " + writeManifest(dir, "none.json", manifest).string());
    EXPECT_EQ(r.exitCode, 1) << r.out;
    const std::string named = "folders[0] (" + (dir / "empty").string() + ") holds no .c3d take";
    EXPECT_NE(r.out.find(named), std::string::npos) << r.out;
    manifest["folders"].push_back(folderManifest("out")["folders"][0]);
    r = runCli("batch " + writeManifest(dir, "some.json", manifest).string());
    EXPECT_EQ(r.exitCode, 0) << r.out;
    EXPECT_NE(r.out.find("warning: " + dir.string() + "/some.json: " + named), std::string::npos)
        << r.out;
    EXPECT_NE(r.out.find("3 of 3 takes in shard 1/1: 3 solved"), std::string::npos) << r.out;
}

// A point cache cut short, a glb cut short or an OBJ frame overwritten was skipped, its sidecar
// saying complete and the file not empty; and the OBJ take, solved again, was refused for want of
// --force: its own damaged frame counted as no Boneless export's.
TEST(Batch, ATakeWhoseOutputIsDamagedIsSolvedAgainWithoutForce) {
    const fs::path dir = makeLibrary();
    json manifest = {{"defaults", {{"mesh", "walker.obj"}, {"map", "walker.map.json"}}},
                     {"takes",
                      {{{"c3d", "takes/walk_a.c3d"}, {"format", "pc2"}, {"out", "pc2"}},
                       {{"c3d", "takes/walk_a.c3d"}, {"format", "mdd"}, {"out", "mdd"}},
                       {{"c3d", "takes/walk_a.c3d"}, {"format", "glb"}, {"out", "glb"}},
                       {{"c3d", "takes/walk_b.c3d"}, {"format", "obj"}, {"out", "obj"}}}}};
    const fs::path path = writeManifest(dir, "m.json", manifest);
    ASSERT_EQ(runCli("batch " + path.string()).exitCode, 0);
    const std::uintmax_t pc2 = fs::file_size(dir / "pc2" / "walker.pc2"),
                         mdd = fs::file_size(dir / "mdd" / "walker.mdd"),
                         glb = fs::file_size(dir / "glb" / "walker.glb");
    fs::resize_file(dir / "pc2" / "walker.pc2", 100);
    fs::resize_file(dir / "mdd" / "walker.mdd", mdd - 12);
    fs::resize_file(dir / "glb" / "walker.glb", glb / 2);
    std::ofstream(dir / "obj" / "walker_0002.obj") << "garbage";
    const CliResult again = runCli("batch " + path.string());
    EXPECT_EQ(again.exitCode, 0) << again.out;
    for (const std::string& line :
         {"walker.pc2 holds 100 bytes where 4 frames need " + std::to_string(pc2) +
              ", solving again: 4 frames",
          "walker.mdd holds " + std::to_string(mdd - 12) + " bytes where 4 frames need " +
              std::to_string(mdd) + ", solving again: 4 frames",
          "walker.glb holds " + std::to_string(glb / 2) + " bytes where its header says " +
              std::to_string(glb) + ", solving again: 4 frames",
          std::string("walker_0002.obj does not start with the \"# Boneless: \" line a solve "
                      "writes, solving again: 5 frames"),
          std::string("4 of 4 takes in shard 1/1: 4 solved, 0 skipped, 0 failed")})
        EXPECT_NE(again.out.find(line), std::string::npos) << line << "\n" << again.out;
    EXPECT_EQ(fs::file_size(dir / "pc2" / "walker.pc2"), pc2);
    const CliResult third = runCli("batch " + path.string());
    EXPECT_NE(third.out.find("4 of 4 takes in shard 1/1: 0 solved, 4 skipped, 0 failed"),
              std::string::npos)
        << third.out;
}

// "[2/3] …/out/walk_a: its sidecar is from another format (obj), solving again: note: …/out/walk_a
// also holds an earlier export's 4 OBJ frames …", and "4 frames in 0.1 s" alone on the next line.
TEST(Batch, ANoteOnAnEarlierExportGoesUnderTheTakesFinishedLine) {
    const fs::path dir = makeLibrary();
    solvedOnce(dir);
    json caches = folderManifest("out");
    caches["defaults"]["format"] = "pc2";
    const fs::path manifest = writeManifest(dir, "caches.json", caches);
    const CliResult r = runCli("batch " + manifest.string());
    ASSERT_EQ(r.exitCode, 0) << r.out;
    const std::string line = (dir / "out" / "walk_a").string() +
                             ": its sidecar is from another format (obj), solving again: 4 frames";
    const std::size_t at = r.out.find(line);
    ASSERT_NE(at, std::string::npos) << r.out;
    EXPECT_NE(r.out.find("\n  note: " + (dir / "out" / "walk_a").string() +
                             " also holds an earlier export's 4 OBJ frames",
                         at),
              std::string::npos)
        << r.out;
}

namespace {

// A point cache of `points` points and `frames` frames whose size is what its own header gives.
void writePc2(const fs::path& file, std::uint32_t points, std::uint32_t frames) {
    std::ofstream out(file, std::ios::binary | std::ios::trunc);
    const float start = 0, rate = 1;
    const std::uint32_t version = 1;
    out.write("POINTCACHE2\0", 12);
    out.write(reinterpret_cast<const char*>(&version), 4);
    out.write(reinterpret_cast<const char*>(&points), 4);
    out.write(reinterpret_cast<const char*>(&start), 4);
    out.write(reinterpret_cast<const char*>(&rate), 4);
    out.write(reinterpret_cast<const char*>(&frames), 4);
    out << std::string(std::size_t(12) * points * frames, '\0');
}

void bigEndian(std::ofstream& out, std::uint32_t word) {
    const char b[4] = {char(word >> 24), char(word >> 16), char(word >> 8), char(word)};
    out.write(b, 4);
}

void writeMdd(const fs::path& file, std::uint32_t points, std::uint32_t frames) {
    std::ofstream out(file, std::ios::binary | std::ios::trunc);
    bigEndian(out, frames);
    bigEndian(out, points);
    out << std::string(std::size_t(4) * frames + std::size_t(12) * points * frames, '\0');
}

}  // namespace

// A cache's size was checked against its own header's point count: a PC2 or MDD of another mesh
// (or one whose header was damaged consistently) passed as complete and the take was skipped.
TEST(Batch, ACacheWhosePointCountIsNotTheMeshsIsSolvedAgainNamingBothCounts) {
    const fs::path dir = makeLibrary();
    json manifest = {{"defaults", {{"mesh", "walker.obj"}, {"map", "walker.map.json"}}},
                     {"takes",
                      {{{"c3d", "takes/walk_a.c3d"}, {"format", "pc2"}, {"out", "pc2"}},
                       {{"c3d", "takes/walk_a.c3d"}, {"format", "mdd"}, {"out", "mdd"}},
                       {{"c3d", "takes/walk_b.c3d"}, {"format", "pc2"}, {"out", "pc2b"}}}}};
    const fs::path path = writeManifest(dir, "m.json", manifest);
    ASSERT_EQ(runCli("batch " + path.string()).exitCode, 0);
    const std::uintmax_t pc2 = fs::file_size(dir / "pc2" / "walker.pc2");
    const int vertices = static_cast<int>((pc2 - 32) / 12 / 4);
    writePc2(dir / "pc2" / "walker.pc2", 100, 4);
    writeMdd(dir / "mdd" / "walker.mdd", 100, 4);
    // The cache is the mesh's, but the sidecar says otherwise: one of the two is not this take's.
    json sidecar = json::parse(std::ifstream(dir / "pc2b" / "walker.json"));
    sidecar["vertices"] = 100;
    std::ofstream(dir / "pc2b" / "walker.json") << sidecar.dump();

    const CliResult again = runCli("batch " + path.string());
    EXPECT_EQ(again.exitCode, 0) << again.out;
    const std::string mesh = "walker.obj has " + std::to_string(vertices) + " vertices";
    for (const std::string& line :
         {"walker.pc2 holds 100 points where " + mesh + ", solving again: 4 frames",
          "walker.mdd holds 100 points where " + mesh + ", solving again: 4 frames",
          "walker.pc2 holds " + std::to_string(vertices) +
              " points where its sidecar says 100, solving again: 5 frames",
          std::string("3 of 3 takes in shard 1/1: 3 solved, 0 skipped, 0 failed")})
        EXPECT_NE(again.out.find(line), std::string::npos) << line << "\n" << again.out;
    EXPECT_EQ(fs::file_size(dir / "pc2" / "walker.pc2"), pc2);
    EXPECT_EQ(json::parse(std::ifstream(dir / "pc2b" / "walker.json")).value("vertices", 0),
              vertices);
    const CliResult third = runCli("batch " + path.string());
    EXPECT_NE(third.out.find("3 of 3 takes in shard 1/1: 0 solved, 3 skipped, 0 failed"),
              std::string::npos)
        << third.out;
}

// A run stopped by Slurm's time limit (SIGTERM) ended its log with the stopped take's line: the
// count of takes solved, skipped or failed before it, which a finished run's last line gives, was
// nowhere.
TEST(Batch, ARunStoppedPartWayStillEndsWithItsSums) {
    const fs::path dir = makeLibrary();
    ASSERT_EQ(runCli("demo --out " + (dir / "long").string() + " --frame-count 3000").exitCode, 0);
    const json finished = {{"mesh", "walker.obj"},
                           {"map", "walker.map.json"},
                           {"c3d", "takes/walk_a.c3d"},
                           {"out", "out/walk_a"}};
    ASSERT_EQ(
        runCli("batch " + writeManifest(dir, "m.json", {{"takes", {finished}}}).string()).exitCode,
        0);
    const json manifest = {{"takes",
                            {finished,
                             {{"mesh", "walker.obj"},
                              {"map", "walker.map.json"},
                              {"c3d", "long/walker.c3d"},
                              {"format", "mdd"},
                              {"out", "out/long"}},
                             {{"mesh", "walker.obj"},
                              {"map", "walker.map.json"},
                              {"c3d", "takes/walk_b.c3d"},
                              {"out", "out/walk_b"}}}}};
    const CliResult r =
        runShell("timeout --preserve-status -s TERM 3 " + std::string(BONELESS_CLI) + " batch " +
                 writeManifest(dir, "m.json", manifest).string() + " 2>&1");
    EXPECT_EQ(r.exitCode, 143) << r.out;
    EXPECT_NE(r.out.find("batch: 3 of 3 takes in shard 1/1: 0 solved, 1 skipped, 0 failed, 1 "
                         "interrupted, 1 not reached\n"),
              std::string::npos)
        << r.out;
}

// A library solved again after its defaults were edited said of every take only "its sidecar is
// from other frames or options": which frames, which option and what it was went unsaid.
TEST(Batch, ATakeSolvedAgainForOtherFramesOrOptionsSaysWhichAndWhatTheyWere) {
    const fs::path dir = makeLibrary();
    json manifest = firstFramesOfWalkC();
    const fs::path path = writeManifest(dir, "m.json", manifest);
    ASSERT_EQ(runCli("batch " + path.string()).exitCode, 0);
    manifest["takes"][0].erase("frames");
    manifest["defaults"]["marker_weight"] = 5;
    writeManifest(dir, "m.json", manifest);
    const CliResult r = runCli("batch " + path.string());
    ASSERT_EQ(r.exitCode, 0) << r.out;
    EXPECT_NE(r.out.find("its sidecar is from other frames or options (frames 0:3, now 0:6; "
                         "marker_weight 100.0, now 5.0), solving again"),
              std::string::npos)
        << r.out;
}

// By position: a job array's tasks take as long as its largest shard, so the shards are even.
// (A hash of each entry's outputs, tried on 1 December 2026, kept a take's shard when the manifest
// changed, but gave these 100 takes 23, 20, 35 and 22.)
TEST(Batch, AHundredTakesSpreadEvenlyOverFourShards) {
    const fs::path dir = freshTestDir("hundred");
    json takes = json::array();
    for (int i = 0; i < 100; ++i) {
        char name[32];
        std::snprintf(name, sizeof name, "walk_%03d", i);
        // Takes that are not there fail at once: only how many each shard has matters here.
        takes.push_back({{"mesh", "walker.obj"},
                         {"map", "walker.map.json"},
                         {"c3d", std::string("takes/") + name + ".c3d"},
                         {"out", std::string("out/") + name}});
    }
    const fs::path manifest = writeManifest(dir, "m.json", {{"takes", takes}});
    int total = 0;
    for (int shard = 1; shard <= 4; ++shard) {
        const CliResult r =
            runCli("batch " + manifest.string() + " --shard " + std::to_string(shard) + "/4");
        const auto at = r.out.find("batch: ");
        ASSERT_NE(at, std::string::npos) << r.out;
        const int mine = std::stoi(r.out.substr(at + 7));
        EXPECT_EQ(mine, 25) << r.out.substr(at);
        total += mine;
    }
    EXPECT_EQ(total, 100);
}

// One rule for the log (the Unix one): each take's line, its result, on stdout; every note and
// warning under it on stderr. The mesh's notes went to stdout while the take's warnings went to
// stderr, so `batch m.json > results.txt` split one take's diagnostics over two places.
TEST(Batch, EveryNoteAndWarningGoesToStderrAndEachTakesLineToStdout) {
    const fs::path dir = makeLibrary();
    std::ostringstream obj;
    obj << std::ifstream(dir / "walker.obj").rdbuf();
    std::ofstream(dir / "walker.obj") << "mtllib gone.mtl\nusemtl skin\n" << obj.str();
    const fs::path take = dir / "takes" / "walk_c.c3d";
    fs::resize_file(take, fs::file_size(take) * 2 / 3);
    const std::string run = std::string(BONELESS_CLI) + " batch " +
                            writeManifest(dir, "m.json", folderManifest("out")).string();
    const CliResult out = runShell(run + " 2>/dev/null");
    fs::remove_all(dir / "out");
    const CliResult err = runShell(run + " 2>&1 >/dev/null");
    ASSERT_EQ(out.exitCode, 0) << out.out;
    ASSERT_EQ(err.exitCode, 0) << err.out;
    EXPECT_NE(out.out.find("walk_a.c3d -> "), std::string::npos) << out.out;
    EXPECT_NE(out.out.find("3 of 3 takes in shard 1/1: 3 solved"), std::string::npos) << out.out;
    EXPECT_EQ(out.out.find("note:"), std::string::npos) << out.out;
    EXPECT_EQ(out.out.find("warning:"), std::string::npos) << out.out;
    EXPECT_NE(err.out.find("note: " + (dir / "walker.obj").string() + ": "), std::string::npos)
        << err.out;
    EXPECT_NE(err.out.find("gone.mtl: material library cannot be read"), std::string::npos)
        << err.out;
    EXPECT_NE(err.out.find("file is truncated"), std::string::npos) << err.out;
    EXPECT_EQ(err.out.find(" -> "), std::string::npos) << err.out;
}

// The mesh's notes are said once each: the first map's "components carry no marker" hid the note
// of a second map of the same mesh, whose marker on one of them leaves one fewer (the notes were
// said once per mesh).
TEST(Batch, EachMapsNoteOfPartsWithoutAMarkerIsSaidOnce) {
    const fs::path dir = makeLibrary();
    std::ostringstream obj;
    obj << std::ifstream(dir / "walker.obj").rdbuf();
    int vertices = 0;
    std::istringstream lines(obj.str());
    for (std::string line; std::getline(lines, line);) vertices += line.rfind("v ", 0) == 0;
    std::ofstream out(dir / "walker.obj");
    out << obj.str();
    for (int t = 0; t < 3; ++t)  // three lone triangles far from the body
        out << "v " << 5 + t << " 0 0\nv " << 5 + t << " 0.1 0\nv " << 5 + t
            << " 0 0.1\nf -3 -2 -1\n";
    out.close();
    json map = json::parse(std::ifstream(dir / "walker.map.json"));
    map["mesh"]["vertices"] = vertices + 9;
    std::ofstream(dir / "walker.map.json") << map.dump(2);
    map["markers"][0]["vertex"] = vertices;  // one marker on the first triangle
    std::ofstream(dir / "other.map.json") << map.dump(2);
    const fs::path path =
        writeManifest(dir, "m.json",
                      {{"defaults", {{"mesh", "walker.obj"}, {"format", "pc2"}}},
                       {"takes",
                        {{{"c3d", "takes/walk_a.c3d"}, {"map", "walker.map.json"}, {"out", "a"}},
                         {{"c3d", "takes/walk_b.c3d"}, {"map", "walker.map.json"}, {"out", "b"}},
                         {{"c3d", "takes/walk_c.c3d"}, {"map", "other.map.json"}, {"out", "c"}}}}});
    const CliResult r = runCli("batch " + path.string());
    ASSERT_EQ(r.exitCode, 0) << r.out;
    const auto count = [&](const std::string& text) {
        int n = 0;
        for (auto at = r.out.find(text); at != std::string::npos; at = r.out.find(text, at + 1))
            ++n;
        return n;
    };
    // Two notes, the two maps' (three and two triangles without a marker), each once.
    EXPECT_EQ(count("no marker: each follows the nearest marked part rigidly"), 2) << r.out;
}

// A map made on group 'body' of an OBJ that holds another group too: batch said "open it with
// --group body", which a manifest cannot take. It names the entry's key.
TEST(Batch, AMapMadeOnAGroupNamesTheManifestKeyToOpenItWith) {
    const fs::path dir = makeLibrary();
    std::ostringstream obj;
    obj << std::ifstream(dir / "walker.obj").rdbuf();
    std::ofstream(dir / "walker.obj")
        << "g body\n"
        << obj.str() << "g helper\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf -3 -2 -1\n";
    json map = json::parse(std::ifstream(dir / "walker.map.json"));
    map["mesh"]["file"] = "walker.obj";
    map["mesh"]["group"] = "body";
    std::ofstream(dir / "walker.map.json") << map.dump(2);
    const json entry = {{"c3d", "takes/walk_a.c3d"},
                        {"mesh", "walker.obj"},
                        {"map", "walker.map.json"},
                        {"out", "out"},
                        {"format", "pc2"}};
    const CliResult r =
        runCli("batch " + writeManifest(dir, "m.json", {{"takes", {entry}}}).string());
    EXPECT_EQ(r.exitCode, 1) << r.out;
    EXPECT_NE(r.out.find("; open it with \"group\": \"body\""), std::string::npos) << r.out;
    EXPECT_EQ(r.out.find("--group"), std::string::npos) << r.out;
    json grouped = entry;
    grouped["group"] = "body";
    EXPECT_EQ(
        runCli("batch " + writeManifest(dir, "g.json", {{"takes", {grouped}}}).string()).exitCode,
        0);
}

// The batch and its take each hold the signals: a SIGINT while the take's solver is prepared stops
// the take before it writes anything (its earlier export stays whole), and the last line sums up.
TEST(Batch, CtrlCWhileATakeIsPreparedStopsItBeforeItWritesAndSumsUp) {
    const fs::path dir = freshTestDir("batch-prepare-stop");
    const fs::path manifest = slowDemoManifest(dir);
    ASSERT_EQ(runCli("batch " + manifest.string()).exitCode, 0);
    fs::last_write_time(dir / "walker.c3d", fs::file_time_type::clock::now());  // solve it again
    const std::string pc2 = (dir / "out" / "walker.pc2").string();
    const auto before = fs::file_size(pc2);
    const CliResult r = runCliAndWhenExists(
        "batch " + manifest.string(), (dir / "out" / ".walker.lock").string(), "kill -INT $pid");
    EXPECT_EQ(r.exitCode, 130) << r.out;
    EXPECT_NE(r.out.find("interrupted before any frame was written"), std::string::npos) << r.out;
    EXPECT_NE(r.out.find("batch: 1 of 1 takes in shard 1/1: 0 solved, 0 skipped, 0 failed, 1 "
                         "interrupted, 0 not reached\n"),
              std::string::npos)
        << r.out;
    EXPECT_EQ(fs::file_size(pc2), before);
    const json sidecar = json::parse(std::ifstream(dir / "out" / "walker.json"));
    EXPECT_TRUE(sidecar["complete"].get<bool>());
}

// The sidecar recorded the map as it was once the solver was prepared, not as it was read: a map
// saved meanwhile was taken for the one solved, and every later run skipped the take.
TEST(Batch, AMapSavedWhileTheTakeIsPreparedIsSolvedByTheNextRun) {
    const fs::path dir = freshTestDir("batch-map-during-prepare");
    const fs::path manifest = slowDemoManifest(dir);
    json map = json::parse(std::ifstream(dir / "walker.map.json"));
    for (auto& m : map["markers"]) m["offset_mm"] = 30;
    const fs::path edited = dir / "edited.json";
    std::ofstream(edited) << map.dump();
    const CliResult r = runCliAndWhenExists(
        "batch " + manifest.string(), (dir / "out" / ".walker.lock").string(),
        "cp '" + edited.string() + "' '" + (dir / "walker.map.json").string() + "'");
    ASSERT_EQ(r.exitCode, 0) << r.out;
    const CliResult again = runCli("batch " + manifest.string());
    EXPECT_NE(again.out.find("1 solved, 0 skipped"), std::string::npos) << again.out;
}
