#include "CarriedParts.h"

#include <algorithm>
#include <limits>
#include <numeric>
#include <queue>
#include <utility>

#include "boneless/Reconstruction.h"
#include "boneless/RigidFit.h"

namespace boneless {

namespace {

int findRoot(std::vector<int>& parent, int v) {
    while (parent[v] != v) v = parent[v] = parent[parent[v]];
    return v;
}

// The `count` vertices among `candidates` nearest to the point set `part` (distance to its
// nearest point), nearest first. Candidates are taken by a lower bound of their distance (to the
// part's bounding sphere), and the part is scanned in runs of vertices with bounding spheres of
// their own, so that tights over a body's legs cost a fraction of every pair.
std::vector<int> nearestTo(const Positions& V, const std::vector<int>& part,
                           const std::vector<int>& candidates, int count) {
    constexpr size_t kRun = 16;  // file order keeps a run's vertices close together
    struct Run {
        Vec3 centre = Vec3::Zero();
        double radius = 0;
        std::vector<Vec3> points;
    };
    std::vector<Run> runs;
    for (size_t i = 0; i < part.size(); i += kRun) {
        Run run;
        for (size_t j = i; j < std::min(part.size(), i + kRun); ++j)
            run.points.push_back(V.row(part[j]).transpose());
        for (const Vec3& x : run.points) run.centre += x;
        run.centre /= static_cast<double>(run.points.size());
        for (const Vec3& x : run.points) run.radius = std::max(run.radius, (x - run.centre).norm());
        runs.push_back(std::move(run));
    }
    Vec3 centre = Vec3::Zero();
    for (int v : part) centre += V.row(v).transpose();
    centre /= static_cast<double>(part.size());
    double radius = 0;
    for (int v : part) radius = std::max(radius, (V.row(v).transpose() - centre).norm());
    std::vector<std::pair<double, int>> bound;  // (lower bound of the distance, vertex)
    bound.reserve(candidates.size());
    for (int u : candidates)
        bound.emplace_back(std::max(0.0, (V.row(u).transpose() - centre).norm() - radius), u);
    std::sort(bound.begin(), bound.end());
    std::priority_queue<std::pair<double, int>> best;  // the nearest so far, farthest on top
    for (const auto& [lower, u] : bound) {
        const bool full = static_cast<int>(best.size()) == count;
        if (full && lower > best.top().first) break;
        const Vec3 x = V.row(u).transpose();
        // Only a distance below the farthest kept matters.
        double d = full ? best.top().first : std::numeric_limits<double>::infinity();
        bool nearer = false;
        for (const Run& run : runs) {
            if ((x - run.centre).norm() - run.radius >= d) continue;
            for (const Vec3& y : run.points)
                if (const double e = (x - y).norm(); e < d) {
                    d = e;
                    nearer = true;
                }
        }
        if (!nearer) continue;
        best.emplace(d, u);
        if (static_cast<int>(best.size()) > count) best.pop();
    }
    std::vector<int> nearest(best.size());
    for (auto i = nearest.size(); i-- > 0; best.pop()) nearest[i] = best.top().second;
    return nearest;
}

}  // namespace

int connectedComponents(const TriMesh& mesh, std::vector<int>& componentOf) {
    const int n = mesh.vertexCount();
    std::vector<int> parent(n);
    std::iota(parent.begin(), parent.end(), 0);
    std::vector<char> used(n, 0);
    for (int f = 0; f < mesh.faceCount(); ++f)
        for (int c = 0; c < 3; ++c) {
            used[mesh.F(f, c)] = 1;
            const int a = findRoot(parent, mesh.F(f, c)),
                      b = findRoot(parent, mesh.F(f, (c + 1) % 3));
            if (a != b) parent[std::max(a, b)] = std::min(a, b);
        }
    componentOf.assign(n, -1);
    std::vector<int> numberOf(n, -1);
    int count = 0;
    for (int v = 0; v < n; ++v) {
        if (!used[v]) continue;
        int& number = numberOf[findRoot(parent, v)];
        if (number < 0) number = count++;
        componentOf[v] = number;
    }
    return count;
}

namespace {

// Per component of `componentOf` (count of them), whether it holds one of the marker vertices.
std::vector<char> markedComponents(const std::vector<int>& componentOf, int count,
                                   const std::vector<int>& markerVertices) {
    std::vector<char> marked(count, 0);
    const int n = static_cast<int>(componentOf.size());
    for (int v : markerVertices)
        if (v >= 0 && v < n && componentOf[v] >= 0) marked[componentOf[v]] = 1;
    return marked;
}

}  // namespace

int componentsWithoutMarkers(const TriMesh& mesh, const std::vector<int>& markerVertices) {
    std::vector<int> componentOf;
    const int count = connectedComponents(mesh, componentOf);
    const std::vector<char> marked = markedComponents(componentOf, count, markerVertices);
    const int unmarked = static_cast<int>(std::count(marked.begin(), marked.end(), 0));
    return unmarked == count ? 0 : unmarked;
}

CarriedParts::CarriedParts(const TriMesh& rest, const std::vector<int>& markerVertices)
    : rest_(rest.V) {
    const int n = rest.vertexCount();
    std::vector<int> componentOf;
    const int count = connectedComponents(rest, componentOf);
    const std::vector<char> marked = markedComponents(componentOf, count, markerVertices);
    const int unmarked = static_cast<int>(std::count(marked.begin(), marked.end(), 0));
    if (unmarked == 0 || unmarked == count) return;

    // Isolated vertices stay with the solved mesh, which moves them with the markers.
    solvedOf_.assign(n, -1);
    std::vector<int> partOf(count, -1);
    for (int v = 0; v < n; ++v) {
        const int c = componentOf[v];
        if (c < 0 || marked[c]) {
            solvedOf_[v] = static_cast<int>(vertexOf_.size());
            vertexOf_.push_back(v);
            continue;
        }
        if (partOf[c] < 0) {
            partOf[c] = static_cast<int>(parts_.size());
            parts_.emplace_back();
        }
        parts_[partOf[c]].vertices.push_back(v);
    }
    solved_.V.resize(static_cast<int>(vertexOf_.size()), 3);
    for (int s = 0; s < solved_.V.rows(); ++s) solved_.V.row(s) = rest.V.row(vertexOf_[s]);
    solvedFaceOf_.assign(rest.faceCount(), -1);
    std::vector<int> faces;
    for (int f = 0; f < rest.faceCount(); ++f)
        if (solvedOf_[rest.F(f, 0)] >= 0) {
            solvedFaceOf_[f] = static_cast<int>(faces.size());
            faces.push_back(f);
        }
    solved_.F.resize(static_cast<int>(faces.size()), 3);
    for (int s = 0; s < solved_.F.rows(); ++s)
        for (int c = 0; c < 3; ++c) solved_.F(s, c) = solvedOf_[rest.F(faces[s], c)];

    std::vector<int> candidates;  // solved vertices with a face: what can carry a part
    for (int v = 0; v < n; ++v)
        if (componentOf[v] >= 0 && marked[componentOf[v]]) candidates.push_back(v);
    for (Part& part : parts_) {
        const int k = std::min<int>(static_cast<int>(candidates.size()),
                                    std::max<int>(kMinAnchors, part.vertices.size()));
        const std::vector<int> nearest = nearestTo(rest.V, part.vertices, candidates, k);
        part.anchorRest.resize(static_cast<int>(nearest.size()), 3);
        for (size_t a = 0; a < nearest.size(); ++a) {
            part.anchors.push_back(solvedOf_[nearest[a]]);
            part.anchorRest.row(static_cast<int>(a)) = rest.V.row(nearest[a]);
        }
    }
}

Positions CarriedParts::solvedRows(const Positions& V) const {
    Positions S(static_cast<int>(vertexOf_.size()), 3);
    for (int s = 0; s < S.rows(); ++s) S.row(s) = V.row(vertexOf_[s]);
    return S;
}

Positions CarriedParts::whole(const Positions& solved) const {
    Positions V(rest_.rows(), 3);
    for (int s = 0; s < solved.rows(); ++s) V.row(vertexOf_[s]) = solved.row(s);
    Positions posed;
    for (const Part& part : parts_) {
        posed.resize(static_cast<int>(part.anchors.size()), 3);
        for (int a = 0; a < posed.rows(); ++a) posed.row(a) = solved.row(part.anchors[a]);
        const RigidMotion motion = fitRigidMotion(part.anchorRest, posed);
        for (int v : part.vertices) V.row(v) = motion.apply(rest_.row(v).transpose()).transpose();
    }
    return V;
}

}  // namespace boneless
