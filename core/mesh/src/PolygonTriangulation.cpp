// Ear clipping in the polygon's best-fit plane, always cutting the ear with the shortest new
// diagonal. For a quad this picks the shorter diagonal unless that diagonal lies outside a
// non-convex quad, where a fan or the shorter-diagonal rule alone would fold a triangle over.

#include <Eigen/Geometry>
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

void triangulatePolygon(const Positions& V, const int* corners, int n, std::vector<int>& out) {
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
        int best = -1, fallback = 0;
        double bestLength = std::numeric_limits<double>::infinity();
        double fallbackLength = bestLength;
        for (int i = 0; i < m; ++i) {
            const int a = ring[(i + m - 1) % m], b = ring[i], c = ring[(i + 1) % m];
            const double length = (V.row(corners[a]) - V.row(corners[c])).squaredNorm();
            if (length < fallbackLength) fallbackLength = length, fallback = i;
            if (length >= bestLength || cross2(p[a], p[b], p[c]) <= 0) continue;
            bool ear = true;
            for (int j = 0; j < m && ear; ++j) {
                const int q = ring[j];
                if (q != a && q != b && q != c && insideOrOn(p[q], p[a], p[b], p[c])) ear = false;
            }
            if (ear) best = i, bestLength = length;
        }
        // No ear means a degenerate or self-intersecting polygon: any cut is as good as another,
        // and the zero-area check reports what comes out.
        const int i = best >= 0 ? best : fallback;
        out.insert(out.end(),
                   {corners[ring[(i + m - 1) % m]], corners[ring[i]], corners[ring[(i + 1) % m]]});
        ring.erase(ring.begin() + i);
    }
    out.insert(out.end(), {corners[ring[0]], corners[ring[1]], corners[ring[2]]});
}

}  // namespace boneless::detail
