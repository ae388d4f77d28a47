#include "MarkerPatch.h"

#include <Eigen/SVD>
#include <algorithm>
#include <limits>

#include "Rotation.h"

namespace boneless {

namespace {

// The corners of a point and their barycentric weights.
void corners(const TriMesh& mesh, const SurfacePoint& p, int out[3], double weight[3], int& count) {
    if (p.face < 0) {
        out[0] = p.vertex;
        weight[0] = 1.0;
        count = 1;
        return;
    }
    count = 3;
    for (int c = 0; c < 3; ++c) {
        out[c] = mesh.F(p.face, c);
        weight[c] = p.barycentric[c];
    }
}

}  // namespace

Vec3 MarkerPatch::centroid(const Positions& V) const {
    Vec3 c = Vec3::Zero();
    for (size_t j = 0; j < vertices.size(); ++j) c += weights[j] * V.row(vertices[j]).transpose();
    return c;
}

Mat3 MarkerPatch::rotation(const Positions& rest, const Positions& V, const Mat3& fallback) const {
    if (!fittable) return fallback;
    const Vec3 c = centroid(V);
    Mat3 S = Mat3::Zero();
    for (size_t j = 0; j < vertices.size(); ++j)
        S += weights[j] * (rest.row(vertices[j]).transpose() - restCentroid) *
             (V.row(vertices[j]).transpose() - c).transpose();
    return bestRotation(S);
}

Vec3 surfacePosition(const Faces& F, const Positions& V, const SurfacePoint& p) {
    if (p.face < 0) return V.row(p.vertex).transpose();
    Vec3 x = Vec3::Zero();
    for (int c = 0; c < 3; ++c) x += p.barycentric[c] * V.row(F(p.face, c)).transpose();
    return x;
}

Vec3 surfacePosition(const TriMesh& mesh, const Positions& V, const SurfacePoint& p) {
    return surfacePosition(mesh.F, V, p);
}

SurfacePoint surfacePointAt(const Faces& F, const Positions& V, int face, const Vec3& x) {
    const Vec3 a = V.row(F(face, 0)).transpose(), b = V.row(F(face, 1)).transpose(),
               c = V.row(F(face, 2)).transpose();
    // Least squares in the triangle's plane (x off the plane projects onto it), then clamped
    // onto the triangle: the nearest point when x lies over it, as a pick's hit does.
    const Vec3 e1 = b - a, e2 = c - a, d = x - a;
    const double d11 = e1.dot(e1), d12 = e1.dot(e2), d22 = e2.dot(e2);
    const double det = d11 * d22 - d12 * d12;
    Vec3 w(1, 0, 0);
    if (det > 0) {
        const double u = (d22 * e1.dot(d) - d12 * e2.dot(d)) / det;
        const double v = (d11 * e2.dot(d) - d12 * e1.dot(d)) / det;
        w = Vec3(1 - u - v, u, v).cwiseMax(0.0);
        w /= w.sum();
    }
    SurfacePoint p;
    p.face = face;
    p.barycentric = w;
    double nearest = std::numeric_limits<double>::infinity();
    for (int k = 0; k < 3; ++k)
        if (const double dk = (V.row(F(face, k)).transpose() - x).squaredNorm(); dk < nearest)
            nearest = dk, p.vertex = F(face, k);
    return p;
}

Vec3 surfaceNormal(const TriMesh& mesh, const ShapeEncoding& encoding, const SurfacePoint& p) {
    int c[3], count;
    double w[3];
    corners(mesh, p, c, w, count);
    Vec3 n = Vec3::Zero();
    for (int i = 0; i < count; ++i)
        if (encoding.encoded(c[i])) n += w[i] * encoding.ringNormal(c[i], mesh.V);
    const double length = n.norm();
    return length > 0 ? Vec3(n / length) : Vec3::Zero();
}

std::vector<int> surfaceDisk(const TriMesh& mesh, const MeshTopology& topology,
                             const SurfacePoint& p, double radius) {
    int c[3], count;
    double w[3];
    corners(mesh, p, c, w, count);
    const Vec3 centre = surfacePosition(mesh, mesh.V, p);
    std::vector<int> disk(c, c + count);
    std::sort(disk.begin(), disk.end());
    disk.erase(std::unique(disk.begin(), disk.end()), disk.end());
    std::vector<int> queue = disk;
    for (size_t q = 0; q < queue.size(); ++q) {
        const int v = queue[q];
        for (int k = 0; k < topology.valence(v); ++k) {
            const int u = topology.ring(v)[k];
            if ((mesh.V.row(u).transpose() - centre).norm() >= radius) continue;
            const auto at = std::lower_bound(disk.begin(), disk.end(), u);
            if (at != disk.end() && *at == u) continue;
            disk.insert(at, u);
            queue.push_back(u);
        }
    }
    return disk;
}

MarkerPatch makeMarkerPatch(const TriMesh& rest, const ShapeEncoding& encoding,
                            const SurfacePoint& p) {
    MarkerPatch patch;
    patch.vertex = p.vertex;
    const Vec3 centre = surfacePosition(rest, rest.V, p);
    int c[3], count;
    double w[3];
    corners(rest, p, c, w, count);
    for (int i = 0; i < count; ++i)
        if (w[i] > 0) {
            patch.vertices.push_back(c[i]);
            patch.weights.push_back(w[i]);
        }
    double total = 0;
    for (double w : patch.weights) total += w;
    for (double& w : patch.weights) w /= total;
    patch.restCentroid = patch.centroid(rest.V);
    patch.sag = centre - patch.restCentroid;
    patch.restNormal = surfaceNormal(rest, encoding, p);
    // A rotation needs the corners to span a plane: its weighted spread's second singular value.
    if (patch.vertices.size() >= 3) {
        Mat3 C = Mat3::Zero();
        for (size_t j = 0; j < patch.vertices.size(); ++j) {
            const Vec3 a = rest.V.row(patch.vertices[j]).transpose() - patch.restCentroid;
            C += patch.weights[j] * a * a.transpose();
        }
        const Vec3 s = Eigen::JacobiSVD<Mat3>(C).singularValues();
        patch.fittable = s[1] > 1e-6 * s[0] && s[0] > 0;
    }
    return patch;
}

std::vector<MarkerPatch> vertexPatches(const TriMesh& rest, const ShapeEncoding& encoding,
                                       const std::vector<int>& vertices) {
    std::vector<MarkerPatch> patches;
    for (int v : vertices) {
        SurfacePoint p;
        p.vertex = v;
        patches.push_back(makeMarkerPatch(rest, encoding, p));
    }
    return patches;
}

}  // namespace boneless
