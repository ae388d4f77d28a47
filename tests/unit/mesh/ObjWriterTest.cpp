#include <gtest/gtest.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <array>
#include <csignal>
#include <filesystem>
#include <fstream>
#include <random>

#include "FileSizeLimit.h"
#include "TestFiles.h"
#include "TestMeshes.h"
#include "boneless/Error.h"
#include "boneless/GltfWriter.h"
#include "boneless/MddWriter.h"
#include "boneless/MeshReader.h"
#include "boneless/MeshSequence.h"
#include "boneless/ObjWriter.h"
#include "boneless/PointCacheWriter.h"

using namespace boneless;
using namespace boneless::testing;
namespace fs = std::filesystem;

TEST(ObjWriter, RoundTripsPositionsBitForBitAndLeavesNoTemporaryFile) {
    const fs::path dir = freshTestDir("obj-writer");
    TriMesh mesh = icosphere(2);
    std::mt19937 rng(5);
    std::uniform_real_distribution<double> noise(-1e-3, 1e-3);
    for (int i = 0; i < mesh.V.rows(); ++i) mesh.V(i, 1) += noise(rng) * 1e-7;  // awkward digits
    const std::string path = (dir / "sphere.obj").string();
    writeObj(path, mesh.V, mesh.F, "test");
    const TriMesh back = readMesh(path).mesh;
    EXPECT_EQ(back.V, mesh.V);
    EXPECT_EQ(back.F, mesh.F);
    EXPECT_EQ(std::distance(fs::directory_iterator(dir), fs::directory_iterator{}), 1);
}

TEST(ObjWriter, NamesTheFileItCannotWrite) {
    const TriMesh mesh = icosphere(0);
    try {
        writeObj("/nonexistent-folder/x.obj", mesh.V, mesh.F);
        FAIL() << "expected an error";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("/nonexistent-folder/x.obj"), std::string::npos);
    }
}

namespace {

// A unit cube as modellers write it: six quads, four texture coordinates each, two materials and
// a bare "usemtl" before the last quad, which keeps its material (as Blender's importer reads it).
std::string cubeObj() {
    std::string s = "mtllib looks/cube.mtl\n";
    for (int v = 0; v < 8; ++v)
        s += "v " + std::to_string(v & 1) + " " + std::to_string((v >> 1) & 1) + " " +
             std::to_string((v >> 2) & 1) + "\n";
    for (int t = 0; t < 24; ++t)
        s += "vt " + std::to_string(0.25 * (t % 4)) + " " + std::to_string(t / 4 / 8.0) + "\n";
    const int quads[6][4] = {{1, 3, 4, 2}, {5, 6, 8, 7}, {1, 2, 6, 5},
                             {3, 7, 8, 4}, {1, 5, 7, 3}, {2, 4, 8, 6}};
    for (int f = 0; f < 6; ++f) {
        if (f == 0) s += "usemtl red\n";
        if (f == 3) s += "usemtl blue\n";
        if (f == 5) s += "usemtl\n";
        s += "f";
        for (int c = 0; c < 4; ++c)
            s += " " + std::to_string(quads[f][c]) + "/" + std::to_string(4 * f + c + 1);
        s += "\n";
    }
    return s;
}

// Each "usemtl" run as (first polygon, material name).
std::vector<std::pair<int, std::string>> materialRuns(const SourceFaces& s) {
    std::vector<std::pair<int, std::string>> runs;
    for (const auto& [first, d] : s.materials)
        runs.push_back({first, s.materialDefinitions.at(d).name});
    return runs;
}

}  // namespace

TEST(ObjWriter, KeepsTheInputsQuadsTextureCoordinatesAndMaterials) {
    const fs::path dir = freshTestDir("obj-writer-quads");
    std::ofstream(dir / "cube.obj") << cubeObj();
    const TriMesh cube = readMesh((dir / "cube.obj").string()).mesh;
    ASSERT_NE(cube.sourceFaces, nullptr);
    const SourceFaces& in = *cube.sourceFaces;
    EXPECT_EQ(cube.faceCount(), 12);  // what the solver sees
    EXPECT_EQ(in.polygonCount(), 6);
    EXPECT_EQ(in.uv.size(), 48u);
    EXPECT_EQ(materialRuns(in),
              (std::vector<std::pair<int, std::string>>{{0, "red"}, {3, "blue"}}));
    ASSERT_EQ(in.materialLibraries.size(), 1u);
    EXPECT_EQ(fs::path(in.materialLibraries[0]), fs::absolute(dir / "looks" / "cube.mtl"));

    // A posed frame in another folder: the same polygons, corners, UVs and materials.
    fs::create_directories(dir / "frames");
    const Positions posed = 2.0 * cube.V;
    writeObj((dir / "frames" / "cube_0001.obj").string(), posed, cube.F, "frame", &in);
    const TriMesh back = readMesh((dir / "frames" / "cube_0001.obj").string()).mesh;
    EXPECT_EQ(back.V, posed);
    EXPECT_EQ(back.F, cube.F);
    ASSERT_NE(back.sourceFaces, nullptr);
    EXPECT_EQ(back.sourceFaces->start, in.start);
    EXPECT_EQ(back.sourceFaces->corners, in.corners);
    EXPECT_EQ(back.sourceFaces->uvOf, in.uvOf);
    EXPECT_EQ(back.sourceFaces->uv, in.uv);
    EXPECT_EQ(materialRuns(*back.sourceFaces), materialRuns(in));
    EXPECT_EQ(back.sourceFaces->materialLibraries, in.materialLibraries);  // ../looks/cube.mtl
}

TEST(ObjWriter, AGroupKeepsItsOwnPolygonsAndTextureCoordinates) {
    const fs::path dir = freshTestDir("obj-writer-group");
    // Group "lid" is the cube's second quad alone, on the file's vertices 5 to 8.
    std::string s = cubeObj();
    s.insert(s.find("f 5/"), "g lid\n");
    s.insert(s.find("f 1/9"), "g box\n");
    std::ofstream(dir / "cube.obj") << s;
    MeshReadOptions options;
    options.group = "lid";
    const TriMesh lid = readMesh((dir / "cube.obj").string(), options).mesh;
    ASSERT_NE(lid.sourceFaces, nullptr);
    EXPECT_EQ(lid.vertexCount(), 4);
    EXPECT_EQ(lid.sourceFaces->polygonCount(), 1);
    EXPECT_EQ(lid.sourceFaces->corners, (std::vector<int>{0, 1, 3, 2}));
    EXPECT_EQ(lid.sourceFaces->uv,
              (std::vector<double>{0, 0.125, 0.25, 0.125, 0.5, 0.125, 0.75, 0.125}));
}

TEST(ObjWriter, AnUnusableTextureCoordinateIsDroppedWithAWarningAndTheMeshStillReads) {
    const fs::path dir = freshTestDir("obj-writer-bad-vt");
    std::string s = cubeObj();
    s.replace(s.rfind("/24"), 3, "/99");
    std::ofstream(dir / "cube.obj") << s;
    const MeshReadResult r = readMesh((dir / "cube.obj").string());
    ASSERT_NE(r.mesh.sourceFaces, nullptr);  // still quads
    EXPECT_TRUE(r.mesh.sourceFaces->uv.empty());
    EXPECT_TRUE(r.mesh.sourceFaces->uvOf.empty());
    bool warned = false;
    for (const std::string& w : r.warnings) warned |= w.find("texture coordinates") != w.npos;
    EXPECT_TRUE(warned);
}

TEST(ObjWriter, ATriangleMeshWithoutTextureCoordinatesNeedsNoSourceFaces) {
    const fs::path dir = freshTestDir("obj-writer-plain");
    const TriMesh sphere = icosphere(1);
    writeObj((dir / "sphere.obj").string(), sphere.V, sphere.F);
    EXPECT_EQ(readMesh((dir / "sphere.obj").string()).mesh.sourceFaces, nullptr);
}

TEST(ObjWriter, TheMaterialLibraryIsFoundFromAFolderNamedWithDotDot) {
    const fs::path dir = freshTestDir("obj-writer-dotdot");
    std::ofstream(dir / "cube.obj") << cubeObj();
    const TriMesh cube = readMesh((dir / "cube.obj").string()).mesh;
    fs::create_directories(dir / "a");
    fs::create_directories(dir / "frames");
    const fs::path frame = dir / "a" / ".." / "frames" / "cube_0001.obj";
    writeObj(frame.string(), cube.V, cube.F, "frame", cube.sourceFaces.get());
    const TriMesh back = readMesh(frame.string()).mesh;
    ASSERT_NE(back.sourceFaces, nullptr);
    EXPECT_EQ(back.sourceFaces->materialLibraries, cube.sourceFaces->materialLibraries);
}

// "mtllib my mat.mtl" was read as the libraries "my" and "mat.mtl": the materials were lost and
// every frame written got two broken mtllib lines. The name is the rest of the line when that
// names a file (as Blender reads it), and a frame in another folder names it so again.
TEST(ObjWriter, AMaterialLibraryWithASpaceInItsNameIsOneLibraryAndWrittenBackSo) {
    const fs::path dir = freshTestDir("obj-writer-space");
    fs::create_directories(dir / "src dir");
    std::ofstream(dir / "src dir" / "my mat.mtl")
        << "newmtl red\nKd 1 0 0\nnewmtl blue\nKd 0 0 1\n";
    std::string obj = cubeObj();
    obj.replace(0, obj.find('\n'), "mtllib my mat.mtl  ");
    std::ofstream(dir / "src dir" / "cube.obj") << obj;
    const MeshReadResult read = readMesh((dir / "src dir" / "cube.obj").string());
    for (const std::string& w : read.warnings) ADD_FAILURE() << w;
    const SourceFaces& in = *read.mesh.sourceFaces;
    ASSERT_EQ(in.materialLibraries.size(), 1u);
    EXPECT_EQ(fs::path(in.materialLibraries[0]), fs::absolute(dir / "src dir" / "my mat.mtl"));
    EXPECT_EQ(in.materialDefinitions.at(0).colour, (std::array<double, 3>{1, 0, 0}));

    fs::create_directories(dir / "out");
    const fs::path frame = dir / "out" / "cube_0001.obj";
    writeObj(frame.string(), read.mesh.V, read.mesh.F, "frame", &in);
    std::ifstream text(frame);
    std::vector<std::string> libraries;
    for (std::string line; std::getline(text, line);)
        if (line.rfind("mtllib", 0) == 0) libraries.push_back(line);
    EXPECT_EQ(libraries, std::vector<std::string>{"mtllib ../src dir/my mat.mtl"});
    const MeshReadResult back = readMesh(frame.string());
    for (const std::string& w : back.warnings) ADD_FAILURE() << w;
    EXPECT_EQ(back.mesh.sourceFaces->materialLibraries, in.materialLibraries);
    EXPECT_EQ(materialRuns(*back.mesh.sourceFaces), materialRuns(in));

    // Names that are no file beside the OBJ are still separate libraries.
    std::ofstream(dir / "src dir" / "two.obj")
        << "mtllib a.mtl b.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nusemtl red\nf 1 2 3\n";
    EXPECT_EQ(
        readMesh((dir / "src dir" / "two.obj").string()).mesh.sourceFaces->materialLibraries.size(),
        2u);
}

TEST(ObjWriter, OddButLegalTextureLinesKeepTheirCoordinates) {
    const fs::path dir = freshTestDir("obj-writer-odd");
    // A one-value vt (v is 0), texture coordinates listed after the face, a material name with a
    // space in it.
    std::ofstream(dir / "tri.obj") << "v 0 0 0\nv 1 0 0\nv 0 1 0\nusemtl Material 1\n"
                                      "f 1/1 2/2 3/3\nvt 0.5\nvt 1 0\nvt 0 1\n";
    const MeshReadResult r = readMesh((dir / "tri.obj").string());
    ASSERT_NE(r.mesh.sourceFaces, nullptr);
    EXPECT_EQ(r.mesh.sourceFaces->uv, (std::vector<double>{0.5, 0, 1, 0, 0, 1}));
    EXPECT_EQ(materialRuns(*r.mesh.sourceFaces),
              (std::vector<std::pair<int, std::string>>{{0, "Material 1"}}));
    for (const std::string& w : r.warnings) EXPECT_EQ(w.find("texture"), w.npos) << w;
}

TEST(ObjWriter, FramesOfAQuadMeshReadBackAsOneSequenceHoweverTheirQuadsSplit) {
    const fs::path dir = freshTestDir("obj-writer-sequence");
    std::ofstream(dir / "cube.obj") << cubeObj();
    const TriMesh cube = readMesh((dir / "cube.obj").string()).mesh;
    fs::create_directories(dir / "frames");
    Positions pulled = cube.V;
    pulled.row(3) << 1.8, 1.8, 0;  // one corner out: the bottom quad's diagonals differ
    writeObj((dir / "frames" / "cube_0000.obj").string(), cube.V, cube.F, "",
             cube.sourceFaces.get());
    writeObj((dir / "frames" / "cube_0001.obj").string(), pulled, cube.F, "",
             cube.sourceFaces.get());
    // The premise: read on its own, the pulled frame splits a quad along the other diagonal.
    ASSERT_NE(readMesh((dir / "frames" / "cube_0001.obj").string()).mesh.F, cube.F);
    const MeshSequence sequence = readMeshSequence((dir / "frames").string());
    ASSERT_EQ(sequence.frames.size(), 2u);
    EXPECT_EQ(sequence.frames[1], pulled);
    EXPECT_EQ(sequence.rest.F, cube.F);
}

// A read-only folder said "walker.pc2: cannot be written (cannot create walker.pc2.tmp12663)":
// our temporary file, and not why. Each writer names the user's file and the system's reason.
TEST(FileWriters, NameTheUsersFileAndTheSystemsReasonWhenItCannotBeCreated) {
    const fs::path missing = fs::path(freshTestDir("unwritable")) / "missing";
    const TriMesh mesh = icosphere(1);
    auto refusal = [&](const std::string& name) {
        return (missing / name).string() + ": cannot be written (No such file or directory)";
    };
    EXPECT_EQ(errorOf([&] { PointCacheWriter((missing / "w.pc2").string(), 12, 0, 1); }),
              refusal("w.pc2"));
    EXPECT_EQ(errorOf([&] { MddWriter((missing / "w.mdd").string(), 12); }), refusal("w.mdd"));
    EXPECT_EQ(errorOf([&] { GltfWriter((missing / "w.glb").string(), mesh, "w"); }),
              refusal("w.glb"));
    EXPECT_EQ(errorOf([&] { writeObj((missing / "w.obj").string(), mesh.V, mesh.F, "test"); }),
              refusal("w.obj"));
}

// A write that fails part-way said "(disk full?)" whatever the system said. Here the process may
// not grow a file past 4 KiB (RLIMIT_FSIZE, as a quota does), and each writer passes the
// system's reason on.
TEST(FileWriters, NameTheSystemsReasonWhenAWriteFailsPartWay) {
    const fs::path dir = freshTestDir("write-fails");
    const TriMesh mesh = icosphere(4);  // 2,562 vertices: 30 KiB a frame
    rlimit normal{};
    ASSERT_TRUE(boneless::test::limitFileSize(normal, 4096));
    auto failure = [&](const std::string& name) {
        return (dir / name).string() + ": writing failed (File too large)";
    };
    const std::string pc2 = errorOf([&] {
        PointCacheWriter((dir / "w.pc2").string(), mesh.vertexCount(), 0, 1).append(mesh.V);
    });
    const std::string mdd =
        errorOf([&] { MddWriter((dir / "w.mdd").string(), mesh.vertexCount()).append(0, mesh.V); });
    const std::string obj =
        errorOf([&] { writeObj((dir / "w.obj").string(), mesh.V, mesh.F, "test"); });
    ASSERT_TRUE(boneless::test::restoreFileSize(normal));
    EXPECT_EQ(pc2, failure("w.pc2"));
    EXPECT_EQ(mdd, failure("w.mdd"));
    EXPECT_EQ(obj, failure("w.obj"));
    EXPECT_TRUE(fs::is_empty(dir)) << "a failed write leaves no file behind";
}

// The frames a PC2 buffers reach the disk as it is finished: a full disk failed there with
// "cannot be written" and no reason. 3 frames of 504 bytes stay in the C library's buffer, and the
// 1 KiB limit stops them at finish().
TEST(FileWriters, NameTheSystemsReasonWhenAPointCacheFailsAsItIsFinished) {
    const fs::path dir = freshTestDir("finish-fails");
    const TriMesh mesh = icosphere(1);
    rlimit normal{};
    ASSERT_TRUE(boneless::test::limitFileSize(normal, 1024));
    const std::string error = errorOf([&] {
        PointCacheWriter pc2((dir / "w.pc2").string(), mesh.vertexCount(), 0, 1);
        for (int f = 0; f < 3; ++f) pc2.append(mesh.V);
        pc2.finish();
    });
    ASSERT_TRUE(boneless::test::restoreFileSize(normal));
    EXPECT_EQ(error, (dir / "w.pc2").string() + ": cannot be written (File too large)");
    EXPECT_TRUE(fs::is_empty(dir)) << "a failed write leaves no file behind";
}

namespace {

// A pid that no process has: a child's, once it has exited and been waited for.
pid_t deadPid() {
    const pid_t child = ::fork();
    if (child == 0) ::_exit(0);
    ::waitpid(child, nullptr, 0);
    return child;
}

std::string contents(const fs::path& file) {
    std::ifstream in(file, std::ios::binary);
    return std::string(std::istreambuf_iterator<char>(in), {});
}

// Writes one frame of `mesh` as w.pc2, w.mdd, w.glb and w.obj in `dir`.
void writeEachFormat(const fs::path& dir, const TriMesh& mesh) {
    PointCacheWriter pc2((dir / "w.pc2").string(), mesh.vertexCount(), 0, 1);
    pc2.append(mesh.V);
    pc2.finish();
    MddWriter mdd((dir / "w.mdd").string(), mesh.vertexCount());
    mdd.append(0, mesh.V);
    mdd.finish();
    GltfWriter glb((dir / "w.glb").string(), mesh, "w");
    glb.append(0, 0, mesh.V);
    glb.finish();
    writeObj((dir / "w.obj").string(), mesh.V, mesh.F, "test");
}

}  // namespace

// An export killed with SIGKILL (or by a power cut) left its temporary, `walker.pc2.tmp<pid>`,
// beside the user's files for good: hundreds of MB for a long take, and more with every such run.
TEST(FileWriters, RemoveTheTemporariesADeadProcessLeftForTheSameOutput) {
    const fs::path dir = freshTestDir("stale-temporaries"), clean = freshTestDir("no-temporaries");
    const TriMesh mesh = icosphere(1);
    // The live pid is not this test's own: that is the writer's, whose temporary is its to replace.
    const std::string dead = std::to_string(deadPid()), live = std::to_string(::getppid());
    const std::vector<std::string> outputs = {"w.pc2", "w.mdd", "w.glb", "w.obj"};
    std::vector<std::string> stale, kept = {"notes.txt",
                                            "w.pc2.tmp",
                                            "w.pc2.tmp" + dead + "x",
                                            "w.pc2.tmp0" + dead,
                                            "w.pc2.tmp-" + dead,
                                            "w.pc2.bak" + dead,
                                            "w.pc2.other.tmp" + dead,
                                            "other.pc2.tmp" + dead,
                                            "w.pc.tmp" + dead,
                                            "ww.pc2.tmp" + dead};
    for (const std::string& output : outputs)
        for (const std::string& suffix : {".tmp", ".frames.tmp"}) {
            stale.push_back(output + suffix + dead);
            kept.push_back(output + suffix + live);  // another export of the same file, running
        }
    for (const std::vector<std::string>* names : {&stale, &kept})
        for (const std::string& name : *names) std::ofstream(dir / name) << name;
    fs::create_directory(dir / ("v.obj.tmp" + dead));  // a folder is never a writer's temporary
    writeObj((dir / "v.obj").string(), mesh.V, mesh.F, "test");
    writeEachFormat(dir, mesh);
    writeEachFormat(clean, mesh);

    for (const std::string& name : stale) EXPECT_FALSE(fs::exists(dir / name)) << name;
    for (const std::string& name : kept) EXPECT_EQ(contents(dir / name), name) << name;
    EXPECT_TRUE(fs::is_directory(dir / ("v.obj.tmp" + dead)));
    for (const std::string& output : outputs)
        EXPECT_EQ(contents(dir / output), contents(clean / output)) << output;
    EXPECT_EQ(std::distance(fs::directory_iterator(dir), fs::directory_iterator{}),
              static_cast<std::ptrdiff_t>(kept.size() + outputs.size() + 2));
}

// MDD and glb spool the frames until the end; a spool with a name is one more file to leave
// behind when the export is killed.
TEST(FileWriters, SpoolTheFramesInAFileWithNoName) {
    const fs::path dir = freshTestDir("unnamed-spool");
    const TriMesh mesh = icosphere(1);
    MddWriter mdd((dir / "w.mdd").string(), mesh.vertexCount());
    GltfWriter glb((dir / "w.glb").string(), mesh, "w");
    mdd.append(0, mesh.V);
    glb.append(0, 0, mesh.V);
    EXPECT_TRUE(fs::is_empty(dir));
    mdd.finish();
    glb.finish();
    EXPECT_EQ(readMdd((dir / "w.mdd").string()).size(), 1u);
}

// Two exports of one file at once: the second's clean-up must leave the first's temporary alone,
// and each must finish whole (the last one renamed into place wins).
TEST(FileWriters, TwoExportsOfTheSameFileAtOnceBothFinish) {
    const fs::path dir = freshTestDir("two-exports");
    const std::string path = (dir / "w.pc2").string();
    const TriMesh mesh = icosphere(1);
    int started[2], go[2];
    ASSERT_EQ(::pipe(started), 0);
    ASSERT_EQ(::pipe(go), 0);
    const pid_t first = ::fork();
    if (first == 0) {  // the first export: one frame, then it waits for the second to finish
        char byte = 0;
        bool ok = true;
        try {
            PointCacheWriter writer(path, mesh.vertexCount(), 0, 1);
            writer.append(mesh.V);
            ok = ::write(started[1], &byte, 1) == 1 && ::read(go[0], &byte, 1) == 1;
            writer.append(mesh.V);
            writer.finish();
        } catch (...) {
            ok = false;
        }
        ::_exit(ok ? 0 : 1);
    }
    char byte = 0;
    ASSERT_EQ(::read(started[0], &byte, 1), 1);
    PointCacheWriter second(path, mesh.vertexCount(), 0, 1);
    second.append(mesh.V);
    second.finish();
    EXPECT_EQ(readPointCache(path).size(), 1u);
    ASSERT_EQ(::write(go[1], &byte, 1), 1);
    int status = 0;
    ASSERT_EQ(::waitpid(first, &status, 0), first);
    EXPECT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 0) << status;
    EXPECT_EQ(readPointCache(path).size(), 2u);
    for (int fd : {started[0], started[1], go[0], go[1]}) ::close(fd);
    EXPECT_EQ(std::distance(fs::directory_iterator(dir), fs::directory_iterator{}), 1);
}
