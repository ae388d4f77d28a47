// Edge and vertex manifoldness on plain arrays: sorting the triangles' edges finds every edge's
// faces, and a union-find over corners joined across shared edges counts the fans at a vertex.

#include <algorithm>
#include <cstdint>
#include <numeric>

#include "PolygonSoup.h"
#include "boneless/Error.h"

namespace boneless::detail {

namespace {

struct HalfEdge {
    uint64_t key;  // unordered vertex pair
    int tri, k;    // runs from corner k to corner k+1 of triangle tri
};

}  // namespace

std::string faceWhere(const PolygonSoup& soup, int face) {
    std::string s = "face " + std::to_string(soup.fileFaceOf(face));
    if (face >= 0 && face < static_cast<int>(soup.faceLine.size()))
        s += " (line " + std::to_string(soup.faceLine[face]) + ")";
    return s;
}

std::string vertexWhere(const PolygonSoup& soup, int vertex) {
    std::string s = "vertex " + std::to_string(vertex);
    if (vertex >= 0 && vertex < static_cast<int>(soup.vertexLine.size()))
        s += " (line " + std::to_string(soup.vertexLine[vertex]) + ")";
    return s;
}

TopologySummary checkManifold(const std::string& file, const Faces& F, int vertexCount,
                              const std::vector<int>& faceOf, const PolygonSoup& soup,
                              const std::vector<int>& vertexOf,
                              const std::unordered_set<uint64_t>& repeated,
                              const std::vector<int>& weldedTo) {
    const int T = static_cast<int>(F.rows());
    auto faceName = [&](int t) { return faceWhere(soup, faceOf[t]); };
    auto vertexName = [&](int v) { return std::to_string(vertexOf[v]); };

    std::vector<HalfEdge> edges;
    edges.reserve(3 * size_t(T));
    for (int t = 0; t < T; ++t) {
        for (int k = 0; k < 3; ++k) {
            const uint32_t a = F(t, k), b = F(t, (k + 1) % 3);
            edges.push_back({(uint64_t(std::min(a, b)) << 32) | std::max(a, b), t, k});
        }
    }
    std::sort(edges.begin(), edges.end(), [](const HalfEdge& x, const HalfEdge& y) {
        return x.key != y.key ? x.key < y.key : x.tri < y.tri;
    });

    UnionFind corners(3 * size_t(T));
    std::vector<int> boundaryNext(vertexCount, -1);
    TopologySummary summary;
    for (size_t i = 0; i < edges.size();) {
        size_t j = i;
        while (j < edges.size() && edges[j].key == edges[i].key) ++j;
        const HalfEdge& e = edges[i];
        const int a = F(e.tri, e.k), b = F(e.tri, (e.k + 1) % 3);
        const std::string edgeName = "edge " + vertexName(a) + "-" + vertexName(b);
        const std::string directed = vertexName(a) + "->" + vertexName(b);
        if (j - i > 2) {
            std::string where;
            for (size_t m = i; m < j && m < i + 4; ++m)
                where += (m > i ? ", " : "") + faceName(edges[m].tri);
            if (j - i > 4) where += ", ...";
            // Ear clipping avoids repeating an edge, but a polygon may have no other way out.
            const std::string made = repeated.count(e.key)
                                         ? " (Boneless made it splitting the file's polygons into "
                                           "triangles: no other split was left)"
                                         : "";
            throw MeshError(file,
                            "non-manifold " + edgeName + ": shared by " + std::to_string(j - i) +
                                " faces" + made,
                            where);
        }
        if (j - i == 1) {
            ++summary.boundaryEdges;
            boundaryNext[a] = b;
        } else {
            const HalfEdge& o = edges[i + 1];
            if (F(o.tri, o.k) == a) {
                throw MeshError(file,
                                "inconsistent orientation: two faces run edge " + directed +
                                    " in the same direction (a flipped face, or a non-manifold "
                                    "edge; Blender: Mesh > Normals > Recalculate Outside)",
                                faceName(e.tri) + " and " + faceName(o.tri));
            }
            // Corner at a in e.tri meets corner at a in o.tri (which runs b -> a), same for b.
            corners.join(3 * e.tri + e.k, 3 * o.tri + (o.k + 1) % 3);
            corners.join(3 * e.tri + (e.k + 1) % 3, 3 * o.tri + o.k);
        }
        i = j;
    }

    // Corners are only ever joined to corners at the same vertex, so a root names one fan.
    std::vector<int> fanRoot(vertexCount, -1);
    UnionFind parts(vertexCount);
    for (int c = 0; c < 3 * T; ++c) {
        const int v = F(c / 3, c % 3), root = corners.find(c);
        parts.join(v, F(c / 3, (c + 1) % 3));
        if (fanRoot[v] < 0) {
            fanRoot[v] = root;
        } else if (fanRoot[v] != root) {
            int fans = 0;
            std::vector<int> seen;
            for (int d = 0; d < 3 * T; ++d) {
                if (F(d / 3, d % 3) != v) continue;
                const int r = corners.find(d);
                if (std::find(seen.begin(), seen.end(), r) == seen.end()) seen.push_back(r), ++fans;
            }
            throw MeshError(file,
                            "non-manifold vertex " + vertexName(v) + ": its faces form " +
                                std::to_string(fans) + " separate fans",
                            vertexWhere(soup, vertexOf[v]) + ", e.g. " + faceName(fanRoot[v] / 3) +
                                " and " + faceName(c / 3));
        }
    }
    for (int v = 0; v < vertexCount; ++v) {
        if (fanRoot[v] < 0 && weldedTo[v] == v) {
            ++summary.isolatedVertices;
            if (summary.isolated.size() < 5) summary.isolated.push_back(vertexOf[v]);
        } else if (fanRoot[v] >= 0 && parts.find(v) == v) {
            ++summary.components;
        }
    }
    // With every vertex on one fan, boundary edges form disjoint cycles.
    for (int v = 0; v < vertexCount; ++v) {
        if (boundaryNext[v] < 0) continue;
        ++summary.boundaryLoops;
        for (int w = v, steps = 0; boundaryNext[w] >= 0 && steps <= vertexCount; ++steps) {
            const int next = boundaryNext[w];
            boundaryNext[w] = -1;
            w = next;
        }
    }
    return summary;
}

}  // namespace boneless::detail
