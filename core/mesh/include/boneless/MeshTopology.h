#pragma once

#include <vector>

#include "boneless/TriMesh.h"

namespace boneless {

// One-rings in cyclic order, the order the faces' orientation induces (counter-clockwise seen from
// outside), which is what makes Σ p_k × p_{k+1} point outwards. A boundary vertex's ring runs from
// one boundary neighbour to the other through its faces.
class MeshTopology {
  public:
    explicit MeshTopology(const TriMesh& mesh);

    int vertexCount() const { return static_cast<int>(offsets_.size()) - 1; }
    int valence(int v) const { return offsets_[v + 1] - offsets_[v]; }
    const int* ring(int v) const { return neighbours_.data() + offsets_[v]; }
    bool isBoundary(int v) const { return boundary_[v]; }
    bool isIsolated(int v) const { return valence(v) == 0; }
    int boundaryVertexCount() const;

    // CSR layout, for code that walks every ring.
    const std::vector<int>& offsets() const { return offsets_; }
    const std::vector<int>& neighbours() const { return neighbours_; }

  private:
    std::vector<int> offsets_;
    std::vector<int> neighbours_;
    std::vector<char> boundary_;
};

}  // namespace boneless
