#pragma once

#include <vector>

#include "boneless/MeshTopology.h"

namespace boneless {

// Per stencil, the vertices it depends on, each at most once, stored flat: a 100K-face mesh has
// 150,000 stencils, which as vectors of their own were as many allocations.
struct Stencils {
    Stencils() = default;
    Stencils(const std::vector<std::vector<int>>& lists);  // NOLINT: a list of lists is one
    int count() const { return static_cast<int>(offsets.size()) - 1; }
    int size(int r) const { return offsets[r + 1] - offsets[r]; }
    const int* operator[](int r) const { return vertices.data() + offsets[r]; }
    // Appends a vertex to the last stencil, which close() ends.
    void push(int v) { vertices.push_back(v); }
    void close() { offsets.push_back(static_cast<int>(vertices.size())); }

    std::vector<int> offsets{0};  // stencil r: vertices[offsets[r] .. offsets[r + 1])
    std::vector<int> vertices;
};

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
    // With blockStarts (the first vertex of each block, then the vertex count) it also drops
    // the pairs between blocks, which makes the matrix block diagonal: the blocks are factorised
    // and solved apart (see ScalarSystem).
    struct Lumping {
        const MeshTopology& topology;
        const std::vector<char>& fixed;  // per vertex
        std::vector<int> blockStarts = {};
    };

    StencilPattern(int vertexCount, const Stencils& stencils, const Lumping* lumping = nullptr);

    // Column b holds rows inner()[outer()[b] .. outer()[b+1]), ascending.
    const std::vector<int>& outer() const { return outer_; }
    const std::vector<int>& inner() const { return inner_; }
    int stencilCount() const { return static_cast<int>(size_.size()); }
    int stencilSize(int r) const { return size_[r]; }
    // The index into inner() of the pair (stencil r's a-th vertex, its b-th vertex); for a pair
    // a lumped pattern dropped onto a diagonal, −1 − that diagonal's index.
    int entry(int r, int a, int b) const { return entries_[offset_[r] + a * size_[r] + b]; }
    int diagonal(int v) const { return diagonal_[v]; }
    // The diagonal blocks no entry crosses: the first vertex of each, then the vertex count.
    const std::vector<int>& blockStarts() const { return blockStarts_; }

  private:
    // A lumped pattern's columns: each vertex and its ring, within its block.
    void layOutRings(const MeshTopology& topology);
    // Otherwise: each vertex and every vertex it shares a stencil with. memberOffset and
    // memberStencil: the stencils each vertex is in (CSR).
    void layOutUnion(const Stencils& stencils, const std::vector<int>& memberOffset,
                     const std::vector<int>& memberStencil);

    std::vector<int> outer_, inner_;
    std::vector<int> size_;     // per stencil
    std::vector<long> offset_;  // per stencil, into entries_ (size² each)
    std::vector<int> entries_;
    std::vector<int> diagonal_;  // per vertex
    std::vector<int> blockStarts_;
};

}  // namespace boneless
