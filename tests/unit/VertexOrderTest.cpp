// The spatial order the multiresolution solver works in on large meshes: a permutation that keeps
// every face (with its orientation), faces in the order of their sorted vertices, and positions
// that go in and come back out unchanged.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <numeric>
#include <random>
#include <set>

#include "TestMeshes.h"
#include "VertexOrder.h"

namespace boneless::testing {
namespace {

// The mesh with its vertices and faces shuffled, so that its order is far from a spatial one.
TriMesh shuffled(const TriMesh& mesh, unsigned seed) {
    std::mt19937 rng(seed);
    std::vector<int> newIndex(mesh.vertexCount());
    std::iota(newIndex.begin(), newIndex.end(), 0);
    std::shuffle(newIndex.begin(), newIndex.end(), rng);
    TriMesh out;
    out.V.resize(mesh.vertexCount(), 3);
    for (int v = 0; v < mesh.vertexCount(); ++v) out.V.row(newIndex[v]) = mesh.V.row(v);
    std::vector<int> faceOrder(mesh.faceCount());
    std::iota(faceOrder.begin(), faceOrder.end(), 0);
    std::shuffle(faceOrder.begin(), faceOrder.end(), rng);
    out.F.resize(mesh.faceCount(), 3);
    for (int f = 0; f < mesh.faceCount(); ++f)
        for (int c = 0; c < 3; ++c) out.F(f, c) = newIndex[mesh.F(faceOrder[f], c)];
    return out;
}

// A face as a cyclic triple started at its smallest vertex: equal for the same orientation.
std::array<int, 3> cyclic(int a, int b, int c) {
    if (b < a && b < c) return {b, c, a};
    if (c < a && c < b) return {c, a, b};
    return {a, b, c};
}

}  // namespace

TEST(VertexOrder, KeepsEveryFaceAndSortsThemByTheirVertices) {
    const TriMesh mesh = shuffled(icosphere(3), 5);
    const VertexOrder order = VertexOrder::spatial(mesh);
    const TriMesh out = order.apply(mesh);
    ASSERT_EQ(out.faceCount(), mesh.faceCount());

    const std::vector<int> all = [&] {
        std::vector<int> ids(mesh.vertexCount());
        std::iota(ids.begin(), ids.end(), 0);
        return order.toInternal(ids);
    }();
    std::vector<int> sorted = all;
    std::sort(sorted.begin(), sorted.end());
    for (int v = 0; v < mesh.vertexCount(); ++v) ASSERT_EQ(sorted[v], v) << "not a permutation";

    std::set<std::array<int, 3>> expected, got;
    for (int f = 0; f < mesh.faceCount(); ++f) {
        expected.insert(cyclic(all[mesh.F(f, 0)], all[mesh.F(f, 1)], all[mesh.F(f, 2)]));
        got.insert(cyclic(out.F(f, 0), out.F(f, 1), out.F(f, 2)));
    }
    EXPECT_EQ(got, expected);

    std::array<int, 3> previous{-1, -1, -1};
    for (int f = 0; f < out.faceCount(); ++f) {
        std::array<int, 3> key{out.F(f, 0), out.F(f, 1), out.F(f, 2)};
        std::sort(key.begin(), key.end());
        EXPECT_LE(previous, key) << "face " << f;
        previous = key;
    }
    // Vertex positions travel with their ids.
    for (int v = 0; v < mesh.vertexCount(); ++v)
        ASSERT_EQ(out.V.row(all[v]), mesh.V.row(v)) << "vertex " << v;
}

TEST(VertexOrder, NeighboursEndUpNearEachOther) {
    const TriMesh mesh = shuffled(icosphere(4), 9);
    const TriMesh out = VertexOrder::spatial(mesh).apply(mesh);
    auto medianEdgeSpan = [](const TriMesh& m) {
        std::vector<int> span;
        for (int f = 0; f < m.faceCount(); ++f)
            for (int c = 0; c < 3; ++c) span.push_back(std::abs(m.F(f, c) - m.F(f, (c + 1) % 3)));
        std::nth_element(span.begin(), span.begin() + span.size() / 2, span.end());
        return span[span.size() / 2];
    };
    // Shuffled, an edge spans about a third of the 2,562 vertices; in the order, a few dozen.
    EXPECT_GT(medianEdgeSpan(mesh), 500);
    EXPECT_LT(medianEdgeSpan(out), 100);
}

TEST(VertexOrder, PositionsComeBackUnchanged) {
    const TriMesh mesh = shuffled(icosphere(2), 1);
    const VertexOrder order = VertexOrder::spatial(mesh);
    EXPECT_EQ(order.toUser(order.toInternal(mesh.V)), mesh.V);
    EXPECT_NE(order.toInternal(mesh.V), mesh.V);
}

}  // namespace boneless::testing
