// Blender 3.4, headless, as the client: each export format read back the way a user would, at the
// first, middle and last frame exported (tests/blender/read_export.py). Skipped without Blender.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "CliRunner.h"
#include "TestFiles.h"

using namespace boneless::testing;
namespace fs = std::filesystem;

namespace {

bool haveBlender() {
    return runShell("command -v blender >/dev/null 2>&1").exitCode == 0;
}

// Solves take frames 2..11 of a 12-frame demo into OBJ (the reference, exact digits) and `format`,
// then has Blender read the export at frames 2, 7 and 11 (and a glb's walker stand upright).
void checkInBlender(const std::string& format) {
    if (!haveBlender()) GTEST_SKIP() << "blender is not installed (scripts/install-deps.sh)";
    const fs::path dir = freshTestDir("blender-" + format);
    ASSERT_EQ(runCli("demo --out " + dir.string() + " --frame-count 12").exitCode, 0);
    auto solve = [&](const std::string& f) {
        const CliResult r =
            runCli("solve --quiet --frames 2:12 --format " + f + " --mesh " +
                   (dir / "walker.obj").string() + " --c3d " + (dir / "walker.c3d").string() +
                   " --map " + (dir / "walker.map.json").string() + " --out " + (dir / f).string());
        ASSERT_EQ(r.exitCode, 0) << r.out;
    };
    solve("obj");
    if (format != "obj") solve(format);
    const double fps =
        nlohmann::json::parse(std::ifstream(dir / "obj" / "walker.json"))["fps"].get<double>();
    const std::string exported =
        format == "obj" ? (dir / "obj").string() : (dir / format / ("walker." + format)).string();
    const CliResult r =
        runShell("blender -b --factory-startup --python " BONELESS_SOURCE_DIR
                 "/tests/blender/read_export.py -- " +
                 format + " " + exported + " " + (dir / "obj").string() + " walker " +
                 std::to_string(static_cast<int>(fps)) + " 2,7,11 2>&1");
    EXPECT_EQ(r.exitCode, 0) << r.out;
    EXPECT_NE(r.out.find(format + ": frames [2, 7, 11] read back within"), std::string::npos)
        << r.out;
}

}  // namespace

TEST(BlenderReads, TheObjSequenceFrameByFrame) {
    checkInBlender("obj");
}

TEST(BlenderReads, ThePc2CacheThroughItsMeshCacheModifier) {
    checkInBlender("pc2");
}

TEST(BlenderReads, TheMddCacheThroughItsMeshCacheModifier) {
    checkInBlender("mdd");
}

TEST(BlenderReads, TheGlbAnimationThroughItsGltfImporter) {
    checkInBlender("glb");
}

// MakeHuman's body as an artist's file: its OBJ frames come into Blender as the input's quads,
// with their texture coordinates, on the input's vertices. Skipped without the shared data.
TEST(BlenderReads, ObjFramesAsTheInputsQuadsWithTheirUvs) {
    if (!haveBlender()) GTEST_SKIP() << "blender is not installed (scripts/install-deps.sh)";
    const fs::path data = BONELESS_SHARED_DATA;
    const fs::path mesh = data / "meshes" / "makehuman" / "makehuman_base.obj";
    const fs::path take = data / "c3d" / "cmu" / "85_02.c3d";
    if (!fs::exists(mesh) || !fs::exists(take)) GTEST_SKIP() << "no shared data (" << data << ")";
    const fs::path out = freshTestDir("blender-quads");
    const CliResult solved = runCli("solve --quiet --frames 300:301 --mesh " + mesh.string() +
                                    " --group body --c3d " + take.string() +
                                    " --map " BONELESS_SOURCE_DIR
                                    "/tests/data/cmu-85_02-makehuman-body.map.json --out " +
                                    out.string());
    ASSERT_EQ(solved.exitCode, 0) << solved.out;
    const CliResult r = runShell("blender -b --factory-startup --python " BONELESS_SOURCE_DIR
                                 "/tests/blender/read_obj_faces.py -- " +
                                 (out / "body_0300.obj").string() + " 2>&1");
    EXPECT_EQ(r.exitCode, 0) << r.out;
    EXPECT_NE(r.out.find("faces: 13380 vertices, 13378 polygons, 13378 quads, 1 uv layers"),
              std::string::npos)
        << r.out;
}

// A textured character for Unity or the web: the OBJ's material and its PNG come with the .glb,
// as rough and with the same normal map as Blender reads the OBJ itself.
TEST(BlenderReads, TheGlbWithTheObjsMaterialAndItsTexture) {
    if (!haveBlender()) GTEST_SKIP() << "blender is not installed (scripts/install-deps.sh)";
    const fs::path dir = freshTestDir("blender-glb-material");
    ASSERT_EQ(runCli("demo --out " + dir.string() + " --frame-count 3").exitCode, 0);
    addTextureCoordinatesAndMaterial((dir / "walker.obj").string(), "walker.mtl", "skin");
    std::ofstream(dir / "walker.mtl")
        << "newmtl skin\nKd 0.8 0.6 0.5\nmap_Kd skin.png\nNs 250\nmap_Bump -bm 0.5 skin.png\n";
    std::ofstream(dir / "skin.png", std::ios::binary) << twoByTwoPng();
    const CliResult solved =
        runCli("solve --quiet --frames 1:3 --format glb --mesh " + (dir / "walker.obj").string() +
               " --c3d " + (dir / "walker.c3d").string() + " --map " +
               (dir / "walker.map.json").string() + " --out " + (dir / "glb").string());
    ASSERT_EQ(solved.exitCode, 0) << solved.out;
    const auto read = [](const fs::path& file) {
        return runShell("blender -b --factory-startup --python " BONELESS_SOURCE_DIR
                        "/tests/blender/read_glb_material.py -- " +
                        file.string() + " 2>&1");
    };
    const CliResult r = read(dir / "glb" / "walker.glb");
    EXPECT_EQ(r.exitCode, 0) << r.out;
    EXPECT_NE(r.out.find("material skin: image 2x2 packed True, roughness 0.50, normal map 0.50"),
              std::string::npos)
        << r.out;
    const CliResult obj = read(dir / "walker.obj");
    EXPECT_EQ(obj.exitCode, 0) << obj.out;
    EXPECT_NE(obj.out.find("roughness 0.50, normal map 0.50"), std::string::npos) << obj.out;
}

// OBJ frames of a mesh in a folder named with a space name a copy of its library beside them
// (ObjFrameMaterials): Blender finds the material and its texture through it.
TEST(BlenderReads, ObjFramesOfAMeshInAFolderWithASpaceWithTheirMaterialAndTexture) {
    if (!haveBlender()) GTEST_SKIP() << "blender is not installed (scripts/install-deps.sh)";
    const fs::path dir = freshTestDir("blender-obj-material");
    ASSERT_EQ(runCli("demo --out " + dir.string() + " --frame-count 3").exitCode, 0);
    const fs::path src = dir / "src dir";
    fs::create_directories(src);
    fs::rename(dir / "walker.obj", src / "walker.obj");
    addTextureCoordinatesAndMaterial((src / "walker.obj").string(), "walker.mtl", "skin");
    std::ofstream(src / "walker.mtl") << "newmtl skin\nKd 0.8 0.6 0.5\nmap_Kd skin.png\n";
    std::ofstream(src / "skin.png", std::ios::binary) << twoByTwoPng();
    const CliResult solved =
        runCli("solve --quiet --frames 1:2 --mesh '" + (src / "walker.obj").string() + "' --c3d " +
               (dir / "walker.c3d").string() + " --map " + (dir / "walker.map.json").string() +
               " --out " + (dir / "out").string());
    ASSERT_EQ(solved.exitCode, 0) << solved.out;
    const CliResult r = runShell("blender -b --factory-startup --python " BONELESS_SOURCE_DIR
                                 "/tests/blender/read_glb_material.py -- " +
                                 (dir / "out" / "walker_0001.obj").string() + " 2>&1");
    EXPECT_EQ(r.exitCode, 0) << r.out;
    EXPECT_NE(r.out.find("material skin: image 2x2 packed False"), std::string::npos) << r.out;
}
