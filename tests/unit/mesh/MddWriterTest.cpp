#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "TestMeshes.h"
#include "boneless/Error.h"
#include "boneless/MddWriter.h"

using namespace boneless;
using namespace boneless::testing;
namespace fs = std::filesystem;

TEST(MddCache, RoundTripsFramesAndTimesInTheBigEndianLayout) {
    const fs::path dir = freshTestDir("mdd");
    const std::string path = (dir / "sphere.mdd").string();
    const TriMesh mesh = icosphere(1);
    {
        MddWriter writer(path, mesh.vertexCount());
        writer.append(0.25, mesh.V);
        writer.append(0.5, 2.0 * mesh.V);
        EXPECT_FALSE(fs::exists(path));  // nothing at the final name before finish()
        writer.finish();
    }
    EXPECT_EQ(fs::file_size(path), 8u + 2u * 4u + 2u * mesh.vertexCount() * 12u);
    unsigned char head[8];
    std::ifstream(path, std::ios::binary).read(reinterpret_cast<char*>(head), 8);
    EXPECT_EQ(head[3], 2);  // frame count, most significant byte first
    EXPECT_EQ((head[6] << 8) | head[7], mesh.vertexCount());
    std::vector<double> seconds;
    const auto frames = readMdd(path, &seconds);
    ASSERT_EQ(frames.size(), 2u);
    EXPECT_EQ(seconds, (std::vector<double>{0.25, 0.5}));
    EXPECT_LT((frames[1] - 2.0 * mesh.V).cwiseAbs().maxCoeff(), 1e-6);  // float32 storage
    EXPECT_EQ(std::distance(fs::directory_iterator(dir), fs::directory_iterator{}), 1);
}

TEST(MddCache, AnAbandonedCacheLeavesNothingBehind) {
    const fs::path dir = freshTestDir("mdd-abandoned");
    const TriMesh mesh = icosphere(0);
    {
        MddWriter writer((dir / "x.mdd").string(), mesh.vertexCount());
        writer.append(0, mesh.V);
        EXPECT_THROW(writer.append(0.1, mesh.V.topRows(3)), Error);  // wrong point count
    }
    EXPECT_TRUE(fs::is_empty(dir));
}
