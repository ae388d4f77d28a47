#include "boneless/Metrics.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <unordered_map>
#include <vector>

#include "boneless/RigidFit.h"

namespace boneless {

double rmsVertexError(const Positions& V, const Positions& T) {
    return V.rows() ? std::sqrt((V - T).rowwise().squaredNorm().mean()) : 0.0;
}

double maxVertexError(const Positions& V, const Positions& T) {
    return V.rows() ? (V - T).rowwise().norm().maxCoeff() : 0.0;
}

namespace {
Eigen::Vector3d faceNormal(const Faces& F, const Positions& P, int f) {
    const Eigen::Vector3d a = P.row(F(f, 0)), b = P.row(F(f, 1)), c = P.row(F(f, 2));
    return (b - a).cross(c - a);
}
}  // namespace

int flippedFaceCount(const Faces& F, const Positions& V, const Positions& T) {
    int flipped = 0;
    for (int f = 0; f < F.rows(); ++f)
        if (faceNormal(F, V, f).dot(faceNormal(F, T, f)) < 0) ++flipped;
    return flipped;
}

std::vector<Vec3> carriedRestNormals(const Faces& F, const Positions& V, const Positions& rest) {
    std::vector<std::vector<int>> ring(rest.rows());
    for (int f = 0; f < F.rows(); ++f)
        for (int c = 0; c < 3; ++c) ring[F(f, c)].push_back(F(f, (c + 1) % 3));
    std::vector<Mat3> rotation(rest.rows(), Mat3::Identity());
    for (int v = 0; v < rest.rows(); ++v) {
        Positions from(ring[v].size() + 1, 3), to(ring[v].size() + 1, 3);
        from.row(0) = rest.row(v);
        to.row(0) = V.row(v);
        for (std::size_t k = 0; k < ring[v].size(); ++k) {
            from.row(k + 1) = rest.row(ring[v][k]);
            to.row(k + 1) = V.row(ring[v][k]);
        }
        rotation[v] = fitRigidMotion(from, to).R;
    }
    std::vector<Vec3> carried(F.rows());
    for (int f = 0; f < F.rows(); ++f)
        carried[f] =
            (rotation[F(f, 0)] + rotation[F(f, 1)] + rotation[F(f, 2)]) * faceNormal(F, rest, f);
    return carried;
}

std::vector<int> foldedFaces(const Faces& F, const Positions& V, const Positions& rest) {
    const std::vector<Vec3> carried = carriedRestNormals(F, V, rest);
    const double diagonal = boundingBoxDiagonal(rest, F);
    std::vector<int> folded;
    for (int f = 0; f < F.rows(); ++f)
        // A face with no area at rest has no side to turn over: its normal is rounding noise.
        if (!zeroArea(rest.row(F(f, 0)), rest.row(F(f, 1)), rest.row(F(f, 2)), diagonal) &&
            faceNormal(F, V, f).dot(carried[f]) < 0)
            folded.push_back(f);
    return folded;
}

double edgeLengthDistortion(const Faces& F, const Positions& V, const Positions& rest) {
    double sum = 0;
    long count = 0;
    for (int f = 0; f < F.rows(); ++f)
        for (int c = 0; c < 3; ++c) {
            const int a = F(f, c), b = F(f, (c + 1) % 3);
            const double restLength = (rest.row(a) - rest.row(b)).norm();
            if (restLength <= 0) continue;
            const double ratio = (V.row(a) - V.row(b)).norm() / restLength - 1.0;
            sum += ratio * ratio;
            ++count;
        }
    return count ? std::sqrt(sum / count) : 0.0;
}

namespace {
// The signed angle between the normals of faces f and g across their edge a→b (as f walks it).
// Signed, so that a ridge pushed through into a valley counts its whole swing.
double dihedral(const Faces& F, const Positions& P, int f, int g, int a, int b) {
    const Eigen::Vector3d n = faceNormal(F, P, f), m = faceNormal(F, P, g);
    const Eigen::Vector3d e = (P.row(b) - P.row(a)).transpose();
    return std::atan2(n.cross(m).dot(e.normalized()), n.dot(m));
}
}  // namespace

double bentEdgeShare(const Faces& F, const Positions& V, const Positions& rest, double degrees) {
    std::unordered_map<std::uint64_t, int> firstFace;  // undirected edge -> the face seen first
    firstFace.reserve(static_cast<size_t>(F.rows()) * 2);
    const double limit = degrees * M_PI / 180.0;
    long interior = 0, bent = 0;
    for (int f = 0; f < F.rows(); ++f)
        for (int c = 0; c < 3; ++c) {
            const int a = F(f, c), b = F(f, (c + 1) % 3);
            const auto key = (std::uint64_t(std::min(a, b)) << 32) | std::uint32_t(std::max(a, b));
            const auto [it, first] = firstFace.try_emplace(key, f);
            if (first) continue;
            ++interior;
            // The face seen first walks the edge the other way round on an oriented surface.
            const int g = it->second;
            double change = dihedral(F, V, g, f, b, a) - dihedral(F, rest, g, f, b, a);
            change = std::remainder(change, 2 * M_PI);
            bent += std::abs(change) > limit;
        }
    return interior ? static_cast<double>(bent) / static_cast<double>(interior) : 0.0;
}

}  // namespace boneless
