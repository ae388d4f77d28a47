// Ear clipping in the polygon's best-fit plane, always cutting the ear with the shortest new
// diagonal. For a quad this picks the shorter diagonal unless that diagonal lies outside a
// non-convex quad, where a fan or the shorter-diagonal rule alone would fold a triangle over.
// A diagonal that is already an edge (of the file, or another polygon's diagonal) is cut only
// when no other ear is left: two hexagons sharing a vertex once both got the same diagonal.

#include <Eigen/Geometry>
#include <algorithm>
#include <limits>

#include "PolygonSoup.h"
#include "boneless/TriMesh.h"

namespace boneless::detail {

namespace {

using Vec2 = Eigen::Vector2d;

double cross2(const Vec2& a, const Vec2& b, const Vec2& c) {
    return (b - a).x() * (c - a).y() - (b - a).y() * (c - a).x();
}

bool insideOrOn(const Vec2& p, const Vec2& a, const Vec2& b, const Vec2& c) {
    return cross2(a, b, p) >= 0 && cross2(b, c, p) >= 0 && cross2(c, a, p) >= 0;
}

}  // namespace

uint64_t edgeKey(int a, int b) {
    return (uint64_t(uint32_t(std::min(a, b))) << 32) | uint32_t(std::max(a, b));
}

void triangulatePolygon(const Positions& V, const int* corners, int n,
                        std::unordered_set<uint64_t>& edges, std::vector<int>& out,
                        std::unordered_set<uint64_t>& repeated) {
    if (n == 3) {
        out.insert(out.end(), corners, corners + 3);
        return;
    }
    // Newell's normal is robust for non-planar and non-convex polygons.
    Vec3 normal = Vec3::Zero();
    for (int i = 0; i < n; ++i) {
        const Vec3 a = V.row(corners[i]), b = V.row(corners[(i + 1) % n]);
        normal += Vec3((a.y() - b.y()) * (a.z() + b.z()), (a.z() - b.z()) * (a.x() + b.x()),
                       (a.x() - b.x()) * (a.y() + b.y()));
    }
    if (normal.squaredNorm() == 0) normal = Vec3::UnitZ();  // degenerate: any plane will do
    // Project onto the plane so that the polygon runs counter-clockwise.
    Vec3 u = normal.unitOrthogonal(), w = normal.cross(u);
    std::vector<Vec2> p(n);
    for (int i = 0; i < n; ++i) {
        const Vec3 x = V.row(corners[i]);
        p[i] = Vec2(x.dot(u), x.dot(w));
    }

    std::vector<int> ring(n);
    for (int i = 0; i < n; ++i) ring[i] = i;
    while (ring.size() > 3) {
        const int m = static_cast<int>(ring.size());
        // Ears whose diagonal is new first, then (only if none is) those that repeat an edge.
        int best = -1, bestTaken = -1, fallback = 0;
        double bestLength = std::numeric_limits<double>::infinity();
        double takenLength = bestLength, fallbackLength = bestLength;
        for (int i = 0; i < m; ++i) {
            const int a = ring[(i + m - 1) % m], b = ring[i], c = ring[(i + 1) % m];
            const double length = (V.row(corners[a]) - V.row(corners[c])).squaredNorm();
            const bool taken = edges.count(edgeKey(corners[a], corners[c])) > 0;
            if (length < fallbackLength && !taken) fallbackLength = length, fallback = i;
            if (cross2(p[a], p[b], p[c]) <= 0) continue;
            if (taken ? length >= takenLength : length >= bestLength) continue;
            bool ear = true;
            for (int j = 0; j < m && ear; ++j) {
                const int q = ring[j];
                if (q != a && q != b && q != c && insideOrOn(p[q], p[a], p[b], p[c])) ear = false;
            }
            if (!ear) continue;
            if (taken)
                bestTaken = i, takenLength = length;
            else
                best = i, bestLength = length;
        }
        // No ear means a degenerate or self-intersecting polygon: any cut is as good as another,
        // and the zero-area check reports what comes out.
        const int i = best >= 0 ? best : bestTaken >= 0 ? bestTaken : fallback;
        const int a = corners[ring[(i + m - 1) % m]], c = corners[ring[(i + 1) % m]];
        if (!edges.insert(edgeKey(a, c)).second) repeated.insert(edgeKey(a, c));
        out.insert(out.end(), {a, corners[ring[i]], c});
        ring.erase(ring.begin() + i);
    }
    out.insert(out.end(), {corners[ring[0]], corners[ring[1]], corners[ring[2]]});
}

}  // namespace boneless::detail
