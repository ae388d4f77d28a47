// Welding the copies of a vertex that a file splits at its UV seams (one vertex per position and
// texture coordinate, as many OBJ and PLY exporters write): unwelded, the seams tore open as the
// mesh moved, with only a note about boundary edges.

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <numeric>
#include <unordered_map>

#include "PolygonSoup.h"

namespace boneless::detail {

namespace {

// The corners of the kept polygons as mesh vertices, polygon after polygon.
struct Corners {
    std::vector<int> vertex, start{0};
};

int find(std::vector<int>& parent, int x) {
    while (parent[x] != x) x = parent[x] = parent[parent[x]];
    return x;
}

// Whether the polygons about welded vertex `w` (copies `members`) form one fan: every edge out of
// it met at most once each way, and the corners joined across their shared edges all one piece.
// Two surfaces touching at a point make two fans; a seam's copies make one.
bool oneFan(int w, const std::vector<int>& members, const std::vector<int>& weld, const Corners& c,
            const std::vector<int>& cornerStart, const std::vector<int>& cornersOf,
            const std::vector<int>& polygonOf) {
    struct Corner {
        int prev, next;
    };
    std::vector<Corner> fan;
    std::vector<int> polygons;
    for (int v : members)
        for (int i = cornerStart[v]; i < cornerStart[v + 1]; ++i) {
            const int k = cornersOf[i], p = polygonOf[k];
            polygons.push_back(p);
            const int first = c.start[p], n = c.start[p + 1] - first;
            const int at = k - first;
            const int prev = weld[c.vertex[first + (at + n - 1) % n]];
            const int next = weld[c.vertex[first + (at + 1) % n]];
            if (prev == w || next == w) return false;  // two copies in one polygon
            fan.push_back({prev, next});
        }
    std::sort(polygons.begin(), polygons.end());
    if (std::adjacent_find(polygons.begin(), polygons.end()) != polygons.end()) return false;
    std::vector<int> parent(fan.size());
    std::iota(parent.begin(), parent.end(), 0);
    std::unordered_map<int, int> byNext, byPrev;
    for (int i = 0; i < static_cast<int>(fan.size()); ++i) {
        if (!byNext.emplace(fan[i].next, i).second) return false;
        if (!byPrev.emplace(fan[i].prev, i).second) return false;
    }
    int pieces = static_cast<int>(fan.size());
    for (int i = 0; i < static_cast<int>(fan.size()); ++i)
        if (const auto it = byPrev.find(fan[i].next); it != byPrev.end()) {
            const int a = find(parent, i), b = find(parent, it->second);
            if (a != b) parent[a] = b, --pieces;
        }
    return pieces == 1;
}

}  // namespace

std::vector<int> weldCopies(const Positions& V, const PolygonSoup& soup,
                            const std::vector<int>& kept, const std::vector<int>& meshIndex,
                            int& welded) {
    const int nv = static_cast<int>(V.rows());
    std::vector<int> weld(nv);
    std::iota(weld.begin(), weld.end(), 0);
    welded = 0;
    Corners c;
    std::vector<int> polygonOf;
    for (int f : kept) {
        for (int k = soup.faceStart[f]; k < soup.faceStart[f + 1]; ++k) {
            c.vertex.push_back(meshIndex[soup.faceIndex[k]]);
            polygonOf.push_back(static_cast<int>(c.start.size()) - 1);
        }
        c.start.push_back(static_cast<int>(c.vertex.size()));
    }
    std::vector<int> cornerStart(nv + 1, 0);
    for (int v : c.vertex) ++cornerStart[v + 1];
    std::partial_sum(cornerStart.begin(), cornerStart.end(), cornerStart.begin());
    std::vector<int> cornersOf(c.vertex.size()), fill(cornerStart.begin(), cornerStart.end() - 1);
    for (int k = 0; k < static_cast<int>(c.vertex.size()); ++k) cornersOf[fill[c.vertex[k]]++] = k;

    // Within a millionth of the used vertices' bounding box: exporters write a vertex's copies
    // from the same number, but a text round trip may leave them a last digit apart.
    Vec3 low = Vec3::Constant(INFINITY), high = -low;
    for (int v = 0; v < nv; ++v)
        if (cornerStart[v + 1] > cornerStart[v]) {
            low = low.cwiseMin(V.row(v).transpose());
            high = high.cwiseMax(V.row(v).transpose());
        }
    const double tolerance = 1e-6 * (high - low).norm();
    if (!(tolerance > 0)) return weld;
    struct CellHash {
        size_t operator()(const Eigen::Vector3i& k) const {
            return (size_t(k.x()) * 73856093u) ^ (size_t(k.y()) * 19349663u) ^
                   (size_t(k.z()) * 83492791u);
        }
    };
    std::unordered_map<Eigen::Vector3i, std::vector<int>, CellHash> grid;
    const auto cellOf = [&](int v) {
        return Eigen::Vector3i(
            ((V.row(v).transpose() - low) / tolerance).array().floor().cast<int>());
    };
    for (int v = 0; v < nv; ++v) {
        if (cornerStart[v + 1] == cornerStart[v]) continue;
        const Eigen::Vector3i cell = cellOf(v);
        for (int dx = -1; dx <= 1; ++dx)
            for (int dy = -1; dy <= 1; ++dy)
                for (int dz = -1; dz <= 1; ++dz) {
                    const auto it = grid.find(cell + Eigen::Vector3i(dx, dy, dz));
                    if (it == grid.end()) continue;
                    for (int u : it->second)
                        if ((V.row(u) - V.row(v)).squaredNorm() <= tolerance * tolerance) {
                            // The first copy in file order stands for them all.
                            const int a = find(weld, u), b = find(weld, v);
                            if (a != b) weld[std::max(a, b)] = std::min(a, b);
                        }
                }
        grid[cell].push_back(v);
    }
    for (int v = 0; v < nv; ++v) weld[v] = find(weld, v);

    // Undone where the polygons about a welded vertex would not form one fan; undoing one may
    // split its neighbours' fans, so they are looked at again.
    std::vector<std::vector<int>> members(nv);
    for (int v = 0; v < nv; ++v)
        if (weld[v] != v) members[weld[v]].push_back(v);
    std::vector<int> work;
    for (int v = 0; v < nv; ++v)
        if (!members[v].empty()) members[v].insert(members[v].begin(), v), work.push_back(v);
    std::vector<char> queued(nv, 0);
    for (int w : work) queued[w] = 1;
    while (!work.empty()) {
        const int w = work.back();
        work.pop_back();
        queued[w] = 0;
        if (members[w].empty() || oneFan(w, members[w], weld, c, cornerStart, cornersOf, polygonOf))
            continue;
        for (int v : members[w]) {
            weld[v] = v;
            for (int i = cornerStart[v]; i < cornerStart[v + 1]; ++i) {
                const int p = polygonOf[cornersOf[i]];
                for (int k = c.start[p]; k < c.start[p + 1]; ++k) {
                    const int u = weld[c.vertex[k]];
                    if (!members[u].empty() && !queued[u]) queued[u] = 1, work.push_back(u);
                }
            }
        }
        members[w].clear();
    }
    for (int v = 0; v < nv; ++v) welded += weld[v] != v;
    return weld;
}

}  // namespace boneless::detail
