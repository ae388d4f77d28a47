#pragma once

// Small meshes made in code, so the solver's tests need no files.
#include <Eigen/Geometry>
#include <cmath>
#include <map>
#include <random>

#include "boneless/TriMesh.h"

namespace boneless::testing {

// Subdivided icosahedron on the unit sphere, outward-oriented.
inline TriMesh icosphere(int subdivisions) {
    const double t = (1.0 + std::sqrt(5.0)) / 2.0;
    std::vector<Eigen::Vector3d> v = {{-1, t, 0}, {1, t, 0}, {-1, -t, 0}, {1, -t, 0},
                                      {0, -1, t}, {0, 1, t}, {0, -1, -t}, {0, 1, -t},
                                      {t, 0, -1}, {t, 0, 1}, {-t, 0, -1}, {-t, 0, 1}};
    std::vector<Eigen::Vector3i> f = {{0, 11, 5}, {0, 5, 1},  {0, 1, 7},   {0, 7, 10}, {0, 10, 11},
                                      {1, 5, 9},  {5, 11, 4}, {11, 10, 2}, {10, 7, 6}, {7, 1, 8},
                                      {3, 9, 4},  {3, 4, 2},  {3, 2, 6},   {3, 6, 8},  {3, 8, 9},
                                      {4, 9, 5},  {2, 4, 11}, {6, 2, 10},  {8, 6, 7},  {9, 8, 1}};
    for (auto& p : v) p.normalize();
    for (int s = 0; s < subdivisions; ++s) {
        std::map<std::pair<int, int>, int> mid;
        auto midpoint = [&](int a, int b) {
            auto key = std::minmax(a, b);
            auto it = mid.find(key);
            if (it != mid.end()) return it->second;
            v.push_back((v[a] + v[b]).normalized());
            return mid[key] = static_cast<int>(v.size()) - 1;
        };
        std::vector<Eigen::Vector3i> g;
        for (auto& tri : f) {
            int a = midpoint(tri[0], tri[1]), b = midpoint(tri[1], tri[2]),
                c = midpoint(tri[2], tri[0]);
            g.push_back({tri[0], a, c});
            g.push_back({tri[1], b, a});
            g.push_back({tri[2], c, b});
            g.push_back({a, b, c});
        }
        f.swap(g);
    }
    TriMesh m;
    m.V.resize(v.size(), 3);
    for (size_t i = 0; i < v.size(); ++i) m.V.row(i) = v[i].transpose();
    m.F.resize(f.size(), 3);
    for (size_t i = 0; i < f.size(); ++i) m.F.row(i) = f[i].transpose();
    return m;
}

// An open tube along z (two boundary loops): rings x segments vertices, radius 1, length `length`.
inline TriMesh tube(int rings, int segments, double length) {
    TriMesh m;
    m.V.resize(rings * segments, 3);
    for (int r = 0; r < rings; ++r)
        for (int s = 0; s < segments; ++s) {
            const double a = 2 * M_PI * s / segments;
            m.V.row(r * segments + s) << std::cos(a), std::sin(a), length * r / (rings - 1);
        }
    m.F.resize(2 * (rings - 1) * segments, 3);
    int f = 0;
    for (int r = 0; r + 1 < rings; ++r)
        for (int s = 0; s < segments; ++s) {
            const int a = r * segments + s, b = r * segments + (s + 1) % segments;
            const int c = a + segments, d = b + segments;
            m.F.row(f++) << a, b, d;
            m.F.row(f++) << a, d, c;
        }
    return m;
}

// tube(10, 12, 9) whose fifth ring sits a hundredth of a ring spacing above the fourth: a band of
// slivers (aspect ratio ~50), like the corners of a mouth.
inline TriMesh tubeWithSlivers() {
    const int segments = 12;
    TriMesh mesh = tube(10, segments, 9.0);
    for (int s = 0; s < segments; ++s)
        mesh.V(5 * segments + s, 2) = mesh.V(4 * segments + s, 2) + 0.01;
    return mesh;
}

// Moves every vertex by a smooth, non-rigid field: a bend plus a twist, so tests see real strain.
inline Positions bent(const Positions& V, double amount) {
    Positions out = V;
    for (int i = 0; i < V.rows(); ++i) {
        const double z = V(i, 2);
        const double angle = amount * z;
        const double x = V(i, 0), y = V(i, 1);
        out(i, 0) = x * std::cos(angle) - y * std::sin(angle) + 0.3 * amount * z * z;
        out(i, 1) = x * std::sin(angle) + y * std::cos(angle);
        out(i, 2) = z + 0.1 * amount * x;
    }
    return out;
}

inline Eigen::Matrix3d randomRotation(std::mt19937& rng) {
    std::normal_distribution<double> g;
    Eigen::Quaterniond q(g(rng), g(rng), g(rng), g(rng));
    return q.normalized().toRotationMatrix();
}

// V turned by R, then moved by t.
inline Positions moved(const Positions& V, const Eigen::Matrix3d& R, const Eigen::Vector3d& t) {
    Positions out(V.rows(), 3);
    for (int v = 0; v < V.rows(); ++v) out.row(v) = (R * V.row(v).transpose() + t).transpose();
    return out;
}

inline std::vector<int> everyNth(int n, int step) {
    std::vector<int> ids;
    for (int v = 0; v < n; v += step) ids.push_back(v);
    return ids;
}

inline double maxDistance(const Positions& a, const Positions& b) {
    return (a - b).rowwise().norm().maxCoeff();
}

inline Positions rows(const Positions& V, const std::vector<int>& ids) {
    Positions out(ids.size(), 3);
    for (size_t k = 0; k < ids.size(); ++k) out.row(k) = V.row(ids[k]);
    return out;
}

}  // namespace boneless::testing
