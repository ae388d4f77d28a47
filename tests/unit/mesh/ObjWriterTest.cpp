#include <gtest/gtest.h>

#include <filesystem>
#include <random>

#include "TestMeshes.h"
#include "boneless/Error.h"
#include "boneless/MeshReader.h"
#include "boneless/ObjWriter.h"

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
