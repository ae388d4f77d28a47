#include "StencilPattern.h"

#include <algorithm>

namespace boneless {

StencilPattern::StencilPattern(int vertexCount, const std::vector<std::vector<int>>& stencils,
                               const Lumping* lumping) {
    const int stencilCount = static_cast<int>(stencils.size());
    size_.resize(stencilCount);
    offset_.assign(stencilCount + 1, 0);
    // Which stencils each vertex is in (and where): a column is the union of those stencils.
    std::vector<int> memberOffset(vertexCount + 1, 0);
    for (int r = 0; r < stencilCount; ++r) {
        const auto& s = stencils[r];
        size_[r] = static_cast<int>(s.size());
        offset_[r + 1] = offset_[r] + static_cast<long>(s.size()) * s.size();
        for (int v : s) ++memberOffset[v + 1];
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
    // Lumped, the columns are known from the rings alone, and all of them are laid out first: a
    // pair with a fixed row lands on that row's diagonal, which may lie in a later column.
    if (lumping) layOutRings(lumping->topology);
    // Otherwise built column by column with a stamp per vertex instead of sorting a list of all
    // pairs: the 3n×3n rest system of a 100K-face mesh spent a third of its assembly time on that.
    if (!lumping) {
        outer_.assign(vertexCount + 1, 0);
        inner_.reserve(static_cast<size_t>(memberOffset.back()) * 4);
        diagonal_.resize(vertexCount);
    }
    entries_.resize(offset_.back());
    std::vector<int> stamp(vertexCount, -1), position(vertexCount, 0);
    for (int b = 0; b < vertexCount; ++b) {
        if (!lumping) {
            const int first = static_cast<int>(inner_.size());
            outer_[b] = first;
            stamp[b] = b;
            inner_.push_back(b);
            for (int at = memberOffset[b]; at < memberOffset[b + 1]; ++at)
                for (int a : stencils[memberStencil[at]])
                    if (stamp[a] != b) {
                        stamp[a] = b;
                        inner_.push_back(a);
                    }
            std::sort(inner_.begin() + first, inner_.end());
        }
        const int end = lumping ? outer_[b + 1] : static_cast<int>(inner_.size());
        for (int i = outer_[b]; i < end; ++i) {
            position[inner_[i]] = i;
            stamp[inner_[i]] = b;
        }
        diagonal_[b] = position[b];
        for (int at = memberOffset[b]; at < memberOffset[b + 1]; ++at) {
            const int r = memberStencil[at], j = memberSlot[at];
            const auto& s = stencils[r];
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
    if (!lumping) outer_[vertexCount] = static_cast<int>(inner_.size());
}

void StencilPattern::layOutRings(const MeshTopology& topology) {
    const int n = topology.vertexCount();
    outer_.assign(n + 1, 0);
    inner_.clear();
    inner_.reserve(topology.neighbours().size() + n);
    diagonal_.resize(n);
    for (int b = 0; b < n; ++b) {
        const int first = static_cast<int>(inner_.size());
        outer_[b] = first;
        inner_.push_back(b);
        inner_.insert(inner_.end(), topology.ring(b), topology.ring(b) + topology.valence(b));
        std::sort(inner_.begin() + first, inner_.end());
        diagonal_[b] = static_cast<int>(std::lower_bound(inner_.begin() + first, inner_.end(), b) -
                                        inner_.begin());
    }
    outer_[n] = static_cast<int>(inner_.size());
}

}  // namespace boneless
