#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <regex>
#include <set>
#include <string>

#include "CliRunner.h"
#include "boneless/TakeOptionsJson.h"

using namespace boneless;
using namespace boneless::testing;
namespace fs = std::filesystem;

namespace {

// The long flags a command's --help lists, as JSON keys ("fill_gaps_s" for --fill-gaps-s).
std::set<std::string> flagKeys(const std::string& command) {
    const CliResult r = runCli(command + " --help");
    EXPECT_EQ(r.exitCode, 0) << r.out;
    std::set<std::string> keys;
    const std::regex flag("(^|[ ,])--([a-z][a-z0-9-]*)");
    for (auto it = std::sregex_iterator(r.out.begin(), r.out.end(), flag);
         it != std::sregex_iterator(); ++it) {
        std::string key = (*it)[2];
        std::replace(key.begin(), key.end(), '-', '_');
        keys.insert(key);
    }
    return keys;
}

}  // namespace

// One name per option: `solve`'s flags are core's table (TakeOptionsJson) keys, with '-' for '_',
// or the paths and output choices a batch manifest names the same way (and --quiet, and --force,
// a flag of batch too); every option of the table is a flag of solve, and the solver's own are
// flags of eval.
TEST(OptionFlags, EverySolveFlagIsNamedAsItsJsonKey) {
    const std::set<std::string> jobKeys = {"mesh",  "group",  "c3d",    "map",
                                           "out",   "format", "frames", "write_calibrated_rest",
                                           "quiet", "force",  "help"};
    const std::set<std::string> solve = flagKeys("solve");
    for (const std::string& key : solve) {
        const TakeOption* option = findTakeOption(key);
        EXPECT_TRUE(jobKeys.count(key) || (option && option->key == key))
            << "--" << key << " is neither an option of the table nor a path or output key";
    }
    const std::set<std::string> eval = flagKeys("eval");
    for (const TakeOption& o : takeOptions()) {
        EXPECT_TRUE(solve.count(o.key)) << optionFlag(o) << " is missing from solve";
        EXPECT_EQ(eval.count(o.key), o.solver ? 1u : 0u) << optionFlag(o) << " on eval";
    }
}

// A flag's value is checked as the JSON reader checks it, with the same words.
TEST(OptionFlags, ABadFlagValueIsRefusedAsTheJsonReaderRefusesIt) {
    const CliResult r =
        runCli("solve --mesh m.obj --c3d t.c3d --map m.json --out o --fill-gaps-s -1");
    EXPECT_NE(r.exitCode, 0);
    EXPECT_NE(r.out.find("--fill-gaps-s"), std::string::npos) << r.out;
    EXPECT_NE(r.out.find("must be a number (s) from 0 to 3600, got -1"), std::string::npos)
        << r.out;
    const CliResult e = runCli("eval --sequence x --markers 3 --solver fast");
    EXPECT_NE(e.exitCode, 0);
    EXPECT_NE(e.out.find("must be one of local-global, exact, got \"fast\""), std::string::npos)
        << e.out;
}

// A flag's number is echoed as typed, as the other flags' checks echo it (--offset-mm nan: "got
// nan"). Through JSON, nan and inf read "got null", and -1 "got -1.0".
TEST(OptionFlags, ABadNumberIsEchoedAsTyped) {
    const std::string solve = "solve --mesh m.obj --c3d t.c3d --map m.json --out o ";
    for (const char* typed : {"nan", "inf", "-1", "0"}) {
        const CliResult r = runCli(solve + "--marker-weight " + typed);
        EXPECT_EQ(r.exitCode, 1) << typed;
        EXPECT_NE(r.out.find("--marker-weight: must be a number from 1e-09 to 1e+09, got " +
                             std::string(typed) + "\n"),
                  std::string::npos)
            << r.out;
    }
    const CliResult frame = runCli(solve + "--calibration-frame nan");
    EXPECT_NE(frame.out.find("must be a whole number from -1 to 1e+09, got nan\n"),
              std::string::npos)
        << frame.out;
}

// strtod reads hexadecimal: "--max-iterations 0x10" solved with 16 steps, and CLI11 reads a
// leading zero as octal: "demo --frame-count 010" wrote 8 frames. Numbers are decimal, as in JSON;
// anything else is refused as the other words that are no number are.
TEST(OptionFlags, ANumberInHexadecimalOrOctalIsRefused) {
    const std::string solve = "solve --mesh m.obj --c3d t.c3d --map m.json --out o ";
    for (const char* typed : {"0x10", "010", "0x1p4"}) {
        const CliResult r = runCli(solve + "--max-iterations " + typed);
        EXPECT_EQ(r.exitCode, 1) << typed;
        EXPECT_NE(r.out.find("--max-iterations: must be a whole number from 1 to 10000, got \"" +
                             std::string(typed) + "\"\n"),
                  std::string::npos)
            << r.out;
    }
    const fs::path dir = freshTestDir("demo-octal");
    for (const char* typed : {"010", "0x10"}) {
        const CliResult r =
            runCli("demo --out " + (dir / "x").string() + " --frame-count " + typed);
        EXPECT_EQ(r.exitCode, 1) << typed;
        EXPECT_NE(r.out.find("--frame-count: must be a whole number from 1 to 100000, got \"" +
                             std::string(typed) + "\"\n"),
                  std::string::npos)
            << r.out;
        EXPECT_FALSE(fs::exists(dir / "x")) << typed;
    }
}

// "--fill-gaps-s 1e-400" was refused as a word, `got "1e-400"`, and with a range that holds it:
// it is a number, too close to 0 for a double. It is echoed as a number, saying so.
TEST(OptionFlags, ANumberThatUnderflowsIsEchoedAsANumberSayingSo) {
    const std::string note =
        ", too close to 0 to be held (it underflows): give 0 or at least "
        "1e-307\n";
    const CliResult r =
        runCli("solve --mesh m.obj --c3d t.c3d --map m.json --out o --fill-gaps-s 1e-400");
    EXPECT_EQ(r.exitCode, 1) << r.out;
    EXPECT_NE(r.out.find("--fill-gaps-s: must be a number (s) from 0 to 3600, got 1e-400" + note),
              std::string::npos)
        << r.out;
    const fs::path dir = freshTestDir("demo-underflow");
    const CliResult demo = runCli("demo --out " + dir.string() + " --offset-mm -1e-400");
    EXPECT_EQ(demo.exitCode, 1) << demo.out;
    EXPECT_NE(demo.out.find("--offset-mm: must be a number from 0 to 100, got -1e-400" + note),
              std::string::npos)
        << demo.out;
}

// A bad --frames or --shard was quoted 'so', where a bad choice is quoted "so".
TEST(OptionFlags, ABadRangeIsQuotedAsABadChoiceIs) {
    const std::string solve = "solve --mesh m.obj --c3d t.c3d --map m.json --out o ";
    const std::pair<std::string, std::string> refused[] = {
        {solve + "--solver fast", "--solver: must be one of local-global, exact, got \"fast\"\n"},
        {solve + "--frames 0-10",
         "--frames expects A:B (0-based, not negative, B excluded), got \"0-10\"\n"},
        {"batch m.json --shard 3/2", "--shard expects I/N with 1 <= I <= N, got \"3/2\"\n"},
        // Numbers are decimal digits alone, in a range or a shard as in any flag: sscanf and
        // stoi had read these as 1/3, 2/3 and 2:5.
        {"batch m.json --shard 01/3", "--shard expects I/N with 1 <= I <= N, got \"01/3\"\n"},
        {"batch m.json --shard \" 2/3\"", "--shard expects I/N with 1 <= I <= N, got \" 2/3\"\n"},
        {solve + "--frames +2:5",
         "--frames expects A:B (0-based, not negative, B excluded), got \"+2:5\"\n"}};
    for (const auto& [arguments, message] : refused) {
        const CliResult r = runCli(arguments);
        EXPECT_EQ(r.exitCode, 1) << arguments;
        EXPECT_NE(r.out.find(message), std::string::npos) << r.out;
    }
}

// An empty path failed later without the flag's name ("solve --out ''" said ": cannot create the
// folder (Invalid argument)", "--mesh ''" ": unknown mesh file extension ''"), or was taken as no
// flag (inspect's --csv). Each path flag refuses it, naming itself, before anything is read.
TEST(OptionFlags, AnEmptyPathIsRefusedNamingTheFlag) {
    const std::string flags[] = {"--mesh", "--c3d", "--map", "--out"};
    for (const std::string command : {"solve", "map suggest"})
        for (const std::string& empty : flags) {
            std::string arguments = command;
            for (const std::string& flag : flags)
                arguments += " " + flag + " " + (flag == empty ? "''" : "x");
            const CliResult r = runCli(arguments);
            EXPECT_EQ(r.exitCode, 1) << arguments;
            EXPECT_NE(r.out.find(empty + ": must be a path, got \"\"\n"), std::string::npos)
                << arguments << "\n"
                << r.out;
        }
    const std::pair<std::string, std::string> refused[] = {
        {"inspect t.c3d --csv ''", "--csv"},
        {"inspect ''", "take"},
        {"demo --out ''", "--out"},  // wrote the demo into the current folder
        {"eval --sequence '' --markers 3", "--sequence"},
        {"eval --sequence s --markers-file ''", "--markers-file"},
        {"map suggest --mesh m.obj --c3d t.c3d --map m.json --out o --check ''", "--check"},
        {"batch ''", "MANIFEST"}};
    for (const auto& [command, flag] : refused) {
        const CliResult r = runCli(command);
        EXPECT_EQ(r.exitCode, 1) << command;
        EXPECT_NE(r.out.find(flag + ": must be a path, got \"\"\n"), std::string::npos)
            << command << "\n"
            << r.out;
    }
}

// The options given on the command line reach the sidecar under the same keys.
TEST(OptionFlags, TheSidecarRecordsTheOptionsUnderTheFlagsNames) {
    const fs::path demo = freshTestDir("option-flags");
    ASSERT_EQ(runCli("demo --frame-count 3 --out " + demo.string()).exitCode, 0);
    const fs::path out = demo / "solved";
    const CliResult r =
        runCli("solve --quiet --mesh " + (demo / "walker.obj").string() + " --c3d " +
               (demo / "walker.c3d").string() + " --map " + (demo / "walker.map.json").string() +
               " --out " + out.string() +
               " --format pc2 --marker-weight 40 --fill-gaps-s 0.1 --low-pass-hz 8 "
               "--calibrate none --calibration-frame 1 --solver exact --fold-guard 0.02 "
               "--max-iterations 4 --relative-tolerance 0.01");
    ASSERT_EQ(r.exitCode, 0) << r.out;
    const auto sidecar = nlohmann::json::parse(std::ifstream(out / "walker.json"));
    const nlohmann::json& o = sidecar.at("options");
    EXPECT_EQ(sidecar["version"], 2);
    EXPECT_EQ(o["marker_weight"], 40.0);
    EXPECT_EQ(o["fill_gaps_s"], 0.1);
    EXPECT_EQ(o["low_pass_hz"], 8.0);
    EXPECT_EQ(o["calibrate"], "none");
    EXPECT_EQ(o["calibration_frame"], 1);
    EXPECT_EQ(o["fold_guard"], 0.02);
    EXPECT_EQ(o["max_iterations"], 4);
    EXPECT_EQ(o["relative_tolerance"], 0.01);
    EXPECT_EQ(o["solver"], "exact");
    EXPECT_EQ(sidecar["alignment"]["calibration_frame"], 1);
}

// "solve --fold-guard 0.5" (help: "exact only") was taken with the default local-global solver:
// it changed nothing, yet the sidecar recorded it, and batch solved the take again whenever it
// changed. Solve and eval refuse it, naming the flag, before reading any file; with --solver exact,
// or at its default value, it is taken.
TEST(OptionFlags, AnExactOnlyFlagWithoutTheExactSolverIsRefusedNamingIt) {
    const std::string solve = "solve --mesh m.obj --c3d t.c3d --map m.json --out o ";
    const std::pair<std::string, std::string> refused[] = {
        {solve + "--fold-guard 0.5",
         "--fold-guard 0.5 changes nothing with the local-global solver: it applies to --solver "
         "exact only\n"},
        {solve + "--solver local-global --orientation-guard 0 --max-iterations 4",
         "--orientation-guard 0.0 and --max-iterations 4 change nothing with the local-global "
         "solver: they apply to --solver exact only\n"},
        {"eval --sequence s --markers 3 --relative-tolerance 0.01",
         "--relative-tolerance 0.01 changes nothing with the local-global solver"}};
    for (const auto& [arguments, message] : refused) {
        const CliResult r = runCli(arguments);
        EXPECT_EQ(r.exitCode, 1) << arguments;
        EXPECT_NE(r.out.find(message), std::string::npos) << r.out;
    }
    // Taken: past the options, the missing mesh or sequence is what is refused.
    for (const std::string& arguments :
         {solve + "--solver exact --fold-guard 0.5", solve + "--fold-guard 0.01",
          std::string("eval --sequence s --markers 3 --solver exact --max-iterations 4")}) {
        const CliResult r = runCli(arguments);
        EXPECT_EQ(r.out.find("changes nothing"), std::string::npos) << arguments << r.out;
        EXPECT_NE(r.out.find(arguments[0] == 's' ? "m.obj" : "s:"), std::string::npos) << r.out;
    }
}

// The flags that took their keys' names are refused naming the new one; CLI11 alone said "The
// following arguments were not expected: 5 --weight". A command without the new flag (inspect)
// gets no such line.
TEST(OptionFlags, AnOldFlagIsRefusedNamingItsNewName) {
    const std::string solve = "solve --mesh m.obj --c3d t.c3d --map m.json --out o ";
    const std::pair<std::string, std::string> renamed[] = {
        {solve + "--weight 5", "--weight was renamed --marker-weight"},
        {solve + "--weight=5", "--weight was renamed --marker-weight"},
        {solve + "--lowpass 6", "--lowpass was renamed --low-pass-hz"},
        {solve + "--fill-gaps 0.1", "--fill-gaps was renamed --fill-gaps-s"},
        {"eval --sequence x --markers 3 --rigidity 1", "--rigidity was renamed --fold-guard"},
        {"eval --sequence x --markers 3 --tolerance 0.1",
         "--tolerance was renamed --relative-tolerance"}};
    for (const auto& [arguments, hint] : renamed) {
        const CliResult r = runCli(arguments);
        EXPECT_EQ(r.exitCode, 1) << arguments;
        EXPECT_NE(r.out.find("not expected"), std::string::npos) << r.out;
        EXPECT_NE(r.out.find(hint + "\n"), std::string::npos) << arguments << "\n" << r.out;
    }
    const CliResult inspect = runCli("inspect t.c3d --weight 5");
    EXPECT_EQ(inspect.exitCode, 1);
    EXPECT_EQ(inspect.out.find("renamed"), std::string::npos) << inspect.out;
}

// --rigidity and --tolerance were eval's flags: solve, which has --fold-guard and
// --relative-tolerance, was told "--rigidity was renamed --fold-guard" of a flag it never had.
TEST(OptionFlags, AnOldFlagIsNamedOnlyOnTheCommandThatHadIt) {
    const std::string solve = "solve --mesh m.obj --c3d t.c3d --map m.json --out o ";
    for (const std::string& arguments : {solve + "--rigidity 1", solve + "--tolerance 0.1"}) {
        const CliResult r = runCli(arguments);
        EXPECT_EQ(r.exitCode, 1) << arguments;
        EXPECT_NE(r.out.find("not expected"), std::string::npos) << r.out;
        EXPECT_EQ(r.out.find("renamed"), std::string::npos) << r.out;
    }
}
