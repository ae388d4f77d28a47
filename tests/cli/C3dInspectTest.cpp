// boneless-cli inspect, run as a user would.

#include <gtest/gtest.h>
#include <sys/resource.h>
#include <sys/wait.h>

#include <csignal>
#include <cstdlib>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "C3dTestSupport.h"
#include "CliRunner.h"
#include "FileSizeLimit.h"

using namespace boneless;

namespace {

struct CliRun {
    int exitCode;
    std::string out, err;
};

std::string slurp(const std::filesystem::path& p) {
    std::ifstream in(p, std::ios::binary);
    std::stringstream s;
    s << in.rdbuf();
    return s.str();
}

CliRun inspect(const std::string& args) {
    const auto dir = c3dtest::workDir();
    const auto out = dir / "inspect.out", err = dir / "inspect.err";
    const std::string cmd = std::string("\"") + BONELESS_CLI + "\" inspect " + args + " >\"" +
                            out.string() + "\" 2>\"" + err.string() + "\"";
    const int status = std::system(cmd.c_str());
    return {WIFEXITED(status) ? WEXITSTATUS(status) : -1, slurp(out), slurp(err)};
}

std::string quoted(const std::string& s) {
    return "\"" + s + "\"";
}

std::string demoFile() {
    C3dTake t = c3dtest::syntheticTake(5, {"bob:LFHD", "bob:LKneeAngles", "RFHD"});
    t.points[1].kind = C3dPointKind::Angle;
    t.rate = 60.0;
    for (std::size_t f = 0; f < 5; ++f) t.samples.set(f, 0, 1.5, -2.25, 3.0);
    t.samples.setMissing(2, 0);
    const std::string path = (c3dtest::workDir() / "inspect-demo.c3d").string();
    writeC3d(t, path);
    return path;
}

}  // namespace

TEST(C3dInspect, JsonDescribesTheTake) {
    const CliRun r = inspect(quoted(demoFile()) + " --json");
    ASSERT_EQ(r.exitCode, 0) << r.err;
    const auto j = nlohmann::json::parse(r.out);
    EXPECT_EQ(j["frame_count"], 5);
    EXPECT_EQ(j["units"], "mm");
    EXPECT_EQ(j["processor"], "intel");
    EXPECT_EQ(j["storage"], "float");
    EXPECT_EQ(j["first_frame"], 1);
    EXPECT_EQ(j["last_frame"], 5);
    EXPECT_EQ(j["analog_channels"], 0);
    EXPECT_EQ(j["analog_rate"], 0.0);
    ASSERT_EQ(j["points"].size(), 3u);
    EXPECT_EQ(j["points"][0]["label"], "bob:LFHD");
    EXPECT_EQ(j["points"][0]["subject"], "bob");
    EXPECT_EQ(j["points"][0]["kind"], "marker");
    EXPECT_EQ(j["points"][0]["missing_frames"], 1);
    EXPECT_EQ(j["points"][1]["kind"], "angle");
    EXPECT_EQ(j["points"][2]["subject"], "");
}

// A take named in Latin-1 ("caf\xe9.c3d", an old archive's) was named "caf\uFFFD.c3d", a name
// nothing can find again; it is read as Latin-1, as the sidecar records it.
TEST(C3dInspect, JsonNamesALatin1TakeAsTheSidecarDoes) {
    const std::filesystem::path take = c3dtest::workDir() / "caf\xe9.c3d";
    writeC3d(c3dtest::syntheticTake(3, {"A"}), take.string());
    const CliRun r = inspect(quoted(take.string()) + " --json");
    ASSERT_EQ(r.exitCode, 0) << r.err;
    const std::string file = nlohmann::json::parse(r.out)["file"];
    EXPECT_EQ(file.substr(file.size() - 9), "caf\xc3\xa9.c3d") << file;
}

// The frame rate has one name, the sidecar's; inspect called it "rate".
TEST(C3dInspect, JsonNamesTheFrameRateFpsAsTheSidecarDoes) {
    const CliRun r = inspect(quoted(demoFile()) + " --json");
    ASSERT_EQ(r.exitCode, 0) << r.err;
    const auto j = nlohmann::json::parse(r.out);
    EXPECT_EQ(j["fps"], 60.0);
    EXPECT_FALSE(j.contains("rate")) << r.out;
    // A take without a frame rate has none, as in the sidecar: not 0 frames a second.
    C3dTake noRate = readC3d(demoFile());
    noRate.rate = 0;
    const std::string file = (c3dtest::workDir() / "inspect-no-rate.c3d").string();
    writeC3d(noRate, file);
    const CliRun none = inspect(quoted(file) + " --json");
    ASSERT_EQ(none.exitCode, 0) << none.err;
    EXPECT_TRUE(nlohmann::json::parse(none.out)["fps"].is_null()) << none.out;
}

// The summary said "5 @ 0 Hz" of a take whose JSON says "fps": null.
TEST(C3dInspect, TheSummaryOfATakeWithoutAFrameRateSaysItHasNone) {
    C3dTake noRate = readC3d(demoFile());
    noRate.rate = 0;
    const std::string file = (c3dtest::workDir() / "inspect-no-rate.c3d").string();
    writeC3d(noRate, file);
    const CliRun none = inspect(quoted(file));
    ASSERT_EQ(none.exitCode, 0) << none.err;
    EXPECT_NE(none.out.find("  frames    5, no frame rate, numbered 1..5 (header frames 1..5)\n"),
              std::string::npos)
        << none.out;
    const CliRun rated = inspect(quoted(demoFile()));
    EXPECT_NE(rated.out.find("  frames    5 @ 60 Hz, numbered 1..5 (header frames 1..5)\n"),
              std::string::npos)
        << rated.out;
}

TEST(C3dInspect, CsvHasOneRowPerSampleAndEmptyMissing) {
    const auto csv = c3dtest::workDir() / "inspect-demo.csv";
    std::filesystem::remove(csv);
    const CliRun r = inspect(quoted(demoFile()) + " --csv " + quoted(csv.string()));
    ASSERT_EQ(r.exitCode, 0) << r.err;
    EXPECT_NE(r.out.find("frames"), std::string::npos);  // the summary still prints
    std::ifstream in(csv);
    std::string line;
    ASSERT_TRUE(std::getline(in, line));
    EXPECT_EQ(line, "frame,label,x,y,z,valid");
    std::vector<std::string> rows;
    while (std::getline(in, line)) rows.push_back(line);
    ASSERT_EQ(rows.size(), 15u);
    EXPECT_EQ(rows[0], "0,bob:LFHD,1.5,-2.25,3,1");
    EXPECT_EQ(rows[6], "2,bob:LFHD,,,,0");
}

// `inspect victim.c3d --csv victim.c3d` replaced the take with its own CSV. An output that is the
// take however it is spelled (through "..", a symbolic or a hard link) is refused, naming both,
// and the take is left as it was.
// `--csv /dev/stdout` (or a process substitution) writes through to the pipe: the atomic path's
// temporary beside it could not be made (Permission denied in /dev).
TEST(C3dInspect, ACsvGivenAsStdoutGoesDownThePipe) {
    namespace fs = std::filesystem;
    const fs::path dir = c3dtest::workDir();
    const fs::path take = dir / "csv-stdout.c3d", out = dir / "piped.out", err = dir / "piped.err";
    writeC3d(c3dtest::syntheticTake(5, {"A", "B"}), take.string());
    const std::string cmd = std::string("\"") + BONELESS_CLI + "\" inspect " +
                            quoted(take.string()) + " --csv /dev/stdout 2>" + quoted(err.string()) +
                            " | cat >" + quoted(out.string());
    ASSERT_EQ(std::system(cmd.c_str()), 0);
    EXPECT_EQ(slurp(err), "");
    EXPECT_EQ(slurp(out).rfind("frame,label,x,y,z,valid\n", 0), 0u) << slurp(out);
}

// `inspect --json > take.json` on a full disk left the file cut short and exited 0.
TEST(C3dInspect, AResultThatCannotBeWrittenToStandardOutputFailsTheRun) {
    namespace fs = std::filesystem;
    const fs::path take = c3dtest::workDir() / "full-disk.c3d";
    writeC3d(c3dtest::syntheticTake(5, {"A", "B"}), take.string());
    for (const char* json : {"", " --json"}) {
        const boneless::testing::CliResult r =
            boneless::testing::runShell(std::string("\"") + BONELESS_CLI + "\" inspect " +
                                        quoted(take.string()) + json + " 2>&1 >/dev/full");
        EXPECT_EQ(r.exitCode, 1) << json << r.out;
        EXPECT_EQ(r.out.rfind("boneless-cli: writing to standard output failed", 0), 0u)
            << json << r.out;
    }
}

TEST(C3dInspect, ACsvThatWouldReplaceTheTakeIsRefusedNamingBoth) {
    namespace fs = std::filesystem;
    const fs::path dir = c3dtest::workDir() / "csv-over-take";
    fs::remove_all(dir);
    fs::create_directories(dir / "sub");
    const fs::path take = dir / "victim.c3d";
    writeC3d(c3dtest::syntheticTake(5, {"A", "B"}), take.string());
    const std::string before = slurp(take);
    fs::create_symlink(take, dir / "link.csv");
    fs::create_hard_link(take, dir / "hard.csv");
    for (const fs::path& csv :
         {take, dir / "sub" / ".." / "victim.c3d", dir / "link.csv", dir / "hard.csv"}) {
        const CliRun r = inspect(quoted(take.string()) + " --csv " + quoted(csv.string()));
        EXPECT_EQ(r.exitCode, 1) << csv;
        EXPECT_EQ(r.err, "boneless-cli: " + csv.string() + ": the CSV would replace the take " +
                             take.string() + "; give --csv another file\n");
        EXPECT_TRUE(slurp(take) == before) << csv << ": the take was replaced";
    }
}

// A CSV that could not be written had already wiped the file it was to replace, was left
// truncated, and the error said only "write failed". Here the process may not grow a file past
// 4 KiB (RLIMIT_FSIZE, as a quota or a full disk stops it): the error gives the system's reason
// and the old file and nothing else is left.
TEST(C3dInspect, ACsvThatCannotBeWrittenSaysWhyAndLeavesTheOldFileAsItWas) {
    namespace fs = std::filesystem;
    const fs::path dir = c3dtest::workDir() / "csv-fails";
    fs::remove_all(dir);
    fs::create_directories(dir);
    const fs::path take = dir / "long.c3d", csv = dir / "long.csv";
    writeC3d(c3dtest::syntheticTake(200, {"A", "B", "C"}), take.string());  // a 20 KB CSV
    std::ofstream(csv) << "the old CSV\n";
    rlimit normal{};
    ASSERT_TRUE(boneless::test::limitFileSize(normal, 4096));
    const CliRun r = inspect(quoted(take.string()) + " --csv " + quoted(csv.string()));
    ASSERT_TRUE(boneless::test::restoreFileSize(normal));
    EXPECT_EQ(r.exitCode, 1);
    EXPECT_EQ(r.err, "boneless-cli: " + csv.string() + ": writing failed (File too large)\n");
    EXPECT_TRUE(slurp(csv) == "the old CSV\n") << "the old CSV was replaced";
    EXPECT_EQ(std::distance(fs::directory_iterator(dir), fs::directory_iterator{}), 2)
        << "a failed write leaves no temporary behind";

    const fs::path nowhere = dir / "missing" / "x.csv";
    const CliRun missing = inspect(quoted(take.string()) + " --csv " + quoted(nowhere.string()));
    EXPECT_EQ(missing.exitCode, 1);
    EXPECT_EQ(missing.err, "boneless-cli: " + nowhere.string() +
                               ": cannot be written (No such file or directory)\n");
}

TEST(C3dInspect, UnreadableFileExitsNonZeroWithOneLine) {
    const auto bad = c3dtest::workDir() / "not-a-c3d.c3d";
    std::ofstream(bad) << "hello, this is not a motion capture file\n";
    const CliRun r = inspect(quoted(bad.string()));
    EXPECT_NE(r.exitCode, 0);
    EXPECT_TRUE(r.out.empty());
    ASSERT_FALSE(r.err.empty());
    EXPECT_EQ(r.err.find('\n'), r.err.size() - 1) << r.err;  // exactly one line
    EXPECT_NE(r.err.find(bad.string()), std::string::npos) << r.err;
    const CliRun missing = inspect(quoted((c3dtest::workDir() / "no-such.c3d").string()));
    EXPECT_NE(missing.exitCode, 0);
    EXPECT_NE(missing.err.find("cannot open the take (No such file or directory)"),
              std::string::npos)
        << missing.err;
}

TEST(C3dInspect, RealFilesJson) {
    C3D_SHARED_OR_SKIP(mips, "c3d-org/sample01/Eb015si.c3d");
    const CliRun r = inspect(quoted(mips) + " --json");
    ASSERT_EQ(r.exitCode, 0) << r.err;
    const auto j = nlohmann::json::parse(r.out);
    EXPECT_EQ(j["processor"], "mips");
    EXPECT_EQ(j["storage"], "int16");
    EXPECT_EQ(j["frame_count"], 450);
    EXPECT_EQ(j["analog_channels"], 16);
    EXPECT_EQ(j["analog_rate"], 200.0);
    EXPECT_EQ(j["points"].size(), 26u);
    C3D_SHARED_OR_SKIP(empty, "btk/Empty.c3d");
    const CliRun e = inspect(quoted(empty));
    EXPECT_EQ(e.exitCode, 1);
    EXPECT_NE(e.err.find("Empty.c3d"), std::string::npos);
    EXPECT_NE(e.err.find("empty"), std::string::npos);
}

// "first_frame" and "first_frame_number" were both there, and a truncated copy's "last_frame" was
// the header's where "frames" counted those it holds. The first and last frames are those held,
// by number, as the summary's "numbered"; the header's words are "header_frames".
TEST(C3dInspect, TheFirstAndLastFramesAreThoseTheTakeHoldsAndTheHeadersApart) {
    C3dTake t = c3dtest::syntheticTake(40, {"LFHD", "RFHD", "LBHD"});
    t.rate = 100.0;
    t.firstFrame = 101;
    const std::string path = (c3dtest::workDir() / "inspect-cut.c3d").string();
    writeC3d(t, path);
    std::filesystem::resize_file(path, std::filesystem::file_size(path) - 1200);
    const CliRun r = inspect(quoted(path) + " --json");
    ASSERT_EQ(r.exitCode, 0) << r.err;
    const auto j = nlohmann::json::parse(r.out);
    const int frames = j["frame_count"];
    ASSERT_LT(frames, 40);
    ASSERT_GT(frames, 0);
    EXPECT_EQ(j["first_frame"], 101);
    EXPECT_EQ(j["last_frame"], 100 + frames);
    EXPECT_EQ(j["header_frames"], nlohmann::json::array({101, 140}));
    EXPECT_FALSE(j.contains("first_frame_number"));
    const CliRun text = inspect(quoted(path));
    EXPECT_NE(text.out.find("  frames    " + std::to_string(frames) + " @ 100 Hz, numbered 101.." +
                            std::to_string(100 + frames) + " (header frames 101..140)\n"),
              std::string::npos)
        << text.out;
}

// Two points with one label: no map can name either, and inspect says so before a solve does.
TEST(C3dInspect, WarnsOfTwoPointsThatShareALabel) {
    const C3dTake t =
        c3dtest::syntheticTake(3, {"Male:LFHD", "Male:LFWT", "Male:RFWT", "Male:LFWT"});
    const std::string path = (c3dtest::workDir() / "shared-label.c3d").string();
    writeC3d(t, path);
    const CliRun r = inspect(quoted(path));
    ASSERT_EQ(r.exitCode, 0) << r.err;
    EXPECT_NE(r.out.find("warning   points 1 and 3 are both labelled Male:LFWT"), std::string::npos)
        << r.out;
}

// The point table pads labels to the columns a terminal shows them in, not to their bytes:
// "walker:頭" (a wide character, 3 bytes) shifted the kind column by one, and so did "KÖPF".
TEST(C3dInspect, ThePointTableStaysAlignedForLabelsOutsideAscii) {
    const C3dTake t = c3dtest::syntheticTake(3, {"walker:頭", "walker:KÖPF", "walker:HEAD"});
    const std::string path = (c3dtest::workDir() / "wide-labels.c3d").string();
    writeC3d(t, path);
    const CliRun r = inspect(quoted(path));
    ASSERT_EQ(r.exitCode, 0) << r.err;
    // The label column is 30 wide and a space follows it: the spaces after each label are what
    // its display width (頭 takes two columns) leaves.
    const std::pair<std::string, std::size_t> rows[] = {
        {"walker:頭", 30 - 9 + 1}, {"walker:KÖPF", 30 - 11 + 1}, {"walker:HEAD", 30 - 11 + 1}};
    for (const auto& [label, spaces] : rows) {
        const std::size_t at = r.out.find(label + " ");
        ASSERT_NE(at, std::string::npos) << label << " not in\n" << r.out;
        const std::size_t after = at + label.size();
        EXPECT_EQ(r.out.find_first_not_of(' ', after) - after, spaces) << label << " in\n" << r.out;
    }
}

namespace {

// 15,000 frames at 120 Hz (125 s) of two subjects' markers and an angle: bob:LFHD misses frames
// 100 to 339 (240), frame 2 and the last 10; ann:RFHD misses 1000 to 1239 too (as long: bob's,
// the first, is named); the angle misses every frame, which no marker's gap is.
std::string gappyFile() {
    C3dTake t = c3dtest::syntheticTake(15000, {"bob:LFHD", "ann:RFHD", "bob:LKneeAngles"});
    t.points[2].kind = C3dPointKind::Angle;
    t.rate = 120.0;
    for (std::size_t f = 0; f < 15000; ++f) {
        t.samples.set(f, 0, 1.5, -2.25, 3.0);
        t.samples.set(f, 1, 4.5, -2.25, 3.0);
        t.samples.setMissing(f, 2);
    }
    for (std::size_t f = 100; f < 340; ++f) t.samples.setMissing(f, 0);
    t.samples.setMissing(2, 0);
    for (std::size_t f = 14990; f < 15000; ++f) t.samples.setMissing(f, 0);
    for (std::size_t f = 1000; f < 1240; ++f) t.samples.setMissing(f, 1);
    const std::string path = (c3dtest::workDir() / "inspect-gappy.c3d").string();
    writeC3d(t, path);
    return path;
}

// A short take of two markers seen in every frame, no subjects, at `rate` (0: none).
std::string plainFile(double rate) {
    C3dTake plain = c3dtest::syntheticTake(6, {"LFHD", "RFHD"});
    plain.rate = rate;
    for (std::size_t f = 0; f < 6; ++f)
        for (std::size_t k = 0; k < 2; ++k) plain.samples.set(f, k, 1.0 + k, 2.0, 3.0);
    const std::string file = (c3dtest::workDir() / "inspect-plain.c3d").string();
    writeC3d(plain, file);
    return file;
}

}  // namespace

// A 25-minute take's summary gave its frames and rate but not how long it is, which subjects it
// holds, or where its longest gap is: the frames given as solve's --frames takes them.
TEST(C3dInspect, TheSummarySaysTheDurationTheSubjectsAndTheLongestGap) {
    const CliRun r = inspect(quoted(gappyFile()));
    ASSERT_EQ(r.exitCode, 0) << r.err;
    EXPECT_NE(r.out.find("  duration  125 s (2 min 5.0 s)\n"), std::string::npos) << r.out;
    EXPECT_NE(r.out.find("  subjects  bob, ann\n"), std::string::npos) << r.out;
    EXPECT_NE(r.out.find("  gaps      longest bob:LFHD, frames 100:340 (240 frames, 2 s)\n"),
              std::string::npos)
        << r.out;
    EXPECT_NE(r.out.find("kind     missing  longest gap\n"), std::string::npos) << r.out;
    EXPECT_NE(r.out.find(" marker   251      240 at 100:340\n"), std::string::npos) << r.out;
    EXPECT_NE(r.out.find(" marker   240      240 at 1000:1240\n"), std::string::npos) << r.out;
    EXPECT_NE(r.out.find(" angle    15000    15000 at 0:15000\n"), std::string::npos) << r.out;
    // A short take without subjects or gaps says neither; its duration in seconds alone.
    const CliRun p = inspect(quoted(plainFile(60.0)));
    ASSERT_EQ(p.exitCode, 0) << p.err;
    EXPECT_NE(p.out.find("  duration  0.1 s\n"), std::string::npos) << p.out;
    EXPECT_EQ(p.out.find("subjects"), std::string::npos) << p.out;
    EXPECT_EQ(p.out.find("  gaps "), std::string::npos) << p.out;
    EXPECT_NE(p.out.find(" marker   0        -\n"), std::string::npos) << p.out;
}

TEST(C3dInspect, JsonGivesTheDurationTheSubjectsAndTheLongestGaps) {
    const CliRun r = inspect(quoted(gappyFile()) + " --json");
    ASSERT_EQ(r.exitCode, 0) << r.err;
    const auto j = nlohmann::json::parse(r.out);
    EXPECT_EQ(j["duration_s"], 125.0);
    EXPECT_EQ(j["subjects"], nlohmann::json({"bob", "ann"}));
    EXPECT_EQ(j["longest_gap"], nlohmann::json({{"point", 0},
                                                {"label", "bob:LFHD"},
                                                {"frames", 240},
                                                {"frame_range", {100, 340}},
                                                {"seconds", 2.0}}));
    EXPECT_EQ(j["points"][0]["missing_frames"], 251);
    EXPECT_EQ(j["points"][0]["longest_gap"],
              nlohmann::json({{"frames", 240}, {"frame_range", {100, 340}}}));
    EXPECT_EQ(j["points"][1]["longest_gap"]["frame_range"], nlohmann::json({1000, 1240}));
    EXPECT_EQ(j["points"][2]["longest_gap"]["frames"], 15000);
    // Without a rate, no duration; without gaps or subjects, none.
    const CliRun p = inspect(quoted(plainFile(0)) + " --json");
    ASSERT_EQ(p.exitCode, 0) << p.err;
    const auto q = nlohmann::json::parse(p.out);
    EXPECT_TRUE(q["duration_s"].is_null()) << p.out;
    EXPECT_EQ(q["subjects"], nlohmann::json::array());
    EXPECT_TRUE(q["longest_gap"].is_null()) << p.out;
    EXPECT_TRUE(q["points"][0]["longest_gap"].is_null()) << p.out;
}

// A take whose labels are Latin-1 (older Vicon files): inspect writes its JSON and CSV in UTF-8.
TEST(C3dInspect, JsonAndCsvOfALatin1FileAreUtf8) {
    const std::string file = (c3dtest::workDir() / "latin1-labels.c3d").string();
    writeC3d(c3dtest::latin1Take(), file);
    const auto csv = c3dtest::workDir() / "latin1-labels.csv";
    const CliRun r = inspect(quoted(file) + " --json --csv " + quoted(csv.string()));
    ASSERT_EQ(r.exitCode, 0) << r.err;
    const auto j = nlohmann::json::parse(r.out);  // throws on invalid UTF-8
    EXPECT_EQ(j["points"][0]["label"], c3dtest::kLatin1Subject + ":LFHD");
    EXPECT_EQ(j["points"][1]["description"], c3dtest::kLatin1Description);
    const std::string rows = slurp(csv);
    EXPECT_NE(rows.find("0," + c3dtest::kLatin1Subject + ":LFHD,"), std::string::npos);
    EXPECT_EQ(rows.find("M\xFCller"), std::string::npos);
}

// Every real file the project has, and a generated Latin-1 one: inspect --json is UTF-8 JSON.
TEST(C3dInspect, JsonIsValidUtf8ForEveryFile) {
    const std::string latin1 = (c3dtest::workDir() / "latin1-every.c3d").string();
    writeC3d(c3dtest::latin1Take(), latin1);
    std::vector<std::string> files{latin1};
    const auto shared = c3dtest::sharedC3d();
    if (std::filesystem::is_directory(shared))
        for (const auto& e : std::filesystem::recursive_directory_iterator(shared))
            if (e.is_regular_file() && e.path().extension() == ".c3d")
                files.push_back(e.path().string());
    if (files.size() == 1) std::cout << "no shared data in " << shared << "; generated file only\n";
    std::size_t read = 0;
    for (const auto& f : files) {
        const CliRun r = inspect(quoted(f) + " --json");
        ASSERT_TRUE(r.exitCode == 0 || r.exitCode == 1) << f;  // read, or refused with a message
        if (r.exitCode != 0) continue;
        ++read;
        EXPECT_TRUE(nlohmann::json::accept(r.out)) << f;  // rejects invalid UTF-8 too
    }
    EXPECT_GE(read, 1u);
}
