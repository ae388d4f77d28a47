#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>

#include "CliRunner.h"

using namespace boneless::testing;
namespace fs = std::filesystem;

namespace {

std::string contentsOf(const fs::path& path) {
    std::ifstream in(path, std::ios::binary);
    return {std::istreambuf_iterator<char>(in), {}};
}

}  // namespace

// Before, a second demo into the folder replaced the map the user had edited there without a
// word. The same demo again replaces its files by the same bytes; one that would change a file
// is refused, naming it, until --force.
TEST(DemoCommand, AFileItWouldChangeIsReplacedOnlyWithForce) {
    const fs::path dir = freshTestDir("demo-again");
    const std::string demo = "demo --out " + dir.string();
    ASSERT_EQ(runCli(demo + " --frame-count 3").exitCode, 0);
    const CliResult same = runCli(demo + " --frame-count 3");
    EXPECT_EQ(same.exitCode, 0) << same.out;
    const std::string written = contentsOf(dir / "walker.map.json");
    std::ofstream(dir / "walker.map.json", std::ios::app) << " ";
    const std::string edited = written + " ";
    const CliResult refused = runCli(demo + " --frame-count 3");
    EXPECT_EQ(refused.exitCode, 1) << refused.out;
    EXPECT_NE(
        refused.out.find(dir.string() + ": walker.map.json differs from what this demo "
                                        "writes (edited, or written with other --frame-count, "
                                        "--offset-mm or --detail); nothing was written: "
                                        "give --force to replace it, or another --out\n"),
        std::string::npos)
        << refused.out;
    EXPECT_TRUE(contentsOf(dir / "walker.map.json") == edited) << "the edited map was replaced";
    // A longer take: its C3D differs too; its first frames of truth do not.
    const CliResult longer = runCli(demo + " --frame-count 4");
    EXPECT_EQ(longer.exitCode, 1) << longer.out;
    EXPECT_NE(longer.out.find(": walker.map.json, walker.c3d differ from what this demo writes"),
              std::string::npos)
        << longer.out;
    EXPECT_FALSE(fs::exists(dir / "truth" / "walker_0003.obj"));
    const CliResult forced = runCli(demo + " --frame-count 3 --force");
    EXPECT_EQ(forced.exitCode, 0) << forced.out;
    EXPECT_TRUE(contentsOf(dir / "walker.map.json") == written) << "the map was kept";
    // A frame of truth past the count (the user's, or a longer demo's) is removed by the write:
    // until 2 December 2026 without --force, and without a word.
    std::ofstream(dir / "truth" / "walker_0100.obj") << "user data\n";
    const CliResult past = runCli(demo + " --frame-count 3");
    EXPECT_EQ(past.exitCode, 1) << past.out;
    EXPECT_NE(past.out.find(": truth/walker_0100.obj differs from what this demo writes"),
              std::string::npos)
        << past.out;
    EXPECT_EQ(contentsOf(dir / "truth" / "walker_0100.obj"), "user data\n");
    EXPECT_EQ(runCli(demo + " --frame-count 3 --force").exitCode, 0);
    EXPECT_FALSE(fs::exists(dir / "truth" / "walker_0100.obj"));
}

// Before, the demo made every frame before writing the first: 100,000 frames at detail 1 (8 GB of
// poses) passed the disk check, ran out of memory and left an empty truth/. Now each frame is
// written as it is made. The demo needs some 220 MB of address space; under 300 MB, 2,000 frames
// (160 MB of poses) ran out.
TEST(DemoCommand, ATakeLongerThanMemoryCouldHoldIsWrittenFrameByFrame) {
    const fs::path dir = freshTestDir("demo-long");
    const CliResult r = runShell("ulimit -v 300000; timeout 120 " + std::string(BONELESS_CLI) +
                                 " demo --out " + dir.string() + " --frame-count 2000 2>&1");
    EXPECT_EQ(r.exitCode, 0) << r.out;
    EXPECT_NE(r.out.find("walker.c3d (39 markers, 2000 frames at 30 Hz)"), std::string::npos)
        << r.out;
    EXPECT_TRUE(fs::exists(dir / "truth" / "walker_1999.obj"));
    fs::remove_all(dir);  // 600 MB
}

// solve --help gives each option's default ("[0.2]"); demo's gave none of 60 frames, detail 1 and
// 10 mm, nor eval's of its method, drop and seed, nor solve's of --format. Each is given so.
TEST(DemoCommand, TheHelpGivesEachDefaultAsSolvesDoes) {
    const std::pair<std::string, std::string> helped[] = {
        {"demo", "How many frames the take has (1 to 100000) [60]\n"},
        {"demo", "How far the markers sit off the skin (0 to 100) [10.0]\n"},
        {"demo", "(1 = 6,848 faces) [1]\n"},
        {"eval", "boneless, arap, or both (side by side) [\"boneless\"]\n"},
        {"eval", "Percentage of markers missing in each frame (seeded) [0.0]\n"},
        {"eval", "Seed for --drop [1]\n"},
        {"map suggest", "how near counts as landing (0.1 to 1000) [30.0]\n"},
        {"solve", "longer gaps stay missing; 0 = off (s) [0.2]\n"},
        {"solve", "(Blender, Unity, web viewers) [\"obj\"]\n"}};
    for (const auto& [command, line] : helped) {
        const CliResult r = runCli(command + " --help");
        EXPECT_EQ(r.exitCode, 0) << r.out;
        EXPECT_NE(r.out.find(line), std::string::npos) << command << ": " << r.out;
    }
}

// Under ulimit -v 150000 the demo wrote every file and printed its line, then spun at full CPU
// for ever: exiting, OpenBLAS joined its worker thread, which retries its 128 MB buffer until it
// gets it. solve did the same after writing its frames. Both end at once now, having done their
// work (0) or run out of memory saying so (3), whichever the limit allows (the worker and the
// program race for the address space).
TEST(DemoCommand, UnderATightAddressSpaceLimitTheDemoAndASolveEndPromptly) {
    const fs::path dir = freshTestDir("demo-tight");
    ASSERT_EQ(runCli("demo --frame-count 3 --out " + (dir / "made").string()).exitCode, 0);
    const fs::path made = dir / "made";
    const std::string solve = "solve --quiet --mesh " + (made / "walker.obj").string() + " --c3d " +
                              (made / "walker.c3d").string() + " --map " +
                              (made / "walker.map.json").string() + " --out " +
                              (dir / "solved").string();
    for (const std::string& command :
         {"demo --frame-count 3 --out " + (dir / "demo").string(), solve})
        for (const char* limit : {"150000", "170000"}) {
            const CliResult r = runShell("ulimit -v " + std::string(limit) + "; timeout 20 " +
                                         std::string(BONELESS_CLI) + " " + command + " 2>&1");
            ASSERT_NE(r.exitCode, 124) << limit << " " << command << ": " << r.out;  // the timeout
            const bool saidSo = r.out.find("out of memory") != std::string::npos ||
                                r.out.find("the system refused") != std::string::npos;
            // The solve's memory estimate refuses such a limit up front, naming the mesh.
            const bool refused =
                r.exitCode == 1 && r.out.find("would need about") != std::string::npos;
            EXPECT_TRUE(r.exitCode == 0 || (r.exitCode == 3 && saidSo) || refused)
                << limit << " " << command << ": " << r.exitCode << " " << r.out;
        }
}

// demo --force with fewer frames than the demo there left that one's truth past the new count
// (truth/walker_0004.obj of 5 after a demo of 3), which a tool reading truth/ by pattern plays as
// the take's. They are removed; files the demo does not name so are the user's and stay.
TEST(DemoCommand, AShorterDemoForcedOverALongerOneLeavesNoTruthPastItsFrames) {
    const fs::path dir = freshTestDir("demo-shorter");
    const std::string demo = "demo --out " + dir.string();
    ASSERT_EQ(runCli(demo + " --frame-count 5").exitCode, 0);
    for (const char* theirs : {"walker_0004.obj.bak", "walker_04.obj", "other_0004.obj"})
        std::ofstream(dir / "truth" / theirs) << "mine\n";
    const CliResult r = runCli(demo + " --frame-count 3 --force");
    ASSERT_EQ(r.exitCode, 0) << r.out;
    EXPECT_TRUE(fs::exists(dir / "truth" / "walker_0002.obj"));
    EXPECT_FALSE(fs::exists(dir / "truth" / "walker_0003.obj"));
    EXPECT_FALSE(fs::exists(dir / "truth" / "walker_0004.obj"));
    for (const char* theirs : {"walker_0004.obj.bak", "walker_04.obj", "other_0004.obj"})
        EXPECT_TRUE(fs::exists(dir / "truth" / theirs)) << theirs;
}

// demo's --frames was a count of frames, where solve, eval and batch read --frames as a range A:B:
// "demo --frames 0:30" was refused as no whole number, and "solve --frames 30" as no range. The
// count is --frame-count; the old name is refused, saying the new one, and writes nothing.
TEST(DemoCommand, TheOldFramesFlagIsRefusedNamingFrameCount) {
    const fs::path dir = freshTestDir("demo-frame-count");
    const CliResult old = runCli("demo --out " + (dir / "old").string() + " --frames 3");
    EXPECT_EQ(old.exitCode, 1) << old.out;
    EXPECT_NE(old.out.find("not expected"), std::string::npos) << old.out;
    EXPECT_NE(old.out.find("--frames was renamed --frame-count\n"), std::string::npos) << old.out;
    EXPECT_FALSE(fs::exists(dir / "old"));
    const CliResult r = runCli("demo --out " + (dir / "new").string() + " --frame-count 3");
    EXPECT_EQ(r.exitCode, 0) << r.out;
    EXPECT_NE(r.out.find("walker.c3d (39 markers, 3 frames at 30 Hz)"), std::string::npos) << r.out;
    const CliResult help = runCli("demo --help");
    EXPECT_NE(help.out.find("--frame-count"), std::string::npos) << help.out;
    EXPECT_EQ(help.out.find("--frames "), std::string::npos) << help.out;
}
