// OBJ frames name their material library and its textures so that an importer that reads the
// OBJ specification word by word (Maya, Houdini) finds them, wherever the mesh lies.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>

#include "CliRunner.h"
#include "TestFiles.h"

using namespace boneless::testing;
namespace fs = std::filesystem;

namespace {

std::string quoted(const fs::path& path) {
    return "'" + path.string() + "'";
}

std::string textOf(const fs::path& file) {
    std::ifstream in(file, std::ios::binary);
    std::ostringstream text;
    text << in.rdbuf();
    return text.str();
}

// The words after `key` on each line that starts with it.
std::vector<std::vector<std::string>> wordsAfter(const fs::path& file, const std::string& key) {
    std::vector<std::vector<std::string>> lines;
    std::ifstream in(file);
    for (std::string line; std::getline(in, line);) {
        std::istringstream words(line);
        std::string first;
        if (!(words >> first) || first != key) continue;
        lines.emplace_back();
        for (std::string w; words >> w;) lines.back().push_back(w);
    }
    return lines;
}

// Each of the OBJ's mtllib words is a library, as the specification reads the line: every one
// must be a file, and each texture a map statement names (its last word, after the options) too.
void expectEveryNameIsAFile(const fs::path& obj) {
    const auto libraries = wordsAfter(obj, "mtllib");
    ASSERT_EQ(libraries.size(), 1u) << textOf(obj).substr(0, 200);
    ASSERT_EQ(libraries[0].size(), 1u) << obj << ": mtllib " << libraries[0].front() << " ...";
    const fs::path library = obj.parent_path() / libraries[0][0];
    ASSERT_TRUE(fs::is_regular_file(library)) << library;
    for (const std::string key : {"map_Kd", "map_Bump"}) {
        const auto maps = wordsAfter(library, key);
        ASSERT_EQ(maps.size(), 1u) << key << " in " << textOf(library);
        const fs::path texture = library.parent_path() / maps[0].back();
        EXPECT_TRUE(fs::is_regular_file(texture)) << key << " " << texture << "\n"
                                                  << textOf(library);
        EXPECT_EQ(textOf(texture), twoByTwoPng()) << texture;
    }
    EXPECT_EQ(wordsAfter(library, "map_Bump")[0].front(), "-bm");  // its options kept
}

}  // namespace

// "mtllib ../src dir/walker.mtl" is two libraries to Maya and Houdini, neither a file, and the
// frames lost their materials. A library whose path from the frames has a space is copied beside
// them under a name without one, its textures named so that they are found from there; a file of
// the user's under that name is left as it is.
TEST(ObjFrameMaterials, AMeshInAFolderWithASpaceGivesFramesWhoseEveryMtllibWordIsAFile) {
    const fs::path dir = freshTestDir("obj-frame-materials");
    ASSERT_EQ(runCli("demo --out " + dir.string() + " --frame-count 3").exitCode, 0);
    const fs::path src = dir / "src dir";
    fs::create_directories(src);
    fs::rename(dir / "walker.obj", src / "walker.obj");
    addTextureCoordinatesAndMaterial((src / "walker.obj").string(), "walker.mtl", "skin");
    std::ofstream(src / "walker.mtl")
        << "newmtl skin\nKd 0.8 0.6 0.5\nmap_Kd skin.png\nmap_Bump -bm 0.5 skin.png\n";
    std::ofstream(src / "skin.png", std::ios::binary) << twoByTwoPng();
    const fs::path out = dir / "out";
    fs::create_directories(out);
    std::ofstream(out / "walker.mtl") << "# the user's own\n";
    const CliResult solved =
        runCli("solve --quiet --frames 1:3 --write-calibrated-rest --mesh " +
               quoted(src / "walker.obj") + " --c3d " + quoted(dir / "walker.c3d") + " --map " +
               quoted(dir / "walker.map.json") + " --out " + quoted(out));
    ASSERT_EQ(solved.exitCode, 0) << solved.out;
    for (const char* frame : {"walker_0001.obj", "walker_0002.obj", "walker_calibrated_rest.obj"})
        expectEveryNameIsAFile(out / frame);
    EXPECT_EQ(textOf(out / "walker.mtl"), "# the user's own\n");
    // Solved again into the same folder, the copies are the same files, not more of them.
    const auto before = std::distance(fs::directory_iterator(out), fs::directory_iterator());
    ASSERT_EQ(runCli("solve --quiet --frames 1:3 --write-calibrated-rest --mesh " +
                     quoted(src / "walker.obj") + " --c3d " + quoted(dir / "walker.c3d") +
                     " --map " + quoted(dir / "walker.map.json") + " --out " + quoted(out))
                  .exitCode,
              0);
    EXPECT_EQ(std::distance(fs::directory_iterator(out), fs::directory_iterator()), before);
    expectEveryNameIsAFile(out / "walker_0001.obj");
}
