#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <functional>

#include "TestMeshes.h"
#include "boneless/Error.h"
#include "boneless/MeshSequence.h"
#include "boneless/ObjWriter.h"

using namespace boneless;
using namespace boneless::testing;
namespace fs = std::filesystem;

namespace {

// Frame `i` of a test sequence: the icosphere moved i units along x, so a frame read tells its
// number.
void writeFrame(const fs::path& file, int i) {
    const TriMesh sphere = icosphere(1);
    Positions V = sphere.V;
    V.col(0).array() += i;
    writeObj(file.string(), V, sphere.F, "");
}

std::string errorOf(const std::function<void()>& f) {
    try {
        f();
    } catch (const std::exception& e) {
        return e.what();
    }
    return {};
}

}  // namespace

// Houdini writes frame_1.obj … frame_12.obj unpadded; a plain text sort read them 1, 10, 11,
// 12, 2, …, silently.
TEST(MeshSequenceOrder, UnpaddedFrameNumbersAreReadInNumberOrder) {
    const fs::path dir = freshTestDir("unpadded");
    for (int i = 1; i <= 12; ++i) writeFrame(dir / ("frame_" + std::to_string(i) + ".obj"), i);
    const MeshSequence sequence = readMeshSequence(dir.string());
    ASSERT_EQ(sequence.frames.size(), 12u);
    for (int i = 0; i < 12; ++i) {
        EXPECT_EQ(fs::path(sequence.files[i]).filename().string(),
                  "frame_" + std::to_string(i + 1) + ".obj");
        EXPECT_DOUBLE_EQ(sequence.frames[i](0, 0) - sequence.rest.V(0, 0), i) << "frame " << i;
    }
}

// Names of two patterns (or one number written twice) give no order to read them in: refused,
// naming the folder and two of the files, rather than guessed.
TEST(MeshSequenceOrder, NamesOfMixedPatternsAreRefusedNamingTwoOfThem) {
    const fs::path dir = freshTestDir("mixed");
    writeFrame(dir / "walk_1.obj", 1);
    writeFrame(dir / "walk_2.obj", 2);
    writeFrame(dir / "rest.obj", 0);
    const std::string why = errorOf([&] { readMeshSequence(dir.string()); });
    EXPECT_NE(why.find(dir.string()), std::string::npos) << why;
    EXPECT_NE(why.find("rest.obj"), std::string::npos) << why;
    EXPECT_NE(why.find("walk_1.obj"), std::string::npos) << why;
    EXPECT_NE(why.find("no frame order"), std::string::npos) << why;

    const fs::path twice = freshTestDir("twice");
    writeFrame(twice / "walk_1.obj", 1);
    writeFrame(twice / "walk_01.obj", 1);
    const std::string same = errorOf([&] { readMeshSequence(twice.string()); });
    EXPECT_NE(same.find("walk_01.obj"), std::string::npos) << same;
    EXPECT_NE(same.find("walk_1.obj"), std::string::npos) << same;
}
