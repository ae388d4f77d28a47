#include "MeshHierarchy.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <numeric>
#include <queue>
#include <string>

#include "boneless/Error.h"
#include "boneless/MeshTopology.h"
#include "boneless/TriMesh.h"

namespace boneless {

namespace {

// A new face may turn at most 60° away from the face it replaces. 90° (a flip) is the hard limit;
// the margin keeps folds from building up over several levels, each of which may turn a region.
constexpr double kMinNormalCos = 0.5;
// A new face's smallest angle must be at least ~8° (sin 8° ≈ 0.139), or at least as large as the
// worst angle among the faces it replaces when those are already slimmer: slivers make ring
// normals and mean-value weights ill-conditioned, but an input full of them must still coarsen.
constexpr double kMinAngleSin = 0.139;
// Every face around a removed vertex must face the same way as its ring polygon (cos > 0.01):
// then the vertex projects into the kernel of its ring, its mean-value weights are all positive
// and prolongation is a convex combination plus a height.
constexpr double kMinStarCos = 0.01;
// Ring vector area against the level's mean squared edge, 100x ShapeEncoding's own cut-off.
constexpr double kMinRingArea = 1e-8;
// Tie-breaker among equally cheap collapses: prefer short edges. Against the quadric error of a
// bend of radius R with edges h (~h⁴/R² per area) this term (~1e-4 h² per area) only decides where
// h/R < ~0.02, i.e. where the surface is flat at the scale of an edge.
constexpr double kLengthWeight = 1e-4;

Vec3 pos(const Positions& V, int i) {
    return V.row(i).transpose();
}

// One-rings in MeshTopology's CSR layout and cyclic order. Level 0 copies MeshTopology's (which
// also validates the input); coarser levels are derived from the finer rings and the collapses,
// which costs a fraction of rebuilding them from the faces. They end up in the levels.
struct Rings {
    std::vector<int> offsets{0}, neighbours;
    std::vector<char> boundary;

    int valence(int v) const { return offsets[v + 1] - offsets[v]; }
    const int* ring(int v) const { return neighbours.data() + offsets[v]; }
    bool contains(int v, int x) const {
        return std::find(ring(v), ring(v) + valence(v), x) != ring(v) + valence(v);
    }
};

Rings ringsOf(const MeshTopology& topology) {
    Rings r;
    r.offsets = topology.offsets();
    r.neighbours = topology.neighbours();
    r.boundary.resize(topology.vertexCount());
    for (int v = 0; v < topology.vertexCount(); ++v) r.boundary[v] = topology.isBoundary(v);
    return r;
}

void keepRings(Rings&& rings, HierarchyLevel& level) {
    level.ringOffsets = std::move(rings.offsets);
    level.rings = std::move(rings.neighbours);
    level.boundary = std::move(rings.boundary);
}

// Rings after collapsing each removed x into into[x] (independent set). Around a survivor v with
// ... a, x, b ... in its ring: x collapsed into v opens into x's ring from after a to before b; x
// collapsed into a or b (so x's faces with v held that edge) just goes; otherwise x becomes its
// target. Removed vertices are never consecutive in a ring, nor at a boundary ring's ends.
Rings coarserRings(const Rings& fine, const std::vector<int>& into,
                   const std::vector<int>& coarser) {
    const int n = static_cast<int>(into.size());
    Rings c;
    c.neighbours.reserve(fine.neighbours.size());
    for (int v = 0; v < n; ++v) {
        if (into[v] >= 0) continue;
        const int m = fine.valence(v);
        const int* ring = fine.ring(v);
        for (int k = 0; k < m; ++k) {
            const int x = ring[k];
            if (into[x] < 0) {
                c.neighbours.push_back(coarser[x]);
                continue;
            }
            const int a = ring[(k + m - 1) % m], b = ring[(k + 1) % m];
            if (into[x] == v) {
                const int mx = fine.valence(x);
                const int* rx = fine.ring(x);
                const int at = static_cast<int>(std::find(rx, rx + mx, v) - rx);
                for (int t = 2; t + 2 <= mx; ++t)
                    c.neighbours.push_back(coarser[rx[(at + t) % mx]]);
            } else if (into[x] != a && into[x] != b) {
                c.neighbours.push_back(coarser[into[x]]);
            }
        }
        c.offsets.push_back(static_cast<int>(c.neighbours.size()));
        c.boundary.push_back(fine.boundary[v]);
    }
    return c;
}

// Garland–Heckbert plane quadric, Q(p) = pᵀAp + 2bᵀp + c with A = (xx xy xz yy yz zz).
struct Quadric {
    double q[10] = {};

    void addPlane(const Vec3& n, double d, double w) {
        const double v[10] = {n.x() * n.x(), n.x() * n.y(), n.x() * n.z(), n.y() * n.y(),
                              n.y() * n.z(), n.z() * n.z(), n.x() * d,     n.y() * d,
                              n.z() * d,     d * d};
        for (int k = 0; k < 10; ++k) q[k] += w * v[k];
    }
    Quadric& operator+=(const Quadric& o) {
        for (int k = 0; k < 10; ++k) q[k] += o.q[k];
        return *this;
    }
    double operator()(const Vec3& p) const {
        const double x = p.x(), y = p.y(), z = p.z();
        return q[0] * x * x + 2 * q[1] * x * y + 2 * q[2] * x * z + q[3] * y * y +
               2 * q[4] * y * z + q[5] * z * z + 2 * (q[6] * x + q[7] * y + q[8] * z) + q[9];
    }
    double area() const { return q[0] + q[3] + q[5]; }  // trace A: the weight of its planes
};

std::vector<Quadric> faceQuadrics(const TriMesh& mesh) {
    std::vector<Quadric> Q(mesh.vertexCount());
    for (int f = 0; f < mesh.faceCount(); ++f) {
        const Vec3 a = pos(mesh.V, mesh.F(f, 0)), b = pos(mesh.V, mesh.F(f, 1)),
                   c = pos(mesh.V, mesh.F(f, 2));
        const Vec3 N = (b - a).cross(c - a);
        const double twiceArea = N.norm();
        if (!(twiceArea > 0)) continue;
        const Vec3 n = N / twiceArea;
        for (int k = 0; k < 3; ++k) Q[mesh.F(f, k)].addPlane(n, -n.dot(a), 0.5 * twiceArea);
    }
    return Q;
}

Positions unitVertexNormals(const TriMesh& mesh) {
    Positions N = Positions::Zero(mesh.vertexCount(), 3);
    for (int f = 0; f < mesh.faceCount(); ++f) {
        const Vec3 a = pos(mesh.V, mesh.F(f, 0)), b = pos(mesh.V, mesh.F(f, 1)),
                   c = pos(mesh.V, mesh.F(f, 2));
        const Vec3 n = (b - a).cross(c - a);  // area-weighted
        for (int k = 0; k < 3; ++k) N.row(mesh.F(f, k)) += n.transpose();
    }
    for (int v = 0; v < mesh.vertexCount(); ++v)
        if (N.row(v).norm() > 0) N.row(v).normalize();
    return N;
}

// sin² of the triangle's smallest angle (between its two longest edges), without roots or sorting.
double minAngleSin2(const Vec3& a, const Vec3& b, const Vec3& c) {
    const double l0 = (b - a).squaredNorm(), l1 = (c - b).squaredNorm(), l2 = (a - c).squaredNorm();
    const double product = l0 * l1 * l2;
    return product > 0 ? (b - a).cross(c - a).squaredNorm() * std::min({l0, l1, l2}) / product : 0;
}

// The smallest sin² a new face around r may have, or -1 when r must stay: its ring has no area or
// is not star-shaped around it.
double removalFloor(const Positions& V, int r, const int* ring, int m, double minArea) {
    const Vec3 pr = pos(V, r);
    Vec3 N = Vec3::Zero();
    for (int k = 0; k < m; ++k) N += pos(V, ring[k]).cross(pos(V, ring[(k + 1) % m]));
    const double area = N.norm();
    if (!(area > minArea)) return -1;
    double worst = 1;
    for (int k = 0; k < m; ++k) {
        const Vec3 a = pos(V, ring[k]), b = pos(V, ring[(k + 1) % m]);
        const Vec3 face = (a - pr).cross(b - pr);
        if (!(face.dot(N) > kMinStarCos * face.norm() * area)) return -1;
        worst = std::min(worst, minAngleSin2(pr, a, b));
    }
    return std::min(kMinAngleSin * kMinAngleSin, worst);
}

// Whether replacing r by u = ring[j] in r's faces leaves sound faces: none turns too far from the
// face it replaces or from the input surface at its corners (the sum of the corners' input unit
// normals; this bounds the drift that per-level turns could add up to), none is a sliver.
// Positions never move and only r's own collapse touches r's faces, so the verdict does not
// depend on the level's other collapses.
bool fanIsSound(const Positions& V, const Positions& inputNormals, int r, const int* ring, int m,
                int j, double minSin2) {
    const Vec3 pr = pos(V, r), pu = pos(V, ring[j]), nu = pos(inputNormals, ring[j]);
    for (int k = 0; k < m; ++k) {
        const int k1 = (k + 1) % m;
        if (k == j || k1 == j) continue;  // the two faces on edge (r, u) disappear
        const Vec3 a = pos(V, ring[k]), b = pos(V, ring[k1]);
        const Vec3 before = (a - pr).cross(b - pr), after = (a - pu).cross(b - pu);
        const double dot = after.dot(before);
        if (!(dot > 0 && dot * dot > kMinNormalCos * kMinNormalCos * after.squaredNorm() *
                                         before.squaredNorm()))
            return false;
        if (!(after.dot(nu + pos(inputNormals, ring[k]) + pos(inputNormals, ring[k1])) > 0))
            return false;
        if (!(minAngleSin2(pu, a, b) >= minSin2)) return false;
    }
    return true;
}

constexpr float kNever = std::numeric_limits<float>::infinity();

// Costs are floats: non-negative floats order like their bit patterns, so a candidate's cost and
// id pack into one integer that orders by cost, then id.
std::uint64_t keyOf(float cost, int r) {
    std::uint32_t bits;
    std::memcpy(&bits, &cost, sizeof bits);
    return (std::uint64_t(bits) << 32) | std::uint32_t(r);
}

float costOf(std::uint64_t key) {
    const std::uint32_t bits = static_cast<std::uint32_t>(key >> 32);
    float cost;
    std::memcpy(&cost, &bits, sizeof cost);
    return cost;
}

// Sorts keys from keyOf, pushed in ascending id order, by their cost bits: a stable radix sort
// (four byte passes) keeps equal costs in id order, so this equals std::sort at a fraction of it.
void sortByKey(std::vector<std::uint64_t>& keys) {
    std::vector<std::uint64_t> buffer(keys.size());
    for (int shift = 32; shift < 64; shift += 8) {
        std::size_t start[257] = {};
        for (std::uint64_t k : keys) ++start[((k >> shift) & 0xff) + 1];
        for (int b = 0; b < 256; ++b) start[b + 1] += start[b];
        for (std::uint64_t k : keys) buffer[start[(k >> shift) & 0xff]++] = k;
        keys.swap(buffer);
    }
}

// The vertices one level removes: an independent set, each with the ring neighbour it collapses
// into, or -1. Cheapest valid collapse first: every candidate waits in the queue under the cost of
// its cheapest collapse not yet found invalid, and is only examined (geometry, link condition
// against the collapses made so far) when it comes up, since most are blocked before they do.
std::vector<int> chooseCollapses(const TriMesh& mesh, const Positions& inputNormals,
                                 const Rings& topology, const std::vector<char>& keep,
                                 const std::vector<Quadric>& Q) {
    const int n = mesh.vertexCount();
    const std::vector<int>& offsets = topology.offsets;
    const std::vector<int>& rings = topology.neighbours;
    const Positions& V = mesh.V;

    std::vector<double> ownError(n);  // Q_u(p_u): the error u already carries
    for (int v = 0; v < n; ++v) ownError[v] = Q[v](pos(V, v));
    std::vector<float> cost(rings.size(), kNever);  // per ring slot: r into that neighbour
    std::vector<std::uint64_t> order;
    order.reserve(n);
    double edges2 = 0;  // Σ over ring entries of |edge|², as ShapeEncoding scales its cut-off
    for (int r = 0; r < n; ++r) {
        const int m = topology.valence(r);
        const int* ring = topology.ring(r);
        const Vec3 pr = pos(V, r);
        if (keep[r] || topology.boundary[r] || m < 3) {
            for (int j = 0; j < m; ++j) edges2 += (pos(V, ring[j]) - pr).squaredNorm();
            continue;
        }
        const double lengthWeight = kLengthWeight * Q[r].area();
        float best = kNever;
        for (int j = 0; j < m; ++j) {
            const Vec3 pu = pos(V, ring[j]);
            const double edge2 = (pu - pr).squaredNorm();
            edges2 += edge2;
            const double c = Q[r](pu) + ownError[ring[j]] + lengthWeight * edge2;
            cost[offsets[r] + j] = static_cast<float>(std::max(c, 0.0));
            best = std::min(best, cost[offsets[r] + j]);
        }
        order.push_back(keyOf(best, r));
    }
    const double minArea =
        kMinRingArea * (rings.empty() ? 1.0 : edges2 / static_cast<double>(rings.size()));
    // Sorted once; the few candidates whose cheapest collapse fails wait in a small heap.
    sortByKey(order);
    std::priority_queue<std::uint64_t, std::vector<std::uint64_t>, std::greater<>> deferred;

    // Only the survivors' adjacency and valences change during a level: a removed vertex's faces
    // and ring are untouched by its neighbours' collapses, since no two removed vertices are
    // adjacent.
    std::vector<int> into(n, -1), valence(n);
    std::vector<char> blocked(n, 0), examined(n, 0);
    std::vector<double> faceFloor(n, -1);  // removalFloor of each examined candidate
    for (int v = 0; v < n; ++v) valence[v] = topology.valence(v);
    auto inRing = [&](int v, int c) { return topology.contains(v, c); };
    // Survivors u and c are adjacent now if they were at the start of the level, or a vertex x
    // adjacent to both has been collapsed into one of them.
    auto adjacentNow = [&](int u, int c) {
        if (inRing(u, c)) return true;
        for (int k = offsets[u]; k < offsets[u + 1]; ++k) {
            const int x = rings[k];
            if (into[x] == c || (into[x] == u && inRing(x, c))) return true;
        }
        return false;
    };
    // Link condition: r's ring and u share only the two vertices opposite edge (r, u), else an
    // edge would double; and no valence drops below 3.
    auto linkOk = [&](const int* ring, int m, int j) {
        const int u = ring[j], prev = ring[(j + m - 1) % m], next = ring[(j + 1) % m];
        if (valence[u] + m - 4 < 3 || valence[prev] <= 3 || valence[next] <= 3) return false;
        for (int k = 2; k + 1 < m; ++k)
            if (adjacentNow(u, ring[(j + k) % m])) return false;
        return true;
    };

    for (size_t next = 0; next < order.size() || !deferred.empty();) {
        std::uint64_t top;
        if (next < order.size() && (deferred.empty() || order[next] < deferred.top())) {
            top = order[next++];
        } else {
            top = deferred.top();
            deferred.pop();
        }
        const int r = static_cast<int>(top & 0xffffffffu);
        const float key = costOf(top);
        if (blocked[r]) continue;
        const int m = topology.valence(r), base = offsets[r];
        const int* ring = topology.ring(r);
        if (!examined[r]) {
            examined[r] = 1;
            faceFloor[r] = removalFloor(V, r, ring, m, minArea);
        }
        if (faceFloor[r] < 0) continue;
        for (;;) {
            int j = -1;
            for (int k = 0; k < m; ++k)
                if (cost[base + k] < kNever && (j < 0 || cost[base + k] < cost[base + j])) j = k;
            if (j < 0) break;
            if (cost[base + j] > key) {  // its cheap collapses are gone: wait for its turn
                deferred.push(keyOf(cost[base + j], r));
                break;
            }
            if (!fanIsSound(V, inputNormals, r, ring, m, j, faceFloor[r]) || !linkOk(ring, m, j)) {
                cost[base + j] = kNever;
                continue;
            }
            into[r] = ring[j];
            for (int k = 0; k < m; ++k) blocked[ring[k]] = 1;
            valence[ring[j]] += m - 4;
            --valence[ring[(j + m - 1) % m]];
            --valence[ring[(j + 1) % m]];
            break;
        }
    }
    return into;
}

}  // namespace

MeshHierarchy::MeshHierarchy(const TriMesh& rest, const std::vector<int>& protectedVertices,
                             HierarchyOptions options)
    : MeshHierarchy(rest, MeshTopology(rest), protectedVertices, options) {}

MeshHierarchy::MeshHierarchy(const TriMesh& rest, const MeshTopology& restTopology,
                             const std::vector<int>& protectedVertices, HierarchyOptions options) {
    if (restTopology.vertexCount() != rest.vertexCount())
        throw SolverError("mesh hierarchy: the topology has " +
                          std::to_string(restTopology.vertexCount()) + " vertices, the mesh " +
                          std::to_string(rest.vertexCount()));
    std::vector<char> protectedInput(rest.vertexCount(), 0);
    for (int v : protectedVertices) {
        if (v < 0 || v >= rest.vertexCount())
            throw SolverError("mesh hierarchy: protected vertex " + std::to_string(v) +
                              " is not a vertex of the mesh (" +
                              std::to_string(rest.vertexCount()) + " vertices)");
        protectedInput[v] = 1;
    }

    HierarchyLevel first;
    first.mesh = rest;
    first.original.resize(rest.vertexCount());
    std::iota(first.original.begin(), first.original.end(), 0);
    levels_.push_back(std::move(first));
    // Quadrics accumulate over the levels, so a collapse's cost measures the distance to the
    // input surface, not only to the previous level.
    std::vector<Quadric> Q = faceQuadrics(rest);
    const Positions inputNormals = unitVertexNormals(rest);
    Rings topology = ringsOf(restTopology);

    while (levelCount() < std::max(options.maxLevels, 1) &&
           levels_.back().mesh.vertexCount() > options.coarsestVertices) {
        HierarchyLevel& fine = levels_.back();
        const int n = fine.mesh.vertexCount();
        std::vector<char> keep(n);
        for (int v = 0; v < n; ++v) keep[v] = protectedInput[fine.original[v]];
        Positions normals(n, 3);
        for (int v = 0; v < n; ++v) normals.row(v) = inputNormals.row(fine.original[v]);
        const std::vector<int> into = chooseCollapses(fine.mesh, normals, topology, keep, Q);

        const int removedCount =
            static_cast<int>(std::count_if(into.begin(), into.end(), [](int u) { return u >= 0; }));
        if (removedCount == 0 || removedCount < options.minRemovedFraction * n) break;

        HierarchyLevel coarse;
        fine.coarser.assign(n, -1);
        fine.removed.clear();
        fine.collapsedInto.clear();
        int count = 0;
        for (int v = 0; v < n; ++v) {
            if (into[v] < 0) {
                fine.coarser[v] = count++;
                coarse.original.push_back(fine.original[v]);
            } else {
                fine.removed.push_back(v);
                fine.collapsedInto.push_back(into[v]);
                Q[into[v]] += Q[v];
            }
        }
        std::vector<Quadric> coarseQ(count);
        for (int v = 0; v < n; ++v)
            if (into[v] < 0) coarseQ[fine.coarser[v]] = Q[v];
        Q.swap(coarseQ);

        coarse.mesh.V.resize(count, 3);
        for (int v = 0; v < count; ++v) coarse.mesh.V.row(v) = rest.V.row(coarse.original[v]);
        // A face holds at most one removed vertex (they are independent): the two faces on the
        // collapsed edge vanish, the others keep their corner order with r replaced by its target.
        coarse.mesh.F.resize(fine.mesh.faceCount(), 3);
        int faces = 0;
        for (int f = 0; f < fine.mesh.faceCount(); ++f) {
            int c[3] = {fine.mesh.F(f, 0), fine.mesh.F(f, 1), fine.mesh.F(f, 2)};
            bool vanishes = false;
            for (int k = 0; k < 3; ++k)
                if (into[c[k]] >= 0) {
                    const int u = into[c[k]];
                    vanishes = c[(k + 1) % 3] == u || c[(k + 2) % 3] == u;
                    c[k] = u;
                }
            if (vanishes) continue;
            coarse.mesh.F.row(faces++) << fine.coarser[c[0]], fine.coarser[c[1]],
                fine.coarser[c[2]];
        }
        coarse.mesh.F.conservativeResize(faces, 3);
        Rings coarseRings = coarserRings(topology, into, fine.coarser);
        keepRings(std::move(topology), fine);
        topology = std::move(coarseRings);
        levels_.push_back(std::move(coarse));
    }
    keepRings(std::move(topology), levels_.back());
}

}  // namespace boneless
