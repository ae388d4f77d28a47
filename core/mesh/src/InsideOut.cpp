// Which pieces of a mesh wind inward: their normals point into the body, so a marker's offset
// along the normal pushed it into the skin, and no check said so (a Maya negative-scale freeze).

#include <algorithm>

#include "PolygonSoup.h"

namespace boneless::detail {

std::vector<int> insideOutPieces(const Positions& V, const Faces& F) {
    const int T = static_cast<int>(F.rows());
    UnionFind parts(V.rows());
    for (int t = 0; t < T; ++t)
        for (int k = 1; k < 3; ++k) parts.join(F(t, k), F(t, 0));
    struct Piece {
        int first = -1, triangles = 0;
        Vec3 sum = Vec3::Zero(), low = Vec3::Constant(1e300), high = -low;
        double volume[2] = {0, 0};  // about its centre and about its box's corner
    };
    std::vector<int> pieceOf(V.rows(), -1);
    std::vector<Piece> pieces;
    const auto pieceAt = [&](int t) -> Piece& {
        int& p = pieceOf[parts.find(F(t, 0))];
        if (p < 0) p = static_cast<int>(pieces.size()), pieces.emplace_back();
        return pieces[p];
    };
    for (int t = 0; t < T; ++t) {
        Piece& p = pieceAt(t);
        if (p.first < 0) p.first = t;
        ++p.triangles;
        for (int k = 0; k < 3; ++k) {
            const Vec3 x = V.row(F(t, k)).transpose();
            p.sum += x / 3;
            p.low = p.low.cwiseMin(x);
            p.high = p.high.cwiseMax(x);
        }
    }
    // The volume the faces enclose, signed by their winding: a closed surface's is the same about
    // any point, an open one's is not, however finely it is tessellated (a cape, a face mask).
    for (int t = 0; t < T; ++t) {
        Piece& p = pieceAt(t);
        const Vec3 about[2] = {p.sum / p.triangles, p.high};
        for (int r = 0; r < 2; ++r) {
            const Vec3 a = V.row(F(t, 0)).transpose() - about[r];
            const Vec3 b = V.row(F(t, 1)).transpose() - about[r];
            const Vec3 c = V.row(F(t, 2)).transpose() - about[r];
            p.volume[r] += a.dot(b.cross(c)) / 6;
        }
    }
    // Closed, or nearly (a body's eye and mouth holes change it by little), enclosing a hundredth
    // of its box at least (a two-sided card encloses none), and inside no other piece's box that
    // winds outward (the lining of a hollow shell).
    const auto inward = [](const Piece& p) {
        const Vec3 size = p.high - p.low;
        return p.volume[0] < 0 && std::abs(p.volume[0] - p.volume[1]) <= 0.05 * -p.volume[0] &&
               size.minCoeff() > 0 && -p.volume[0] >= 0.01 * size.prod();
    };
    std::vector<int> found;
    for (const Piece& p : pieces) {
        if (!inward(p)) continue;
        const bool lining = std::any_of(pieces.begin(), pieces.end(), [&](const Piece& q) {
            return &q != &p && q.volume[0] > 0 && (q.low.array() <= p.low.array()).all() &&
                   (q.high.array() >= p.high.array()).all();
        });
        if (!lining) found.push_back(p.first);
    }
    std::sort(found.begin(), found.end());
    return found;
}

}  // namespace boneless::detail
