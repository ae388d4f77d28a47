#include "boneless/Sampling.h"

#include <algorithm>
#include <limits>
#include <queue>

namespace boneless {

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

// The vertex with the largest distance, lowest id first among equals.
int farthest(const std::vector<double>& distance) {
    int best = -1;
    for (int v = 0; v < static_cast<int>(distance.size()); ++v)
        if (best < 0 || distance[v] > distance[best]) best = v;
    return best;
}

}  // namespace

std::vector<int> geodesicFarthestPoints(const TriMesh& mesh, int K, int seed) {
    const int n = mesh.vertexCount();
    K = std::min(K, n);
    std::vector<std::vector<std::pair<int, double>>> adjacency(n);
    for (int f = 0; f < mesh.faceCount(); ++f)
        for (int c = 0; c < 3; ++c) {
            const int a = mesh.F(f, c), b = mesh.F(f, (c + 1) % 3);
            const double len = (mesh.V.row(a) - mesh.V.row(b)).norm();
            adjacency[a].push_back({b, len});
            adjacency[b].push_back({a, len});
        }
    std::vector<double> distance(n, kInf);
    std::vector<int> picked;
    using Item = std::pair<double, int>;
    int next = seed;
    while (static_cast<int>(picked.size()) < K) {
        picked.push_back(next);
        // Dijkstra from the new pick only improves distances: the multi-source field is updated
        // incrementally instead of being recomputed.
        std::priority_queue<Item, std::vector<Item>, std::greater<>> queue;
        distance[next] = 0;
        queue.push({0.0, next});
        while (!queue.empty()) {
            auto [d, v] = queue.top();
            queue.pop();
            if (d > distance[v]) continue;
            for (auto [w, len] : adjacency[v])
                if (d + len < distance[w]) {
                    distance[w] = d + len;
                    queue.push({distance[w], w});
                }
        }
        next = farthest(distance);
        if (distance[next] == 0) break;  // every vertex already picked or coincident
    }
    return picked;
}

std::vector<int> euclideanFarthestPoints(const Positions& V, int K, int seed) {
    const int n = static_cast<int>(V.rows());
    K = std::min(K, n);
    std::vector<double> distance(n, kInf);
    std::vector<int> picked;
    int next = seed;
    while (static_cast<int>(picked.size()) < K) {
        picked.push_back(next);
        for (int v = 0; v < n; ++v)
            distance[v] = std::min(distance[v], (V.row(v) - V.row(next)).norm());
        next = farthest(distance);
        if (distance[next] == 0) break;
    }
    return picked;
}

}  // namespace boneless
