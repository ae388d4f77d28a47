// Which pieces of a mesh wind inward: their normals point into the body, so a marker's offset
// along the normal pushed it into the skin, and no check said so (a Maya negative-scale freeze).

#include <algorithm>
#include <cstdint>
#include <numeric>

#include "PolygonSoup.h"

namespace boneless::detail {

std::vector<int> insideOutPieces(const Positions& V, const Faces& F) {
    const int T = static_cast<int>(F.rows());
    std::vector<int> parent(V.rows());
    std::iota(parent.begin(), parent.end(), 0);
    const auto find = [&](int x) {
        while (parent[x] != x) x = parent[x] = parent[parent[x]];
        return x;
    };
    std::vector<uint64_t> keys;
    keys.reserve(3 * size_t(T));
    for (int t = 0; t < T; ++t)
        for (int k = 0; k < 3; ++k) {
            const int a = F(t, k), b = F(t, (k + 1) % 3);
            keys.push_back(edgeKey(a, b));
            parent[find(a)] = find(b);
        }
    struct Piece {
        int first = -1, triangles = 0, edges = 0, boundary = 0;
        Vec3 sum = Vec3::Zero(), low = Vec3::Constant(1e300), high = -low;
        double volume = 0;
    };
    std::vector<Piece> piece(V.rows());
    for (int t = 0; t < T; ++t) {
        Piece& p = piece[find(F(t, 0))];
        if (p.first < 0) p.first = t;
        ++p.triangles;
        for (int k = 0; k < 3; ++k) {
            const Vec3 x = V.row(F(t, k)).transpose();
            p.sum += x / 3;
            p.low = p.low.cwiseMin(x);
            p.high = p.high.cwiseMax(x);
        }
    }
    std::sort(keys.begin(), keys.end());
    for (size_t i = 0; i < keys.size();) {
        size_t j = i;
        while (j < keys.size() && keys[j] == keys[i]) ++j;
        Piece& p = piece[find(int(keys[i] >> 32))];
        ++p.edges;
        p.boundary += j - i == 1;
        i = j;
    }
    // The volume the faces enclose, signed by their winding, about the piece's centre.
    for (int t = 0; t < T; ++t) {
        Piece& p = piece[find(F(t, 0))];
        const Vec3 c = p.sum / p.triangles;
        const Vec3 a = V.row(F(t, 0)).transpose() - c, b = V.row(F(t, 1)).transpose() - c,
                   d = V.row(F(t, 2)).transpose() - c;
        p.volume += a.dot(b.cross(d)) / 6;
    }
    // Closed, or nearly (a body's eye and mouth holes), and enclosing a hundredth of its box at
    // least: an open sheet's sign says nothing.
    std::vector<int> inward;
    for (const Piece& p : piece) {
        const Vec3 size = p.high - p.low;
        if (p.first >= 0 && p.boundary * 100 <= p.edges && p.volume < 0 &&
            -p.volume >= 0.01 * size.prod())
            inward.push_back(p.first);
    }
    std::sort(inward.begin(), inward.end());
    return inward;
}

}  // namespace boneless::detail
