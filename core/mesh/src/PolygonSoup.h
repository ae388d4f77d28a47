#pragma once

// Internal to the mesh reader: what a format reader hands over before any checking.

#include <cstdint>
#include <numeric>
#include <string>
#include <unordered_set>
#include <vector>

#include "boneless/MeshReader.h"
#include "boneless/TriMesh.h"

namespace boneless::detail {

// Vertices and polygons exactly as the file lists them: no merging, no topology, indices 0-based
// but not yet range-checked. Lines are 1-based, 0 where the format has none (binary files).
struct PolygonSoup {
    std::vector<double> xyz;        // 3 per vertex
    std::vector<int> vertexLine;    // per vertex, or empty
    std::vector<int> faceStart{0};  // face f is faceIndex[faceStart[f] .. faceStart[f+1])
    std::vector<int> faceIndex;
    std::vector<int> faceLine;  // per face, or empty
    std::vector<int> fileFace;  // per face its number among all the file's faces; empty = same
    // OBJ only: per entry of faceIndex its "vt" index (-1 none); every "vt" of the file; per face
    // its "usemtl" (-1 none) into materialNames; the "mtllib" files, as written.
    std::vector<int> uvOf;
    std::vector<double> uv;
    std::vector<int> faceMaterial;
    std::vector<std::string> materialNames, materialLibraries;
    std::vector<std::string> warnings;

    int vertexCount() const { return static_cast<int>(xyz.size() / 3); }
    int faceCount() const { return static_cast<int>(faceStart.size()) - 1; }
    int fileFaceOf(int f) const { return fileFace.empty() ? f : fileFace[f]; }
    void endFace() { faceStart.push_back(static_cast<int>(faceIndex.size())); }
};

// Sets of indices joined pairwise (vertices of one piece, corners of one fan).
class UnionFind {
  public:
    explicit UnionFind(size_t n) : parent_(n) { std::iota(parent_.begin(), parent_.end(), 0); }
    int find(int x) {
        while (parent_[x] != x) x = parent_[x] = parent_[parent_[x]];
        return x;
    }
    void join(int a, int b) { parent_[find(a)] = find(b); }

  private:
    std::vector<int> parent_;
};

// "face 12 (line 40)", "vertex 3"
std::string faceWhere(const PolygonSoup& soup, int face);
std::string vertexWhere(const PolygonSoup& soup, int vertex);

// OBJ, own parser. group empty = every face; otherwise only faces of that "g"/"o" group.
PolygonSoup readObj(const std::string& path, const std::string& group);
std::vector<ObjGroup> readObjGroups(const std::string& path);

// OFF, PLY, STL: a plausibility pass over the text formats, whose OpenMesh parsers turn malformed
// numbers into silent garbage (text OFF it reads itself), then OpenMesh for the rest.
PolygonSoup readWithOpenMesh(const std::string& path);

// Splits polygon `corners` (>= 3 vertex indices into V) into corners.size() - 2 triangles
// appended to `out`, never creating a triangle that folds over the polygon when an ear exists.
// `edges` (edgeKey) holds the mesh's edges so far: every polygon's sides and the diagonals cut
// before; the polygon's diagonals join them, and `repeated` gets any that had to be one of them.
uint64_t edgeKey(int a, int b);
void triangulatePolygon(const Positions& V, const int* corners, int n,
                        std::unordered_set<uint64_t>& edges, std::vector<int>& out,
                        std::unordered_set<uint64_t>& repeated);

// Per mesh vertex (meshIndex maps the soup's), the vertex it is welded to: copies at the same
// position (within 1e-6 of the used vertices' bounding-box diagonal), the first in file order
// standing for them, where the kept polygons about it still form one fan. `welded`: copies.
std::vector<int> weldCopies(const Positions& V, const PolygonSoup& soup,
                            const std::vector<int>& kept, const std::vector<int>& meshIndex,
                            int& welded);

// The first triangle of each piece (connected through vertices) that encloses volume with its
// faces wound inward, the normals pointing into it; F consistently oriented.
std::vector<int> insideOutPieces(const Positions& V, const Faces& F);

// Throws MeshError for non-manifold edges, inconsistent orientation and non-manifold vertices;
// fills the boundary and component counts of `result`. F rows come from soup faces `faceOf`.
struct TopologySummary {
    int boundaryEdges = 0, boundaryLoops = 0, components = 0, isolatedVertices = 0;
    std::vector<int> isolated;  // first few isolated vertices, for the warning
};
// `repeated`: edges (edgeKey) the triangulation cut again, to say it made them, not the file.
// `weldedTo`: weldCopies', whose copies F does not use and are not isolated.
TopologySummary checkManifold(const std::string& file, const Faces& F, int vertexCount,
                              const std::vector<int>& faceOf, const PolygonSoup& soup,
                              const std::vector<int>& vertexOf,
                              const std::unordered_set<uint64_t>& repeated,
                              const std::vector<int>& weldedTo);

}  // namespace boneless::detail
