#pragma once

#include <vector>

#include "boneless/TriMesh.h"

namespace boneless {

// An order of a mesh's vertices in which neighbours sit near each other in memory, for a solver
// to work in and translate from at its edges. Meshes come in any order: koala's (100K faces) is
// scattered, 70 % of ring neighbours over 2,000 places apart, so that every loop over rings or
// faces waits on memory. In this order its input level prepared in 235 ms instead of 345.
// The order is the Morton (Z-curve) order of the vertex positions, faces sorted by their vertices
// after it, so it depends on the geometry alone: the same mesh in another order gets the same one,
// except among coincident vertices (kept in the caller's order) and in where each face's corners
// start (kept as given).
class VertexOrder {
  public:
    VertexOrder() = default;  // the identity
    static VertexOrder spatial(const TriMesh& mesh);

    bool identity() const { return internalOf_.empty(); }
    // The mesh in this order (faces keep their corners' order, so their orientation).
    TriMesh apply(const TriMesh& mesh) const;
    std::vector<int> toInternal(const std::vector<int>& vertices) const;
    // #V by 3, from the caller's order to this one and back.
    Positions toInternal(const Positions& V) const;
    Positions toUser(const Positions& V) const;

  private:
    std::vector<int> internalOf_;  // per caller's vertex
    std::vector<int> userOf_;      // per vertex in this order
};

}  // namespace boneless
