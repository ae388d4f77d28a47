#pragma once

#include <vector>

#include "boneless/MeshTopology.h"

namespace boneless {

// The sparsity of a sum over stencils of all their vertex pairs (the Gauss–Newton matrix's: a
// residual couples every pair of vertices it depends on), one entry per vertex pair, both
// triangles, and where each stencil's pairs land in it. BlockSystem (3×3 blocks) and ScalarSystem
// (one number per pair) are both laid out from it.
class StencilPattern {
  public:
    // Which pairs a lumped pattern keeps: each vertex with itself and with its edge neighbours,
    // a third of a Gauss–Newton matrix's pairs. A pair it drops lands on the diagonal of its
    // column's vertex (see entry()), or of its row's vertex when that one is fixed (its row and
    // column become the identity's later), so that it goes with them.
    struct Lumping {
        const MeshTopology& topology;
        const std::vector<char>& fixed;  // per vertex
    };

    // stencils[r] = the vertices residual r depends on, each at most once.
    StencilPattern(int vertexCount, const std::vector<std::vector<int>>& stencils,
                   const Lumping* lumping = nullptr);

    // Column b holds rows inner()[outer()[b] .. outer()[b+1]), ascending.
    const std::vector<int>& outer() const { return outer_; }
    const std::vector<int>& inner() const { return inner_; }
    int stencilCount() const { return static_cast<int>(size_.size()); }
    int stencilSize(int r) const { return size_[r]; }
    // The index into inner() of the pair (stencil r's a-th vertex, its b-th vertex); for a pair
    // a lumped pattern dropped onto a diagonal, −1 − that diagonal's index.
    int entry(int r, int a, int b) const { return entries_[offset_[r] + a * size_[r] + b]; }
    int diagonal(int v) const { return diagonal_[v]; }

  private:
    // A lumped pattern's columns: each vertex and its ring.
    void layOutRings(const MeshTopology& topology);

    std::vector<int> outer_, inner_;
    std::vector<int> size_;     // per stencil
    std::vector<long> offset_;  // per stencil, into entries_ (size² each)
    std::vector<int> entries_;
    std::vector<int> diagonal_;  // per vertex
};

}  // namespace boneless
