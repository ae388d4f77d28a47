#include "boneless/MeshTopology.h"

#include <algorithm>
#include <string>

#include "boneless/Error.h"

namespace boneless {

MeshTopology::MeshTopology(const TriMesh& mesh) {
    const int n = mesh.vertexCount();
    // Each face (i, a, b) says: around i, b follows a. Collect those (a -> b) links per vertex.
    std::vector<int> count(n + 1, 0);
    for (int f = 0; f < mesh.faceCount(); ++f)
        for (int c = 0; c < 3; ++c) ++count[mesh.F(f, c) + 1];
    std::vector<int> start(count);
    for (int v = 0; v < n; ++v) start[v + 1] += start[v];
    std::vector<std::pair<int, int>> links(start[n]);
    std::vector<int> fill(start.begin(), start.end() - 1);
    for (int f = 0; f < mesh.faceCount(); ++f)
        for (int c = 0; c < 3; ++c) {
            int i = mesh.F(f, c), a = mesh.F(f, (c + 1) % 3), b = mesh.F(f, (c + 2) % 3);
            links[fill[i]++] = {a, b};
        }

    offsets_.assign(n + 1, 0);
    boundary_.assign(n, 0);
    neighbours_.reserve(links.size() + n);
    for (int v = 0; v < n; ++v) {
        auto first = links.begin() + start[v], last = links.begin() + start[v + 1];
        std::sort(first, last);
        auto next = [&](int a) -> int {
            auto it = std::lower_bound(first, last, std::make_pair(a, -1));
            return (it != last && it->first == a) ? it->second : -1;
        };
        auto hasPredecessor = [&](int a) {
            return std::any_of(first, last, [a](const auto& l) { return l.second == a; });
        };
        const int fanSize = static_cast<int>(last - first);
        if (fanSize > 0) {
            // A boundary ring starts at the neighbour nothing leads to.
            int begin = first->first;
            for (auto it = first; it != last; ++it)
                if (!hasPredecessor(it->first)) {
                    begin = it->first;
                    boundary_[v] = 1;
                    break;
                }
            int cur = begin, steps = 0;
            do {
                neighbours_.push_back(cur);
                cur = next(cur);
                ++steps;
            } while (cur != -1 && cur != begin && steps <= fanSize);
            if (boundary_[v] && cur != -1)
                throw MeshError("<mesh>", "non-manifold vertex", "vertex " + std::to_string(v));
            if (steps != fanSize + (boundary_[v] ? 1 : 0))
                throw MeshError("<mesh>", "non-manifold vertex (its faces form several fans)",
                                "vertex " + std::to_string(v));
        }
        offsets_[v + 1] = static_cast<int>(neighbours_.size());
    }
}

int MeshTopology::boundaryVertexCount() const {
    return static_cast<int>(std::count(boundary_.begin(), boundary_.end(), 1));
}

}  // namespace boneless
