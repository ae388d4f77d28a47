#include <gtest/gtest.h>

#include <algorithm>
#include <limits>
#include <set>

#include "TestMeshes.h"
#include "boneless/Sampling.h"

using namespace boneless;
using namespace boneless::testing;

namespace {

// All-pairs edge distances by Floyd–Warshall: slow, obviously right, for small meshes only.
std::vector<std::vector<double>> allPairs(const TriMesh& m) {
    const int n = m.vertexCount();
    const double inf = std::numeric_limits<double>::infinity();
    std::vector<std::vector<double>> d(n, std::vector<double>(n, inf));
    for (int v = 0; v < n; ++v) d[v][v] = 0;
    for (int f = 0; f < m.faceCount(); ++f)
        for (int c = 0; c < 3; ++c) {
            const int a = m.F(f, c), b = m.F(f, (c + 1) % 3);
            d[a][b] = d[b][a] = (m.V.row(a) - m.V.row(b)).norm();
        }
    for (int k = 0; k < n; ++k)
        for (int i = 0; i < n; ++i)
            for (int j = 0; j < n; ++j) d[i][j] = std::min(d[i][j], d[i][k] + d[k][j]);
    return d;
}

}  // namespace

TEST(Sampling, GeodesicFarthestPointsMatchABruteForceDefinition) {
    const TriMesh mesh = tube(7, 9, 3.0);
    const auto d = allPairs(mesh);
    const auto picked = geodesicFarthestPoints(mesh, 12, 0);
    ASSERT_EQ(picked.size(), 12u);
    EXPECT_EQ(picked[0], 0);
    for (size_t i = 1; i < picked.size(); ++i) {
        // Expected: the vertex maximising the distance to the set so far, lowest id on ties.
        int best = -1;
        double bestDistance = -1;
        for (int v = 0; v < mesh.vertexCount(); ++v) {
            double toSet = std::numeric_limits<double>::infinity();
            for (size_t j = 0; j < i; ++j) toSet = std::min(toSet, d[v][picked[j]]);
            if (toSet > bestDistance + 1e-12) best = v, bestDistance = toSet;
        }
        EXPECT_EQ(picked[i], best) << "pick " << i;
    }
    EXPECT_EQ(std::set<int>(picked.begin(), picked.end()).size(), picked.size());
}

TEST(Sampling, EuclideanFarthestPointsSpreadOverTheShape) {
    const TriMesh mesh = icosphere(2);
    const auto picked = euclideanFarthestPoints(mesh.V, 2, 5);
    ASSERT_EQ(picked.size(), 2u);
    EXPECT_EQ(picked[0], 5);
    // On a sphere the farthest point from a vertex is (nearly) its antipode.
    EXPECT_NEAR((mesh.V.row(picked[0]) - mesh.V.row(picked[1])).norm(), 2.0, 1e-9);
}

TEST(Sampling, KIsCappedAtTheVertexCount) {
    const TriMesh mesh = icosphere(0);
    EXPECT_EQ(geodesicFarthestPoints(mesh, 100, 0).size(), 12u);
}
