#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <limits>
#include <map>
#include <random>
#include <set>

#include "TestMeshes.h"
#include "boneless/Error.h"
#include "MeshHierarchy.h"
#include "boneless/MeshReader.h"
#include "boneless/MeshTopology.h"
#include "boneless/ShapeEncoding.h"

using namespace boneless;
using namespace boneless::testing;

namespace {

using Vec3 = Eigen::Vector3d;

Vec3 pos(const Positions& V, int i) {
    return V.row(i).transpose();
}

// A wavy height field over [0,1]² with alternating diagonals: a patch with one boundary loop.
TriMesh wavyGrid(int cells) {
    TriMesh m;
    const int side = cells + 1;
    m.V.resize(side * side, 3);
    for (int y = 0; y < side; ++y)
        for (int x = 0; x < side; ++x) {
            const double u = double(x) / cells, v = double(y) / cells;
            m.V.row(y * side + x) << u, v, 0.08 * std::sin(6 * u) * std::cos(5 * v);
        }
    m.F.resize(2 * cells * cells, 3);
    int f = 0;
    for (int y = 0; y < cells; ++y)
        for (int x = 0; x < cells; ++x) {
            const int a = y * side + x, b = a + 1, c = a + side, d = c + 1;
            if ((x + y) % 2) {
                m.F.row(f++) << a, b, d;
                m.F.row(f++) << a, d, c;
            } else {
                m.F.row(f++) << a, b, c;
                m.F.row(f++) << b, d, c;
            }
        }
    return m;
}

// An icosphere with its top cut off along faces: a jagged boundary loop whose corners have one or
// two faces, where a careless collapse would leave a boundary vertex with a single face.
TriMesh cutSphere(int subdivisions, double zCut) {
    const TriMesh sphere = icosphere(subdivisions);
    std::vector<int> index(sphere.vertexCount(), -1);
    std::vector<Eigen::Vector3i> faces;
    int used = 0;
    for (int f = 0; f < sphere.faceCount(); ++f) {
        double z = 0;
        for (int k = 0; k < 3; ++k) z += sphere.V(sphere.F(f, k), 2) / 3;
        if (z > zCut) continue;
        Eigen::Vector3i face;
        for (int k = 0; k < 3; ++k) {
            int& i = index[sphere.F(f, k)];
            if (i < 0) i = used++;
            face[k] = i;
        }
        faces.push_back(face);
    }
    TriMesh m;
    m.V.resize(used, 3);
    for (int v = 0; v < sphere.vertexCount(); ++v)
        if (index[v] >= 0) m.V.row(index[v]) = sphere.V.row(v);
    m.F.resize(faces.size(), 3);
    for (size_t f = 0; f < faces.size(); ++f) m.F.row(f) = faces[f].transpose();
    return m;
}

// The icosphere with every vertex moved radially and tangentially at random: irregular valences
// stay, but faces are uneven and the surface is bumpy, which is where collapses fold.
TriMesh jitteredSphere(int subdivisions, double amount, unsigned seed) {
    TriMesh m = icosphere(subdivisions);
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> u(-amount, amount);
    const double edge = (pos(m.V, m.F(0, 0)) - pos(m.V, m.F(0, 1))).norm();
    for (int i = 0; i < m.vertexCount(); ++i) {
        const Vec3 p = pos(m.V, i);
        m.V.row(i) = (p * (1 + 0.3 * u(rng)) + edge * Vec3(u(rng), u(rng), u(rng))).transpose();
    }
    return m;
}

std::vector<int> spreadVertices(int n, int count) {
    std::vector<int> ids;
    for (int k = 0; k < count; ++k) ids.push_back(static_cast<int>((k * 7919LL) % n));
    std::sort(ids.begin(), ids.end());
    ids.erase(std::unique(ids.begin(), ids.end()), ids.end());
    return ids;
}

double minAngleSin(const Vec3& a, const Vec3& b, const Vec3& c) {
    double l[3] = {(b - a).squaredNorm(), (c - b).squaredNorm(), (a - c).squaredNorm()};
    std::sort(l, l + 3);
    return (b - a).cross(c - a).norm() / std::sqrt(l[1] * l[2]);
}

double worstMinAngleSin(const TriMesh& m) {
    double worst = 1;
    for (int f = 0; f < m.faceCount(); ++f)
        worst = std::min(
            worst, minAngleSin(pos(m.V, m.F(f, 0)), pos(m.V, m.F(f, 1)), pos(m.V, m.F(f, 2))));
    return worst;
}

struct EdgeCensus {
    int edges = 0;
    int nonManifoldEdges = 0;   // in more than two faces
    int repeatedHalfEdges = 0;  // the same directed edge twice: inconsistent orientation
    std::set<std::pair<int, int>> boundary;  // as original-id pairs (directed)
};

EdgeCensus census(const HierarchyLevel& level) {
    std::map<std::pair<int, int>, int> undirected;
    std::set<std::pair<int, int>> directed;
    EdgeCensus c;
    for (int f = 0; f < level.mesh.faceCount(); ++f)
        for (int k = 0; k < 3; ++k) {
            const int a = level.mesh.F(f, k), b = level.mesh.F(f, (k + 1) % 3);
            if (!directed.insert({a, b}).second) ++c.repeatedHalfEdges;
            ++undirected[std::minmax(a, b)];
        }
    for (const auto& [e, count] : undirected) {
        ++c.edges;
        if (count > 2) ++c.nonManifoldEdges;
    }
    for (const auto& [a, b] : directed)
        if (!directed.count({b, a})) c.boundary.insert({level.original[a], level.original[b]});
    return c;
}

std::array<int, 3> canonical(int a, int b, int c) {  // same cyclic order, smallest id first
    if (b < a && b < c) return {b, c, a};
    if (c < a && c < b) return {c, a, b};
    return {a, b, c};
}

// Faces (as original ids) whose normal points against the input's smoothed normal over them (the
// sum of the unit area-weighted vertex normals at its corners): folds. The input may have a few; a
// level must add none.
std::set<std::array<int, 3>> foldedFaces(const HierarchyLevel& level,
                                         const Positions& inputNormals) {
    std::set<std::array<int, 3>> folded;
    const TriMesh& m = level.mesh;
    for (int f = 0; f < m.faceCount(); ++f) {
        const Vec3 a = pos(m.V, m.F(f, 0)), b = pos(m.V, m.F(f, 1)), c = pos(m.V, m.F(f, 2));
        const Vec3 n = (b - a).cross(c - a);
        Vec3 smooth = Vec3::Zero();
        for (int k = 0; k < 3; ++k) smooth += pos(inputNormals, level.original[m.F(f, k)]);
        if (n.dot(smooth) <= 0)
            folded.insert(canonical(level.original[m.F(f, 0)], level.original[m.F(f, 1)],
                                    level.original[m.F(f, 2)]));
    }
    return folded;
}

Positions vertexNormals(const TriMesh& m) {
    Positions N = Positions::Zero(m.vertexCount(), 3);
    for (int f = 0; f < m.faceCount(); ++f) {
        const Vec3 a = pos(m.V, m.F(f, 0)), b = pos(m.V, m.F(f, 1)), c = pos(m.V, m.F(f, 2));
        for (int k = 0; k < 3; ++k) N.row(m.F(f, k)) += (b - a).cross(c - a).transpose();
    }
    N.rowwise().normalize();
    return N;
}

// The level's own rings against MeshTopology's, each closed ring rotated to start alike.
void expectSameRings(const HierarchyLevel& L, const MeshTopology& t) {
    ASSERT_EQ(L.ringOffsets.size(), t.offsets().size());
    ASSERT_EQ(L.rings.size(), t.neighbours().size());
    ASSERT_EQ(static_cast<int>(L.boundary.size()), t.vertexCount());
    for (int v = 0; v < t.vertexCount(); ++v) {
        std::vector<int> mine(L.rings.begin() + L.ringOffsets[v],
                              L.rings.begin() + L.ringOffsets[v + 1]);
        const std::vector<int> theirs(t.ring(v), t.ring(v) + t.valence(v));
        EXPECT_EQ(bool(L.boundary[v]), t.isBoundary(v)) << v;
        if (!mine.empty() && !theirs.empty()) {
            const auto start = std::find(mine.begin(), mine.end(), theirs[0]);
            if (start != mine.end()) std::rotate(mine.begin(), start, mine.end());
        }
        EXPECT_EQ(mine, theirs) << "ring of " << v;
    }
}

// Every structural promise the solver relies on; the property tests below run it on many meshes.
void expectSoundHierarchy(const TriMesh& rest, const std::vector<int>& protectedIds,
                          const MeshHierarchy& h, const HierarchyOptions& options) {
    ASSERT_GE(h.levelCount(), 1);
    EXPECT_LE(h.levelCount(), options.maxLevels);
    EXPECT_EQ(h.level(0).mesh.V, rest.V);
    EXPECT_EQ(h.level(0).mesh.F, rest.F);
    const EdgeCensus input = census(h.level(0));
    const int inputEuler = rest.vertexCount() - input.edges + rest.faceCount();
    const double inputWorstSin = worstMinAngleSin(rest);
    const Positions inputNormals = vertexNormals(rest);
    const std::set<std::array<int, 3>> inputFolds = foldedFaces(h.level(0), inputNormals);
    const MeshTopology inputTopology(rest);

    for (int l = 0; l < h.levelCount(); ++l) {
        SCOPED_TRACE("level " + std::to_string(l));
        const HierarchyLevel& L = h.level(l);
        const int n = L.mesh.vertexCount();
        ASSERT_EQ(static_cast<int>(L.original.size()), n);

        // Vertices: distinct original ids at their exact rest positions, protected ones present.
        std::set<int> ids(L.original.begin(), L.original.end());
        EXPECT_EQ(static_cast<int>(ids.size()), n);
        for (int v = 0; v < n; ++v) {
            ASSERT_TRUE(L.original[v] >= 0 && L.original[v] < rest.vertexCount());
            EXPECT_EQ(L.mesh.V.row(v), rest.V.row(L.original[v]));
        }
        for (int p : protectedIds) EXPECT_TRUE(ids.count(p)) << "protected vertex " << p;

        // Clean mesh: proper faces, manifold, oriented like the input, same topology, same
        // boundary (as original ids), no slivers beyond what the input already has.
        for (int f = 0; f < L.mesh.faceCount(); ++f) {
            const int a = L.mesh.F(f, 0), b = L.mesh.F(f, 1), c = L.mesh.F(f, 2);
            ASSERT_TRUE(a >= 0 && b >= 0 && c >= 0 && a < n && b < n && c < n);
            EXPECT_TRUE(a != b && b != c && c != a);
            EXPECT_GE(minAngleSin(pos(L.mesh.V, a), pos(L.mesh.V, b), pos(L.mesh.V, c)),
                      std::min(0.13, inputWorstSin) * (1 - 1e-9))
                << "face " << f;
        }
        const EdgeCensus e = census(L);
        EXPECT_EQ(e.nonManifoldEdges, 0);
        EXPECT_EQ(e.repeatedHalfEdges, 0);
        EXPECT_EQ(e.boundary, input.boundary);
        EXPECT_EQ(n - e.edges + L.mesh.faceCount(), inputEuler);
        ASSERT_NO_THROW(MeshTopology{L.mesh});  // every vertex a single fan
        const MeshTopology topology(L.mesh);
        expectSameRings(L, topology);
        for (int v = 0; v < n; ++v)  // no valence drops below 3 (or below what the input had)
            EXPECT_GE(topology.valence(v), std::min(3, inputTopology.valence(L.original[v]))) << v;
        const std::set<std::array<int, 3>> folds = foldedFaces(L, inputNormals);
        EXPECT_TRUE(std::includes(inputFolds.begin(), inputFolds.end(), folds.begin(), folds.end()))
            << folds.size() << " folded faces, the input has " << inputFolds.size();

        if (l + 1 == h.levelCount()) {
            EXPECT_TRUE(L.coarser.empty());
            EXPECT_TRUE(L.removed.empty());
            continue;
        }
        const HierarchyLevel& C = h.level(l + 1);
        EXPECT_LT(C.mesh.vertexCount(), n);
        EXPECT_GE(static_cast<double>(L.removed.size()), options.minRemovedFraction * n);

        // Maps: removed = the vertices without a coarser index, ascending; survivors map onto
        // level l+1 one to one, keeping their original ids.
        ASSERT_EQ(static_cast<int>(L.coarser.size()), n);
        ASSERT_EQ(L.collapsedInto.size(), L.removed.size());
        std::vector<int> removed, hit(C.mesh.vertexCount(), 0);
        for (int v = 0; v < n; ++v) {
            if (L.coarser[v] < 0) {
                removed.push_back(v);
                continue;
            }
            ASSERT_LT(L.coarser[v], C.mesh.vertexCount());
            ++hit[L.coarser[v]];
            EXPECT_EQ(C.original[L.coarser[v]], L.original[v]);
        }
        EXPECT_EQ(removed, L.removed);
        EXPECT_EQ(n - static_cast<int>(removed.size()), C.mesh.vertexCount());
        EXPECT_TRUE(std::all_of(hit.begin(), hit.end(), [](int k) { return k == 1; }));

        // Independence and encodability: every removed vertex is interior, unprotected, Full, and
        // its ring (containing the vertex it collapsed into) survives.
        const ShapeEncoding encoding(L.mesh, topology);
        std::set<int> protectedSet(protectedIds.begin(), protectedIds.end());
        for (size_t k = 0; k < L.removed.size(); ++k) {
            const int r = L.removed[k];
            EXPECT_FALSE(topology.isBoundary(r)) << r;
            EXPECT_FALSE(protectedSet.count(L.original[r])) << r;
            EXPECT_EQ(encoding.kind(r), ShapeEncoding::Kind::Full) << r;
            // Star-shaped ring: prolongation is a convex combination of the ring plus a height.
            const double* w = encoding.weights(r);
            EXPECT_GT(*std::min_element(w, w + topology.valence(r)), 0) << r;
            const int* ring = topology.ring(r);
            for (int j = 0; j < topology.valence(r); ++j)
                EXPECT_GE(L.coarser[ring[j]], 0)
                    << "removed " << r << " next to removed " << ring[j];
            const int m = topology.valence(r),
                      j = static_cast<int>(std::find(ring, ring + m, L.collapsedInto[k]) - ring);
            ASSERT_LT(j, m) << "collapsed into a non-neighbour";
            // No collapse flips a face: each face (r, a, b) that survives as (u, a, b) keeps its
            // side.
            const Vec3 pr = pos(L.mesh.V, r), pu = pos(L.mesh.V, ring[j]);
            for (int i = 0; i < m; ++i) {
                const int i1 = (i + 1) % m;
                if (i == j || i1 == j) continue;
                const Vec3 a = pos(L.mesh.V, ring[i]), b = pos(L.mesh.V, ring[i1]);
                EXPECT_GT((a - pu).cross(b - pu).dot((a - pr).cross(b - pr)), 0) << r;
            }
        }
    }
}

// What the solver does: fill level l from level l+1, then place each removed vertex from its ring.
// Removed rows start as NaN, so reading anything but survivors shows.
Positions prolongAll(const MeshHierarchy& h, int l, const Positions& coarserPositions) {
    const HierarchyLevel& L = h.level(l);
    Positions V =
        Positions::Constant(L.mesh.vertexCount(), 3, std::numeric_limits<double>::quiet_NaN());
    for (int v = 0; v < L.mesh.vertexCount(); ++v)
        if (L.coarser[v] >= 0) V.row(v) = coarserPositions.row(L.coarser[v]);
    const MeshTopology topology(L.mesh);
    const ShapeEncoding encoding(L.mesh, topology);
    Positions out = V;
    for (int r : L.removed) out.row(r) = encoding.decode(r, V).transpose();
    return out;
}

void expectExactProlongation(const MeshHierarchy& h) {
    std::mt19937 rng(7);
    const Eigen::Matrix3d R = randomRotation(rng);
    const Vec3 t(0.3, -1.2, 2.0);
    const double scale = boundingBoxDiagonal(h.level(0).mesh.V);
    auto moved = [&](const Positions& V) {
        Positions out = V * R.transpose();
        out.rowwise() += t.transpose();
        return out;
    };
    // From the coarsest rest (or rigidly moved) pose all the way down, level by level.
    Positions still = h.coarsest().mesh.V, rigid = moved(still);
    for (int l = h.levelCount() - 2; l >= 0; --l) {
        SCOPED_TRACE("level " + std::to_string(l));
        still = prolongAll(h, l, still);
        rigid = prolongAll(h, l, rigid);
        const Positions& rest = h.level(l).mesh.V;
        EXPECT_LE((still - rest).cwiseAbs().maxCoeff(), 1e-12 * scale);
        EXPECT_LE((rigid - moved(rest)).cwiseAbs().maxCoeff(), 1e-12 * scale);
    }
}

std::string sharedMesh(const std::string& relative) {
    return (std::filesystem::path(BONELESS_SHARED_DATA) / relative).string();
}

std::string levelSizes(const MeshHierarchy& h) {
    std::string s;
    for (int l = 0; l < h.levelCount(); ++l)
        s += (l ? " > " : "") + std::to_string(h.level(l).mesh.vertexCount());
    return s;
}

}  // namespace

TEST(MeshHierarchy, IcosphereCoarsensToTheTargetWithSoundLevels) {
    const TriMesh sphere = icosphere(5);  // 10,242 vertices
    const std::vector<int> markers = spreadVertices(sphere.vertexCount(), 40);
    HierarchyOptions options;
    options.coarsestVertices = 300;
    const MeshHierarchy h(sphere, markers, options);
    std::printf("icosphere(5): %s\n", levelSizes(h).c_str());
    EXPECT_LE(h.coarsest().mesh.vertexCount(), options.coarsestVertices);
    expectSoundHierarchy(sphere, markers, h, options);
    // A sphere stays convex: every face of every level points away from the centre.
    for (int l = 0; l < h.levelCount(); ++l) {
        const TriMesh& m = h.level(l).mesh;
        for (int f = 0; f < m.faceCount(); ++f) {
            const Vec3 a = pos(m.V, m.F(f, 0)), b = pos(m.V, m.F(f, 1)), c = pos(m.V, m.F(f, 2));
            EXPECT_GT((b - a).cross(c - a).dot(a + b + c), 0) << "level " << l << " face " << f;
        }
    }
}

TEST(MeshHierarchy, EveryLevelRemovesAFifthOrMoreOfARegularMesh) {
    const TriMesh sphere = icosphere(5);
    const MeshHierarchy h(sphere, {}, HierarchyOptions{300, 16});
    for (int l = 0; l + 1 < h.levelCount(); ++l) {
        const double fraction = double(h.level(l).removed.size()) / h.level(l).mesh.vertexCount();
        // On a regular mesh the costs are nearly all equal, so the greedy set is close to a random
        // maximal independent set of a triangular lattice: ~23% (the best packing is 1/3).
        EXPECT_GE(fraction, 0.2) << "level " << l;
        EXPECT_LE(fraction, 0.4) << "level " << l;
    }
}

TEST(MeshHierarchy, ProlongationReproducesRestAndRigidMotionsExactly) {
    const TriMesh sphere = icosphere(4);
    expectExactProlongation(
        MeshHierarchy(sphere, spreadVertices(sphere.vertexCount(), 20), HierarchyOptions{100, 16}));
    const TriMesh bumpy = jitteredSphere(4, 0.3, 3);
    expectExactProlongation(MeshHierarchy(bumpy, {}, HierarchyOptions{100, 16}));
    const TriMesh grid = wavyGrid(40);
    expectExactProlongation(MeshHierarchy(grid, {}, HierarchyOptions{100, 16}));
}

TEST(MeshHierarchy, IrregularBumpyMeshesStaySound) {
    for (unsigned seed : {1u, 2u, 3u}) {
        SCOPED_TRACE("seed " + std::to_string(seed));
        const TriMesh bumpy = jitteredSphere(4, 0.4, seed);
        const std::vector<int> markers = spreadVertices(bumpy.vertexCount(), 25);
        const HierarchyOptions options{200, 16};
        const MeshHierarchy h(bumpy, markers, options);
        expectSoundHierarchy(bumpy, markers, h, options);
        EXPECT_GE(h.levelCount(), 3) << levelSizes(h);
    }
}

TEST(MeshHierarchy, BoundaryVerticesAreNeverRemoved) {
    const TriMesh grid = wavyGrid(60);     // one boundary loop, 240 boundary vertices
    const TriMesh open = tube(30, 24, 3);  // two loops
    const TriMesh cut = cutSphere(4, 0.35);
    for (const TriMesh* mesh : {&grid, &open, &cut}) {
        const std::vector<int> markers = spreadVertices(mesh->vertexCount(), 15);
        const HierarchyOptions options{50, 16};
        const MeshHierarchy h(*mesh, markers, options);
        expectSoundHierarchy(*mesh, markers, h, options);  // includes: same boundary edges
        ASSERT_GE(h.levelCount(), 2) << levelSizes(h);
        const MeshTopology topology(*mesh);
        std::set<int> coarse(h.coarsest().original.begin(), h.coarsest().original.end());
        for (int v = 0; v < mesh->vertexCount(); ++v)
            if (topology.isBoundary(v)) EXPECT_TRUE(coarse.count(v)) << v;
        // The interior still coarsens: only boundary (and protected) vertices are left at last.
        int interiorLeft = 0;
        for (int v : coarse) interiorLeft += !topology.isBoundary(v);
        EXPECT_LT(interiorLeft, mesh->vertexCount() / 4) << levelSizes(h);
    }
}

TEST(MeshHierarchy, ProtectingEveryOtherVertexStillGivesAValidHierarchy) {
    const TriMesh sphere = icosphere(3);
    std::vector<int> markers;
    for (int v = 0; v < sphere.vertexCount(); v += 2) markers.push_back(v);
    const HierarchyOptions options{10, 16};
    const MeshHierarchy h(sphere, markers, options);
    expectSoundHierarchy(sphere, markers, h, options);
    EXPECT_GE(h.coarsest().mesh.vertexCount(), static_cast<int>(markers.size()));
}

TEST(MeshHierarchy, OptionsBoundTheLevels) {
    const TriMesh sphere = icosphere(4);
    const MeshHierarchy two(sphere, {}, HierarchyOptions{10, 2});
    EXPECT_EQ(two.levelCount(), 2);
    const MeshHierarchy one(sphere, {}, HierarchyOptions{sphere.vertexCount(), 16});
    ASSERT_EQ(one.levelCount(), 1);
    EXPECT_TRUE(one.level(0).coarser.empty());
    // Demanding more than any level can remove leaves the input alone.
    HierarchyOptions greedy{10, 16};
    greedy.minRemovedFraction = 0.6;
    EXPECT_EQ(MeshHierarchy(sphere, {}, greedy).levelCount(), 1);
}

TEST(MeshHierarchy, IsDeterministic) {
    const TriMesh bumpy = jitteredSphere(3, 0.3, 5);
    const MeshHierarchy a(bumpy, {1, 2, 3}, HierarchyOptions{50, 16});
    const MeshHierarchy b(bumpy, {1, 2, 3}, HierarchyOptions{50, 16});
    ASSERT_EQ(a.levelCount(), b.levelCount());
    for (int l = 0; l < a.levelCount(); ++l) {
        EXPECT_EQ(a.level(l).original, b.level(l).original);
        EXPECT_EQ(a.level(l).mesh.F, b.level(l).mesh.F);
    }
}

TEST(MeshHierarchy, GivenTheInputTopologyBuildsTheSameLevels) {
    const TriMesh bumpy = jitteredSphere(3, 0.3, 9);
    const MeshTopology topology(bumpy);
    const MeshHierarchy a(bumpy, {4, 5}, HierarchyOptions{50, 16});
    const MeshHierarchy b(bumpy, topology, {4, 5}, HierarchyOptions{50, 16});
    ASSERT_EQ(a.levelCount(), b.levelCount());
    for (int l = 0; l < a.levelCount(); ++l) {
        EXPECT_EQ(a.level(l).original, b.level(l).original);
        EXPECT_EQ(a.level(l).mesh.F, b.level(l).mesh.F);
        EXPECT_EQ(a.level(l).rings, b.level(l).rings);
    }
    EXPECT_THROW(MeshHierarchy(bumpy, MeshTopology(icosphere(1)), {}), SolverError);
}

TEST(MeshHierarchy, RejectsProtectedIdsOutOfRange) {
    const TriMesh sphere = icosphere(2);
    EXPECT_THROW(MeshHierarchy(sphere, {sphere.vertexCount()}), SolverError);
    EXPECT_THROW(MeshHierarchy(sphere, {-1}), SolverError);
}

TEST(MeshHierarchy, KoalaWhenTheSharedDataIsPresent) {
    const std::string path = sharedMesh("meshes/koala/koala.obj");
    if (!std::filesystem::exists(path)) GTEST_SKIP() << "no " << path;
    const TriMesh koala = readMesh(path).mesh;
    const std::vector<int> markers = spreadVertices(koala.vertexCount(), 60);
    const HierarchyOptions options;
    const auto start = std::chrono::steady_clock::now();
    const MeshHierarchy h(koala, markers, options);
    const double ms =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    std::printf("koala: %s vertices, built in %.1f ms\n", levelSizes(h).c_str(), ms);
    EXPECT_LE(h.coarsest().mesh.vertexCount(), options.coarsestVertices);
    for (int l = 0; l + 1 < h.levelCount(); ++l)
        EXPECT_GE(double(h.level(l).removed.size()) / h.level(l).mesh.vertexCount(), 0.2) << l;
    expectSoundHierarchy(koala, markers, h, options);
    expectExactProlongation(h);
}

TEST(MeshHierarchy, RejectsANonManifoldInput) {
    TriMesh bowtie;  // two triangles sharing only vertex 0: two fans there
    bowtie.V.resize(5, 3);
    bowtie.V << 0, 0, 0, 1, 0, 0, 1, 1, 0, -1, 0, 0, -1, -1, 0;
    bowtie.F.resize(2, 3);
    bowtie.F << 0, 1, 2, 0, 3, 4;
    EXPECT_THROW(MeshHierarchy(bowtie, {}, HierarchyOptions{1, 16}), MeshError);
}
