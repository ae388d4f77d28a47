// Inputs that are no file to read: a folder, a FIFO, a device. Every loader refuses them by what
// they are, before opening them.
#include <gtest/gtest.h>
#include <sys/stat.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "CliRunner.h"

using namespace boneless::testing;
namespace fs = std::filesystem;

namespace {

// boneless-cli with `arguments`, stopped after 10 s: a loader that opens a FIFO waits for a
// writer for ever.
CliResult runBounded(const std::string& arguments) {
    return runShell("timeout 10 " + std::string(BONELESS_CLI) + " " + arguments + " 2>&1");
}

struct Case {
    std::string arguments, refusal;
};

void expectRefusals(const std::vector<Case>& cases) {
    for (const Case& c : cases) {
        const CliResult r = runBounded(c.arguments);
        EXPECT_EQ(r.exitCode, 1) << c.arguments << "\n" << r.out;
        EXPECT_EQ(r.out, "boneless-cli: " + c.refusal + "\n") << c.arguments;
    }
}

}  // namespace

// `solve --mesh somedir` said "unknown mesh file extension ''", a folder named d.obj "cannot read
// file", one named d.ply "not a PLY file", `--map somedir` "is not valid JSON" and
// `eval --markers-file somedir` "no vertex ids in the marker file".
TEST(InputFiles, AFolderGivenForAFileIsRefusedAsAFolderByEveryLoader) {
    const fs::path dir = freshTestDir("folders");
    ASSERT_EQ(runCli("demo --out " + dir.string() + " --frame-count 3").exitCode, 0);
    for (const char* folder : {"somedir", "d.obj", "d.ply"}) fs::create_directory(dir / folder);
    const std::string somedir = (dir / "somedir").string(), mesh = (dir / "walker.obj").string(),
                      take = (dir / "walker.c3d").string(),
                      map = (dir / "walker.map.json").string(),
                      out = " --out " + (dir / "out").string();
    auto solve = [&](const std::string& m, const std::string& t, const std::string& c) {
        return "solve --mesh " + m + " --c3d " + t + " --map " + c + out;
    };
    expectRefusals({
        {solve(somedir, take, map), somedir + ": is a directory, not a mesh file"},
        {solve((dir / "d.obj").string() + "/", take, map),
         (dir / "d.obj").string() + "/: is a directory, not a mesh file"},
        {solve((dir / "d.ply").string(), take, map),
         (dir / "d.ply").string() + ": is a directory, not a mesh file"},
        {solve(mesh, take, somedir), somedir + ": is a directory, not a correspondence file"},
        {solve(mesh, somedir, map), somedir + ": is a directory, not a C3D file"},
        {"map suggest --mesh " + mesh + " --c3d " + take + " --map " + map + " --check " + somedir +
             " --out " + (dir / "full.json").string(),
         somedir + ": is a directory, not a correspondence file"},
        {"eval --sequence " + (dir / "truth").string() + " --markers-file " + somedir,
         somedir + ": is a directory, not a marker file"},
        {"batch " + somedir, somedir + ": is a directory, not a batch manifest file"},
        {"inspect " + somedir, somedir + ": is a directory, not a C3D file"},
    });
}

// `inspect fifo.c3d` waited for a writer for ever, as did every other loader given a FIFO; a
// device (/dev/null) read as an empty file or went by its name's extension.
TEST(InputFiles, AFifoOrADeviceIsRefusedBeforeItIsOpenedRatherThanWaitedOn) {
    const fs::path dir = freshTestDir("fifos");
    ASSERT_EQ(runCli("demo --out " + dir.string() + " --frame-count 3").exitCode, 0);
    for (const char* name : {"fifo.obj", "fifo.c3d", "fifo.json", "fifo.txt"})
        ASSERT_EQ(::mkfifo((dir / name).c_str(), 0600), 0) << name;
    const std::string mesh = (dir / "walker.obj").string(), take = (dir / "walker.c3d").string(),
                      map = (dir / "walker.map.json").string(),
                      out = " --out " + (dir / "out").string();
    auto solve = [&](const std::string& m, const std::string& t, const std::string& c) {
        return "solve --mesh " + m + " --c3d " + t + " --map " + c + out;
    };
    auto fifo = [&](const char* name) { return (dir / name).string(); };
    expectRefusals({
        {"inspect " + fifo("fifo.c3d"), fifo("fifo.c3d") + ": is not a regular file"},
        {solve(fifo("fifo.obj"), take, map), fifo("fifo.obj") + ": is not a regular file"},
        {solve(mesh, fifo("fifo.c3d"), map), fifo("fifo.c3d") + ": is not a regular file"},
        {solve(mesh, take, fifo("fifo.json")), fifo("fifo.json") + ": is not a regular file"},
        {"map suggest --mesh " + mesh + " --c3d " + fifo("fifo.c3d") + " --map " + map + " --out " +
             (dir / "full.json").string(),
         fifo("fifo.c3d") + ": is not a regular file"},
        {"eval --sequence " + (dir / "truth").string() + " --markers-file " + fifo("fifo.txt"),
         fifo("fifo.txt") + ": is not a regular file"},
        {"batch " + fifo("fifo.json"), fifo("fifo.json") + ": is not a regular file"},
        {solve("/dev/null", take, map), "/dev/null: is not a regular file"},
        {"inspect /dev/null", "/dev/null: is not a regular file"},
    });
}

// A marker file or manifest that cannot be opened says why, as the other loaders do: a missing
// one, one under a file and (not as root, whom permissions do not stop) an unreadable one all said
// "cannot open the marker file".
TEST(InputFiles, AMarkerFileOrManifestThatCannotBeOpenedSaysWhy) {
    const fs::path dir = freshTestDir("unopened");
    ASSERT_EQ(runCli("demo --out " + dir.string() + " --frame-count 3").exitCode, 0);
    const std::string missing = (dir / "missing.txt").string(),
                      underAFile = (dir / "walker.obj" / "m.json").string(),
                      unreadable = (dir / "unreadable.txt").string();
    const std::string eval = "eval --sequence " + (dir / "truth").string() + " --markers-file ";
    std::vector<Case> cases = {
        {eval + missing, missing + ": cannot open the marker file (No such file or directory)"},
        {eval + underAFile, underAFile + ": cannot open the marker file (Not a directory)"},
        {"batch " + missing,
         missing + ": cannot open the batch manifest (No such file or directory)"},
        {"batch " + underAFile, underAFile + ": cannot open the batch manifest (Not a directory)"},
    };
    std::ofstream(unreadable) << "1\n";
    fs::permissions(unreadable, fs::perms::none);
    if (::geteuid() != 0) {
        cases.push_back(
            {eval + unreadable, unreadable + ": cannot open the marker file (Permission denied)"});
        cases.push_back({"batch " + unreadable,
                         unreadable + ": cannot open the batch manifest (Permission denied)"});
    }
    expectRefusals(cases);
}

// A link to a take, mesh or map that was moved said "cannot open the take (No such file or
// directory)" of the link, which is there: the link and where it points are named.
TEST(InputFiles, ALinkWhoseTargetIsGoneIsNamedWithItsTargetByEveryLoader) {
    const fs::path dir = freshTestDir("links");
    ASSERT_EQ(runCli("demo --out " + dir.string() + " --frame-count 3").exitCode, 0);
    const std::string mesh = (dir / "walker.obj").string(), take = (dir / "walker.c3d").string(),
                      map = (dir / "walker.map.json").string(),
                      out = " --out " + (dir / "out").string();
    const auto link = [&](const char* name) {
        fs::create_symlink(dir / "moved" / name, dir / name);
        return (dir / name).string() + ": is a link to " + (dir / "moved" / name).string() +
               ", which does not exist";
    };
    auto solve = [&](const std::string& m, const std::string& t, const std::string& c) {
        return "solve --mesh " + m + " --c3d " + t + " --map " + c + out;
    };
    const auto at = [&](const char* name) { return (dir / name).string(); };
    expectRefusals({
        {solve(at("gone.obj"), take, map), link("gone.obj")},
        {solve(mesh, at("gone.c3d"), map), link("gone.c3d")},
        {solve(mesh, take, at("gone.json")), link("gone.json")},
        {"inspect " + at("gone.c3d"), at("gone.c3d") + ": is a link to " +
                                          (dir / "moved" / "gone.c3d").string() +
                                          ", which does not exist"},
    });
}
