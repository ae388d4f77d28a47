#pragma once

#include <vector>

#include "boneless/TriMesh.h"

namespace boneless {

class MeshTopology;

// One level of the hierarchy. Level 0 is the input mesh; each next level is made from the previous
// one by half-edge collapses of an independent set of vertices, so coarse vertices are original
// vertices at their rest positions.
struct HierarchyLevel {
    TriMesh mesh;               // this level: rest positions (rows of the input's V), own faces
    std::vector<int> original;  // level vertex -> input (level-0) vertex id
    std::vector<int> coarser;   // level vertex -> its index in level+1, or -1 when removed going
                                // there (empty for the coarsest level)
    std::vector<int> removed;   // the level vertices removed going to level+1, ascending
    std::vector<int> collapsedInto;  // aligned with removed: the ring neighbour (a level vertex)
                                     // each one was collapsed into
    // The one-rings of `mesh` as MeshTopology(mesh) has them: same CSR layout, same cyclic order
    // (a closed ring may start at another neighbour). Ring v is rings[ringOffsets[v] ..
    // ringOffsets[v + 1]); boundary[v] is 1 for a boundary vertex.
    std::vector<int> ringOffsets, rings;
    std::vector<char> boundary;
};

struct HierarchyOptions {
    // Stop at or below this many vertices (§1.6: ~300–2000, or ~10x the markers).
    int coarsestVertices = 2000;
    // levelCount() never exceeds this (level 0 included; at least 1).
    int maxLevels = 16;
    // A level that would remove fewer than this fraction of its vertices is not made: the previous
    // one is the coarsest (it may then be larger than coarsestVertices).
    double minRemovedFraction = 0.05;
};

// The mesh hierarchy of docs/algorithm.md §4 (the local/global method's coarse level is its
// coarsest). Every removed vertex is interior, not protected, and ShapeEncoding-Full on its
// level's mesh with a star-shaped ring (positive mean-value weights), and its whole ring
// survives into the next level, so the next level's positions determine it explicitly. Each level
// is a manifold mesh oriented like the input with the input's topology (half-edge collapses under
// the link condition); boundary vertices are never removed. Hand-written rather than OpenMesh's
// Decimater: that was measured slower to build and less accurate (docs/benchmarks.md, 27 Nov 2026).
class MeshHierarchy {
  public:
    // protectedVertices (input ids, e.g. the marker vertices) survive into every level. Throws
    // SolverError for an id out of range and MeshError when the input is not manifold.
    MeshHierarchy(const TriMesh& rest, const std::vector<int>& protectedVertices,
                  HierarchyOptions options = {});
    // The same from the input's MeshTopology, e.g. the one its ShapeEncoding holds, instead of
    // building it again (~10% of the time here).
    MeshHierarchy(const TriMesh& rest, const MeshTopology& restTopology,
                  const std::vector<int>& protectedVertices, HierarchyOptions options = {});

    int levelCount() const { return static_cast<int>(levels_.size()); }
    const HierarchyLevel& level(int l) const { return levels_[l]; }
    const HierarchyLevel& coarsest() const { return levels_.back(); }

  private:
    std::vector<HierarchyLevel> levels_;
};

}  // namespace boneless
