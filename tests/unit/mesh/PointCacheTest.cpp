#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "TestMeshes.h"
#include "boneless/Error.h"
#include "boneless/PointCacheWriter.h"

using namespace boneless;
using namespace boneless::testing;
namespace fs = std::filesystem;

TEST(PointCache, RoundTripsFramesWithTheDocumentedLayout) {
    const fs::path dir = freshTestDir("pc2");
    const std::string path = (dir / "sphere.pc2").string();
    const TriMesh mesh = icosphere(1);
    {
        PointCacheWriter writer(path, mesh.vertexCount(), 7.0);
        writer.append(mesh.V);
        writer.append(2.0 * mesh.V);
        EXPECT_FALSE(fs::exists(path));  // nothing at the final name before finish()
        writer.finish();
    }
    EXPECT_EQ(fs::file_size(path), 32u + 2u * mesh.vertexCount() * 12u);
    double start = 0;
    const auto frames = readPointCache(path, &start);
    ASSERT_EQ(frames.size(), 2u);
    EXPECT_EQ(start, 7.0);
    EXPECT_LT((frames[1] - 2.0 * mesh.V).cwiseAbs().maxCoeff(), 1e-6);  // float32 storage
    EXPECT_EQ(std::distance(fs::directory_iterator(dir), fs::directory_iterator{}), 1);
}

TEST(PointCache, AnAbandonedCacheLeavesNothingBehind) {
    const fs::path dir = freshTestDir("pc2-abandoned");
    const TriMesh mesh = icosphere(0);
    {
        PointCacheWriter writer((dir / "x.pc2").string(), mesh.vertexCount(), 0.0);
        writer.append(mesh.V);
        EXPECT_THROW(writer.append(mesh.V.topRows(3)), Error);  // wrong point count
    }
    EXPECT_TRUE(fs::is_empty(dir));
}
