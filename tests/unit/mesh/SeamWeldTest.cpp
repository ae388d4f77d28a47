// The mesh reader welds the copies a file splits its vertices into at UV seams (one vertex per
// position and texture coordinate), but never two surfaces that merely touch.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>

#include "boneless/MeshReader.h"

using namespace boneless;
namespace fs = std::filesystem;

namespace {

std::string writeObj(const std::string& name, const Positions& V,
                     const std::vector<std::vector<int>>& polygons, bool uvs = false) {
    const fs::path dir = fs::path(BONELESS_TEST_WORK_DIR) / "seam-weld";
    fs::create_directories(dir);
    std::ostringstream s;
    s.precision(17);
    for (int i = 0; i < V.rows(); ++i)
        s << "v " << V(i, 0) << ' ' << V(i, 1) << ' ' << V(i, 2) << '\n';
    if (uvs)  // one coordinate per vertex, as a seam-splitting exporter writes them
        for (int i = 0; i < V.rows(); ++i) s << "vt " << i * 0.01 << " 0.5\n";
    for (const auto& p : polygons) {
        s << 'f';
        for (int v : p) {
            s << ' ' << v + 1;
            if (uvs) s << '/' << v + 1;
        }
        s << '\n';
    }
    const std::string path = (dir / name).string();
    std::ofstream(path) << s.str();
    return path;
}

// An octahedron: poles 0 (top) and 5 (bottom), equator 1-4.
Positions octahedron() {
    Positions V(6, 3);
    V << 0, 0, 1, 1, 0, 0, 0, 1, 0, -1, 0, 0, 0, -1, 0, 0, 0, -1;
    return V;
}
const std::vector<std::vector<int>> kTop{{0, 1, 2}, {0, 2, 3}, {0, 3, 4}, {0, 4, 1}};
const std::vector<std::vector<int>> kBottom{{5, 2, 1}, {5, 3, 2}, {5, 4, 3}, {5, 1, 4}};

// The octahedron split at its equator: the bottom faces use copies 6-9 of equator vertices 1-4.
std::string splitOctahedron(const std::string& name, const Positions& copyOffset) {
    const Positions O = octahedron();
    Positions V(10, 3);
    V.topRows(6) = O;
    for (int k = 0; k < 4; ++k) V.row(6 + k) = O.row(1 + k) + copyOffset.row(k);
    std::vector<std::vector<int>> faces = kTop;
    for (auto f : kBottom) {
        for (int& v : f)
            if (v >= 1 && v <= 4) v += 5;
        faces.push_back(f);
    }
    return writeObj(name, V, faces, true);
}

}  // namespace

TEST(SeamWeld, ACopyPerPositionAndUvReadsAsOneClosedSurfaceWithTheFilesVertices) {
    const MeshReadResult whole = readMesh(writeObj("octahedron.obj", octahedron(), [] {
        auto f = kTop;
        f.insert(f.end(), kBottom.begin(), kBottom.end());
        return f;
    }()));
    const MeshReadResult r = readMesh(splitOctahedron("split.obj", Positions::Zero(4, 3)));
    EXPECT_EQ(r.mesh.vertexCount(), 10);  // the file's count and order
    EXPECT_EQ(r.mesh.V.topRows(6), octahedron());
    EXPECT_EQ(r.weldedVertices, 4);
    EXPECT_EQ(r.mesh.weldedTo, (std::vector<int>{0, 1, 2, 3, 4, 5, 1, 2, 3, 4}));
    EXPECT_EQ(r.mesh.F, whole.mesh.F);  // the first copy stands for the others
    EXPECT_EQ(r.boundaryEdges, 0);
    EXPECT_EQ(r.components, 1);
    EXPECT_EQ(r.isolatedVertices, 0);
    ASSERT_FALSE(r.warnings.empty());
    EXPECT_EQ(r.warnings.back(),
              "welded 4 vertices that share a position with another (split UV seams)");
    // The polygons keep naming the copies, whose texture coordinates tell them apart.
    ASSERT_TRUE(r.mesh.sourceFaces);
    EXPECT_EQ(r.mesh.sourceFaces->corners[12], 5);
    EXPECT_EQ(r.mesh.sourceFaces->corners[13], 7);
}

// Exporters write a vertex's copies from the same number, but a round trip through text may
// leave them a last digit apart; copies a visible distance apart are not one vertex.
TEST(SeamWeld, CopiesWithinAMillionthOfTheSizeAreWeldedAndFartherOnesAreNot) {
    const Positions close = Positions::Constant(4, 3, 1e-9);
    EXPECT_EQ(readMesh(splitOctahedron("close.obj", close)).weldedVertices, 4);
    const MeshReadResult apart =
        readMesh(splitOctahedron("apart.obj", 1e-3 * Positions::Ones(4, 3)));
    EXPECT_EQ(apart.weldedVertices, 0);
    EXPECT_TRUE(apart.mesh.weldedTo.empty());
    EXPECT_EQ(apart.boundaryEdges, 8);
}

// Two closed pyramids whose apexes touch: welding the apexes would make a vertex with two fans.
TEST(SeamWeld, TwoSurfacesTouchingAtOnePointAreNotWeldedIntoANonManifoldVertex) {
    Positions V(8, 3);
    V << 0, 0, 0, 1, 0, -1, -1, 1, -1, -1, -1, -1,  // apex up, base below
        0, 0, 0, 1, 0, 1, -1, -1, 1, -1, 1, 1;      // its mirror image above
    const MeshReadResult r = readMesh(writeObj(
        "touching.obj", V,
        {{0, 1, 2}, {0, 2, 3}, {0, 3, 1}, {1, 3, 2}, {4, 5, 6}, {4, 6, 7}, {4, 7, 5}, {5, 7, 6}}));
    EXPECT_EQ(r.weldedVertices, 0);
    EXPECT_EQ(r.components, 2);
    EXPECT_EQ(r.boundaryEdges, 0);
    for (const std::string& w : r.warnings) EXPECT_EQ(w.find("welded"), std::string::npos) << w;
}

// Three sheets hinged on one edge, each with its own copies of the edge's ends: welded, the edge
// would have three faces.
TEST(SeamWeld, ThreeSheetsMeetingAtOneEdgeAreNotWeldedIntoANonManifoldEdge) {
    Positions V(12, 3);
    V << 0, 0, 0, 0, 0, 1, 1, 0, 0, 1, 0, 1,   //
        0, 0, 0, 0, 0, 1, -1, 1, 0, -1, 1, 1,  //
        0, 0, 0, 0, 0, 1, -1, -1, 0, -1, -1, 1;
    const MeshReadResult r =
        readMesh(writeObj("hinged.obj", V, {{0, 2, 3, 1}, {4, 5, 7, 6}, {8, 9, 11, 10}}));
    EXPECT_EQ(r.weldedVertices, 0);
    EXPECT_EQ(r.components, 3);
}
