#include "StencilPattern.h"

#include <algorithm>

#include "boneless/Parallel.h"

namespace boneless {

Stencils::Stencils(const std::vector<std::vector<int>>& lists) {
    for (const auto& list : lists) {
        for (int v : list) push(v);
        close();
    }
}

StencilPattern::StencilPattern(int vertexCount, const Stencils& stencils, const Lumping* lumping) {
    const int stencilCount = stencils.count();
    size_.resize(stencilCount);
    offset_.assign(stencilCount + 1, 0);
    // Which stencils each vertex is in (and where): a column is the union of those stencils.
    std::vector<int> memberOffset(vertexCount + 1, 0);
    for (int r = 0; r < stencilCount; ++r) {
        const int m = stencils.size(r);
        size_[r] = m;
        offset_[r + 1] = offset_[r] + static_cast<long>(m) * m;
        for (int j = 0; j < m; ++j) ++memberOffset[stencils[r][j] + 1];
    }
    for (int v = 0; v < vertexCount; ++v) memberOffset[v + 1] += memberOffset[v];
    std::vector<int> memberStencil(memberOffset.back()), memberSlot(memberOffset.back());
    {
        std::vector<int> fill(memberOffset.begin(), memberOffset.end() - 1);
        for (int r = 0; r < stencilCount; ++r)
            for (int j = 0; j < size_[r]; ++j) {
                const int at = fill[stencils[r][j]]++;
                memberStencil[at] = r;
                memberSlot[at] = j;
            }
    }
    // All columns are laid out first: a lumped pair with a fixed row lands on that row's
    // diagonal, which may lie in a later column.
    blockStarts_ = {0, vertexCount};
    if (lumping && !lumping->blockStarts.empty()) blockStarts_ = lumping->blockStarts;
    if (lumping)
        layOutRings(lumping->topology);
    else
        layOutUnion(stencils, memberOffset, memberStencil);
    // Column b's entries are those of the stencils' b-th vertices: columns are independent.
    entries_.resize(offset_.back());
    parallelFor(vertexCount, [&](int begin, int end, int) {
        std::vector<int> stamp(vertexCount, -1), position(vertexCount, 0);
        for (int b = begin; b < end; ++b) {
            for (int i = outer_[b]; i < outer_[b + 1]; ++i) {
                position[inner_[i]] = i;
                stamp[inner_[i]] = b;
            }
            for (int at = memberOffset[b]; at < memberOffset[b + 1]; ++at) {
                const int r = memberStencil[at], j = memberSlot[at];
                const int* s = stencils[r];
                for (int i = 0; i < size_[r]; ++i) {
                    const int a = s[i];
                    int& entry = entries_[offset_[r] + i * size_[r] + j];
                    if (stamp[a] == b)
                        entry = position[a];
                    else if (lumping->fixed[a])
                        entry = diagonal_[a];
                    else
                        entry = -1 - diagonal_[b];
                }
            }
        }
    });
}

void StencilPattern::layOutUnion(const Stencils& stencils, const std::vector<int>& memberOffset,
                                 const std::vector<int>& memberStencil) {
    const int n = static_cast<int>(memberOffset.size()) - 1;
    outer_.assign(n + 1, 0);
    inner_.reserve(static_cast<size_t>(memberOffset.back()) * 4);
    diagonal_.resize(n);
    // A stamp per vertex instead of sorting a list of all pairs: the 3n×3n rest system of a
    // 100K-face mesh spent a third of its assembly time on that.
    std::vector<int> stamp(n, -1);
    for (int b = 0; b < n; ++b) {
        const int first = static_cast<int>(inner_.size());
        outer_[b] = first;
        stamp[b] = b;
        inner_.push_back(b);
        for (int at = memberOffset[b]; at < memberOffset[b + 1]; ++at) {
            const int r = memberStencil[at];
            for (int i = 0; i < stencils.size(r); ++i) {
                const int a = stencils[r][i];
                if (stamp[a] == b) continue;
                stamp[a] = b;
                inner_.push_back(a);
            }
        }
        std::sort(inner_.begin() + first, inner_.end());
        diagonal_[b] = static_cast<int>(std::lower_bound(inner_.begin() + first, inner_.end(), b) -
                                        inner_.begin());
    }
    outer_[n] = static_cast<int>(inner_.size());
}

void StencilPattern::layOutRings(const MeshTopology& topology) {
    const int n = topology.vertexCount();
    outer_.assign(n + 1, 0);
    inner_.clear();
    inner_.reserve(topology.neighbours().size() + n);
    diagonal_.resize(n);
    for (size_t k = 0; k + 1 < blockStarts_.size(); ++k)
        for (int b = blockStarts_[k]; b < blockStarts_[k + 1]; ++b) {
            const int first = static_cast<int>(inner_.size());
            outer_[b] = first;
            inner_.push_back(b);
            for (int i = 0; i < topology.valence(b); ++i) {
                const int u = topology.ring(b)[i];
                if (u >= blockStarts_[k] && u < blockStarts_[k + 1]) inner_.push_back(u);
            }
            std::sort(inner_.begin() + first, inner_.end());
            diagonal_[b] = static_cast<int>(
                std::lower_bound(inner_.begin() + first, inner_.end(), b) - inner_.begin());
        }
    outer_[n] = static_cast<int>(inner_.size());
}

}  // namespace boneless
