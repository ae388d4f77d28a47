// An OBJ's material libraries as readMesh reads them for the glb: colour, opacity, texture.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "TestFiles.h"
#include "boneless/MeshReader.h"
#include "boneless/ObjWriter.h"

using namespace boneless;
using namespace boneless::testing;
namespace fs = std::filesystem;

namespace {

const char* kTriangle = "v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nvt 1 0\nvt 0 1\n";

bool anyWarningHas(const MeshReadResult& r, const std::string& a, const std::string& b) {
    for (const std::string& w : r.warnings)
        if (w.find(a) != w.npos && w.find(b) != w.npos) return true;
    return false;
}

}  // namespace

TEST(MaterialLibrary, GivesEachMaterialItsColourOpacityAndTexture) {
    const fs::path dir = freshTestDir("mtl-read");
    fs::create_directories(dir / "looks" / "maps");
    std::ofstream(dir / "looks" / "maps" / "skin tone.png", std::ios::binary) << twoByTwoPng();
    std::ofstream(dir / "looks" / "maps" / "worn -bm 3", std::ios::binary) << twoByTwoPng();
    // Options before the file name, a name with a space, "Tr" as the inverse of "d".
    // Ns as Blender's OBJ importer reads it (roughness 1 − √(Ns / 1000)); map_Bump and bump as
    // normal maps, with -bm as their strength.
    std::ofstream(dir / "looks" / "body.mtl")
        << "# exported\nnewmtl skin\nKd 0.9 0.7 0.6\nmap_Kd -s 1 1 1 -clamp on maps/skin tone.png\n"
           "Ns 250\nmap_Bump -o 0 0 0 -bm 0.5 maps/skin tone.png\n"
           "newmtl glass pane\nKd 0.1 0.2 0.3\nTr 0.25\nNs 4000\nbump maps/skin tone.png\n"
           "newmtl lacquer\nillum 2\nmap_bump -bm 2 maps/skin tone.png\n"
           "newmtl satin\nNs 90\nillum 2\n"
           "newmtl worn\nbump maps/worn -bm 3\n";  // "-bm 3" is part of the file's name
    std::ofstream(dir / "body.obj") << "mtllib looks/body.mtl\n"
                                    << kTriangle << "v 1 1 0\nusemtl skin\nf 1/1 2/2 3/3\n"
                                    << "usemtl glass pane\nf 2/2 4/1 3/3\n";
    const MeshReadResult r = readMesh((dir / "body.obj").string());
    ASSERT_NE(r.mesh.sourceFaces, nullptr);
    const std::vector<ObjMaterial>& m = r.mesh.sourceFaces->materialDefinitions;
    ASSERT_EQ(m.size(), 5u);
    EXPECT_EQ(m[0].name, "skin");
    EXPECT_EQ(m[0].colour, (std::array<double, 3>{0.9, 0.7, 0.6}));
    EXPECT_EQ(m[0].opacity, 1.0);
    EXPECT_EQ(fs::path(m[0].texture), fs::absolute(dir / "looks" / "maps" / "skin tone.png"));
    EXPECT_DOUBLE_EQ(m[0].roughness, 0.5);
    EXPECT_EQ(m[0].normalTexture, m[0].texture);
    EXPECT_DOUBLE_EQ(m[0].normalScale, 0.5);
    EXPECT_EQ(m[1].name, "glass pane");
    EXPECT_DOUBLE_EQ(m[1].opacity, 0.75);
    EXPECT_TRUE(m[1].texture.empty());
    EXPECT_DOUBLE_EQ(m[1].roughness, 0.0);  // Ns beyond 1000 is as smooth as 1000
    EXPECT_EQ(m[1].normalTexture, m[0].texture);
    EXPECT_DOUBLE_EQ(m[1].normalScale, 1.0);
    // "illum 2" without Ns is smooth to Blender; with Ns, Ns decides (checked headless).
    EXPECT_EQ(m[2].roughness, 0.0);
    EXPECT_EQ(m[2].normalTexture, m[0].texture);
    EXPECT_DOUBLE_EQ(m[2].normalScale, 2.0);
    EXPECT_DOUBLE_EQ(m[3].roughness, 0.7);
    EXPECT_EQ(fs::path(m[4].normalTexture), fs::absolute(dir / "looks" / "maps" / "worn -bm 3"));
    EXPECT_DOUBLE_EQ(m[4].normalScale, 1.0);
    EXPECT_FALSE(anyWarningHas(r, "body.mtl", ""));  // only the open strip's boundary
}

TEST(MaterialLibrary, WhatItCannotUseIsAWarningNamingTheFileAndTheMeshStillReads) {
    const fs::path dir = freshTestDir("mtl-warn");
    std::ofstream(dir / "a.tga", std::ios::binary) << "not a png at all";
    std::ofstream(dir / "m.mtl") << "Kd 1 1 1\nnewmtl a\nKd 0.5 x\nmap_Kd a.tga\n"
                                    "newmtl b\nmap_Kd gone.png\nKd 0.2 0.4\n";
    // m.mtl twice: read once. "c" is used but defined nowhere.
    std::ofstream(dir / "t.obj") << "mtllib m.mtl missing.mtl m.mtl\n"
                                 << kTriangle << "v 1 1 0\nusemtl a\nf 1/1 2/2 3/3\n"
                                 << "usemtl c\nf 2/2 4/1 3/3\n";
    const MeshReadResult r = readMesh((dir / "t.obj").string());
    ASSERT_NE(r.mesh.sourceFaces, nullptr);
    EXPECT_EQ(r.mesh.faceCount(), 2);
    const std::string lib = (dir / "m.mtl").string();
    EXPECT_TRUE(anyWarningHas(r, lib + " line 1", "before any newmtl"));
    EXPECT_TRUE(anyWarningHas(r, lib + " line 3", "Kd needs one or three numbers"));
    EXPECT_TRUE(anyWarningHas(r, lib + " line 7", "Kd needs one or three numbers"));
    EXPECT_TRUE(anyWarningHas(r, lib + " line 4", "neither PNG nor JPEG"));
    EXPECT_TRUE(anyWarningHas(r, lib + " line 6", "gone.png not found"));
    EXPECT_TRUE(anyWarningHas(r, "missing.mtl", "cannot be read"));
    EXPECT_TRUE(anyWarningHas(r, "material 'c'", "no mtllib defines it"));
    int fromLibrary = 0;
    for (const std::string& w : r.warnings) fromLibrary += w.rfind(lib, 0) == 0;
    EXPECT_EQ(fromLibrary, 5);  // not twice
    const std::vector<ObjMaterial>& m = r.mesh.sourceFaces->materialDefinitions;
    ASSERT_EQ(m.size(), 3u);  // a and b, then a default for c
    EXPECT_EQ(m[0].colour, (std::array<double, 3>{0.8, 0.8, 0.8}));  // the bad Kd left as default
    EXPECT_TRUE(m[0].texture.empty());
    EXPECT_TRUE(m[1].texture.empty());
    EXPECT_EQ(m[1].colour, (std::array<double, 3>{0.8, 0.8, 0.8}));  // two numbers: not a colour
    EXPECT_EQ(m[2].name, "c");
    EXPECT_EQ(r.mesh.sourceFaces->materials, (std::vector<std::pair<int, int>>{{0, 0}, {1, 2}}));
}

TEST(MaterialLibrary, MaterialsWithoutAnyLibraryAreNoted) {
    const fs::path dir = freshTestDir("mtl-none");
    std::ofstream(dir / "t.obj") << kTriangle << "usemtl skin\nf 1/1 2/2 3/3\n";
    const MeshReadResult r = readMesh((dir / "t.obj").string());
    EXPECT_TRUE(anyWarningHas(r, "usemtl", "names no material library"));
}

TEST(MaterialLibrary, ShortFormsAreReadAndABrokenLibraryGivesAFewNotesNotOneALine) {
    const fs::path dir = freshTestDir("mtl-short");
    std::ofstream(dir / "tex.png", std::ios::binary) << twoByTwoPng();
    std::string mtl = "newmtl grey\nKd 0.25\nd -halo 0.5\nmap_Kd tex.png\n";
    for (int k = 0; k < 20; ++k) mtl += "Kd ?\n";
    std::ofstream(dir / "m.mtl") << mtl;
    // No vt: the texture has nothing to place it.
    std::ofstream(dir / "t.obj")
        << "mtllib m.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nusemtl grey\nf 1 2 3\n";
    const MeshReadResult r = readMesh((dir / "t.obj").string());
    ASSERT_NE(r.mesh.sourceFaces, nullptr);
    const ObjMaterial& grey = r.mesh.sourceFaces->materialDefinitions.at(0);
    EXPECT_EQ(grey.colour, (std::array<double, 3>{0.25, 0.25, 0.25}));
    EXPECT_DOUBLE_EQ(grey.opacity, 0.5);
    EXPECT_TRUE(anyWarningHas(r, "material 'grey' has a texture", "no texture coordinates"));
    int kd = 0;
    for (const std::string& w : r.warnings) kd += w.find("Kd needs one or three") != w.npos;
    EXPECT_EQ(kd, 5);
    EXPECT_TRUE(anyWarningHas(r, "m.mtl: 15 more lines", ""));
}

// A folder reached through a link: "lnk/../mats" is beside the link's target, where opening it
// looks, and the paths were tidied as text to "mats" beside the link. The mesh in a linked folder
// lost its library ("cannot be read", naming a path the file never gave), and OBJ frames written
// into a linked folder named theirs by a path that led nowhere.
TEST(MaterialLibrary, AFolderReachedThroughALinkIsFollowedAsTheSystemFollowsIt) {
    const fs::path dir = fs::absolute(freshTestDir("mtl-link"));
    fs::create_directories(dir / "real" / "deep");
    fs::create_directories(dir / "real" / "mats");
    fs::create_directory_symlink(dir / "real" / "deep", dir / "lnk");
    std::ofstream(dir / "real" / "mats" / "w.mtl") << "newmtl skin\nKd 0.9 0.7 0.6\n";
    std::ofstream(dir / "real" / "deep" / "body.obj")
        << "mtllib ../mats/w.mtl\n"
        << kTriangle << "usemtl skin\nf 1/1 2/2 3/3\n";
    const MeshReadResult r = readMesh((dir / "lnk" / "body.obj").string());
    for (const std::string& w : r.warnings)  // a lone triangle's open surface aside
        EXPECT_EQ(w.find("material"), std::string::npos) << w;
    ASSERT_NE(r.mesh.sourceFaces, nullptr);
    ASSERT_EQ(r.mesh.sourceFaces->materialDefinitions.size(), 1u);
    EXPECT_EQ(r.mesh.sourceFaces->materialDefinitions[0].colour,
              (std::array<double, 3>{0.9, 0.7, 0.6}));

    // Written into another link to the same folder, and into the folder itself: each frame's
    // mtllib opens the library from where the frame is.
    fs::create_directory_symlink(dir / "real" / "deep", dir / "out");
    for (const fs::path& frame : {dir / "out" / "f.obj", dir / "real" / "f2.obj"}) {
        writeObj(frame.string(), r.mesh.V, r.mesh.F, "test", r.mesh.sourceFaces.get());
        std::ifstream in(frame);
        std::string line;
        while (std::getline(in, line) && line.rfind("mtllib ", 0) != 0) {
        }
        ASSERT_EQ(line.rfind("mtllib ", 0), 0u) << frame;
        EXPECT_TRUE(fs::is_regular_file(frame.parent_path() / line.substr(7))) << line;
    }
}

// .NET's writers start a file with a byte-order mark: it hid the first newmtl, whose material then
// came out grey, and the copy written for an OBJ frame kept the mark after its own first line.
TEST(MaterialLibrary, AByteOrderMarkHidesNoMaterial) {
    const fs::path dir = freshTestDir("mtl-bom");
    std::ofstream(dir / "skin tone.mtl") << "\xEF\xBB\xBFnewmtl Skin\r\nKd 0.8 0.6 0.5\r\n";
    std::ofstream(dir / "t.obj") << "mtllib skin tone.mtl\n"
                                 << kTriangle << "usemtl Skin\nf 1/1 2/2 3/3\n";
    const MeshReadResult r = readMesh((dir / "t.obj").string());
    ASSERT_NE(r.mesh.sourceFaces, nullptr);
    EXPECT_FALSE(anyWarningHas(r, "skin tone.mtl", ""));
    const std::vector<ObjMaterial>& m = r.mesh.sourceFaces->materialDefinitions;
    ASSERT_EQ(m.size(), 1u);
    EXPECT_EQ(m[0].name, "Skin");
    EXPECT_EQ(m[0].colour, (std::array<double, 3>{0.8, 0.6, 0.5}));
    const fs::path out = dir / "out";
    fs::create_directories(out);
    const SourceFaces copy = withLibraryCopies(*r.mesh.sourceFaces, out.string());
    ASSERT_EQ(copy.materialLibraries.size(), 1u);
    std::ifstream in(copy.materialLibraries[0], std::ios::binary);
    const std::string text{std::istreambuf_iterator<char>(in), {}};
    EXPECT_EQ(text.find("\xEF\xBB\xBF"), std::string::npos);
    EXPECT_EQ(text.find('\r'), std::string::npos);
    EXPECT_NE(text.find("\nnewmtl Skin\n"), std::string::npos) << text;
}
