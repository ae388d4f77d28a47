#include "VertexOrder.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>

namespace boneless {

namespace {

// 21 bits per axis, interleaved: two vertices share a code only within 1/2,097,152 of the
// bounding box of each other.
std::uint64_t mortonCode(const Eigen::Vector3d& p, const Eigen::Vector3d& low,
                         const Eigen::Vector3d& scale) {
    std::uint64_t code = 0;
    std::array<std::uint32_t, 3> cell;
    for (int d = 0; d < 3; ++d) {
        const double x = (p[d] - low[d]) * scale[d];
        // A non-finite position (the API does not refuse one) goes to the first cell: converting
        // it would be undefined.
        cell[d] = std::isfinite(x) ? static_cast<std::uint32_t>(std::clamp(x, 0.0, 2097151.0)) : 0;
    }
    for (int bit = 20; bit >= 0; --bit)
        for (int d = 0; d < 3; ++d) code = (code << 1) | ((cell[d] >> bit) & 1u);
    return code;
}

}  // namespace

VertexOrder VertexOrder::spatial(const TriMesh& mesh) {
    const int n = mesh.vertexCount();
    VertexOrder order;
    if (n == 0) return order;
    const Eigen::Vector3d low = mesh.V.colwise().minCoeff().transpose();
    const Eigen::Vector3d extent = mesh.V.colwise().maxCoeff().transpose() - low;
    Eigen::Vector3d scale;
    for (int d = 0; d < 3; ++d)
        scale[d] = std::isfinite(extent[d]) && extent[d] > 0 ? 2097151.0 / extent[d] : 0.0;
    std::vector<std::pair<std::uint64_t, int>> keys(n);
    for (int v = 0; v < n; ++v) keys[v] = {mortonCode(mesh.V.row(v).transpose(), low, scale), v};
    // Vertices that share a cell (duplicates) keep the caller's order among themselves.
    std::sort(keys.begin(), keys.end());
    order.userOf_.resize(n);
    order.internalOf_.resize(n);
    for (int i = 0; i < n; ++i) {
        order.userOf_[i] = keys[i].second;
        order.internalOf_[keys[i].second] = i;
    }
    return order;
}

TriMesh VertexOrder::apply(const TriMesh& mesh) const {
    if (identity()) return mesh;
    TriMesh out;
    out.V = toInternal(mesh.V);
    const int m = mesh.faceCount();
    // Faces sorted by their vertices' sorted triple, so that a face's neighbours in memory share
    // its vertices, and the result does not depend on the caller's face order.
    // Bucketed by the smallest vertex first (a handful of faces each), then sorted within.
    using Key = std::pair<std::array<int, 3>, int>;
    const int n = mesh.vertexCount();
    std::vector<int> start(n + 1, 0);
    std::vector<Key> unsorted(m);
    for (int f = 0; f < m; ++f) {
        std::array<int, 3> key;
        for (int c = 0; c < 3; ++c) key[c] = internalOf_[mesh.F(f, c)];
        std::sort(key.begin(), key.end());
        unsorted[f] = {key, f};
        ++start[key[0] + 1];
    }
    for (int v = 0; v < n; ++v) start[v + 1] += start[v];
    std::vector<Key> keys(m);
    {
        std::vector<int> fill(start.begin(), start.end() - 1);
        for (const Key& k : unsorted) keys[fill[k.first[0]]++] = k;
    }
    for (int v = 0; v < n; ++v) std::sort(keys.begin() + start[v], keys.begin() + start[v + 1]);
    out.F.resize(m, 3);
    for (int i = 0; i < m; ++i)
        for (int c = 0; c < 3; ++c) out.F(i, c) = internalOf_[mesh.F(keys[i].second, c)];
    return out;
}

std::vector<int> VertexOrder::toInternal(const std::vector<int>& vertices) const {
    if (identity()) return vertices;
    std::vector<int> out(vertices.size());
    for (size_t i = 0; i < vertices.size(); ++i) out[i] = internalOf_[vertices[i]];
    return out;
}

Positions VertexOrder::toInternal(const Positions& V) const {
    if (identity()) return V;
    Positions out(V.rows(), 3);
    for (int i = 0; i < static_cast<int>(userOf_.size()); ++i) out.row(i) = V.row(userOf_[i]);
    return out;
}

Positions VertexOrder::toUser(const Positions& V) const {
    if (identity()) return V;
    Positions out(V.rows(), 3);
    for (int i = 0; i < static_cast<int>(userOf_.size()); ++i) out.row(userOf_[i]) = V.row(i);
    return out;
}

}  // namespace boneless
