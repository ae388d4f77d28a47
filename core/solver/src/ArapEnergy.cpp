#include "ArapEnergy.h"

#include <algorithm>
#include <cmath>

#include "Rotation.h"
#include "boneless/Parallel.h"

namespace boneless {

ArapEnergy::ArapEnergy(const TriMesh& rest) : rest_(&rest) {
    const int n = rest.vertexCount();
    cotangent_.resize(rest.faceCount(), 3);
    restEdge_.resize(3 * static_cast<size_t>(rest.faceCount()));
    cornerOffsets_.assign(n + 1, 0);
    const double diagonal = boundingBoxDiagonal(rest.V, rest.F);
    for (int f = 0; f < rest.faceCount(); ++f) {
        // A zero-area face has no angles to keep; it contributes nothing. Its cotangents, rounding
        // noise over a rounding-noise sine, would otherwise reach ±1e15 and swamp the others.
        const bool flat = zeroArea(rest.V.row(rest.F(f, 0)), rest.V.row(rest.F(f, 1)),
                                   rest.V.row(rest.F(f, 2)), diagonal);
        for (int c = 0; c < 3; ++c) {
            ++cornerOffsets_[rest.F(f, c) + 1];
            const int o = rest.F(f, c), j = rest.F(f, (c + 1) % 3), k = rest.F(f, (c + 2) % 3);
            const Vec3 a = rest.V.row(j) - rest.V.row(o), b = rest.V.row(k) - rest.V.row(o);
            cotangent_(f, c) = flat ? 0.0 : 0.5 * a.dot(b) / a.cross(b).norm();
            restEdge_[3 * f + c] = rest.V.row(j) - rest.V.row(k);
        }
    }
    cornerRest_.resize(restEdge_.size());
    for (int f = 0; f < rest.faceCount(); ++f)
        for (int c = 0; c < 3; ++c) {
            const int first = (c + 2) % 3, second = (c + 1) % 3;
            cornerRest_[3 * f + c] = cotangent_(f, first) * restEdge_[3 * f + first] -
                                     cotangent_(f, second) * restEdge_[3 * f + second];
        }
    for (int v = 0; v < n; ++v) cornerOffsets_[v + 1] += cornerOffsets_[v];
    corners_.resize(cornerOffsets_[n]);
    std::vector<int> fill(cornerOffsets_.begin(), cornerOffsets_.end() - 1);
    for (int f = 0; f < rest.faceCount(); ++f)
        for (int c = 0; c < 3; ++c) corners_[fill[rest.F(f, c)]++] = 3 * f + c;
    buildLaplacian();
}

void ArapEnergy::buildLaplacian() {
    const TriMesh& rest = *rest_;
    const int n = rest.vertexCount();
    // Laid out from the corners rather than from a list of triplets: that list and its sorting
    // were 40 MB for a 100K-face mesh, a fifth of the memory its preparation first touched.
    // Column v holds v and every vertex it shares a face with (nothing when it is in no face),
    // each entry summed in the order setFromTriplets summed it (face by face, corner by corner,
    // the four terms of a corner in turn), so that it is the same to the last bit.
    auto column = [&](int v, std::vector<std::pair<int, double>>& entries) {
        entries.clear();
        auto add = [&](int row, double x) {
            for (auto& [r, value] : entries)
                if (r == row) {
                    value += x;
                    return;
                }
            entries.emplace_back(row, x);
        };
        int lastFace = -1;
        for (int i = cornerOffsets_[v]; i < cornerOffsets_[v + 1]; ++i) {
            const int f = corners_[i] / 3;
            if (f == lastFace) continue;  // v is at two corners of a degenerate face
            lastFace = f;
            for (int c = 0; c < 3; ++c) {
                const int j = rest.F(f, (c + 1) % 3), k = rest.F(f, (c + 2) % 3);
                const double w = cotangent_(f, c);
                if (j == v) add(v, w);   // (j, j, w)
                if (k == v) add(v, w);   // (k, k, w)
                if (k == v) add(j, -w);  // (j, k, −w)
                if (j == v) add(k, -w);  // (k, j, −w)
            }
        }
        std::sort(entries.begin(), entries.end());
    };
    // Each column is made once, into room for its most entries (v and two per corner), then
    // packed.
    std::vector<int> room(n + 1, 0), outer(n + 1, 0);
    for (int v = 0; v < n; ++v)
        room[v + 1] = room[v] + 1 + 2 * (cornerOffsets_[v + 1] - cornerOffsets_[v]);
    std::vector<std::pair<int, double>> made(room[n]);
    parallelFor(n, [&](int begin, int end, int) {
        std::vector<std::pair<int, double>> entries;
        for (int v = begin; v < end; ++v) {
            column(v, entries);
            std::copy(entries.begin(), entries.end(), made.begin() + room[v]);
            outer[v + 1] = static_cast<int>(entries.size());
        }
    });
    for (int v = 0; v < n; ++v) outer[v + 1] += outer[v];
    laplacian_.resize(n, n);
    laplacian_.resizeNonZeros(outer[n]);
    std::copy(outer.begin(), outer.end(), laplacian_.outerIndexPtr());
    for (int v = 0; v < n; ++v)
        for (int e = 0; e < outer[v + 1] - outer[v]; ++e) {
            laplacian_.innerIndexPtr()[outer[v] + e] = made[room[v] + e].first;
            laplacian_.valuePtr()[outer[v] + e] = made[room[v] + e].second;
        }
}

void ArapEnergy::fitRotations(const Positions& V, std::vector<Mat3>& R, bool warmStart,
                              std::vector<Mat3>* curvature, double tolerance) const {
    const TriMesh& rest = *rest_;
    const int n = rest.vertexCount();
    // Per calling thread, so that const callers on several threads do not share scratch.
    // (A thread_local is not captured by the lambdas below: they must go through a reference.)
    thread_local std::vector<Mat3> scratch;
    std::vector<Mat3>& faceCovariance = scratch;
    faceCovariance.resize(rest.faceCount());
    parallelFor(rest.faceCount(), [&](int begin, int end, int) {
        for (int f = begin; f < end; ++f) {
            Mat3 cov = Mat3::Zero();
            for (int c = 0; c < 3; ++c) {
                const int j = rest.F(f, (c + 1) % 3), k = rest.F(f, (c + 2) % 3);
                const Vec3 e = V.row(j) - V.row(k);
                cov.noalias() += cotangent_(f, c) * restEdge_[3 * f + c] * e.transpose();
            }
            faceCovariance[f] = cov;
        }
    });
    warmStart = warmStart && static_cast<int>(R.size()) == n;
    R.resize(n);
    if (curvature) curvature->resize(n);
    parallelFor(n, [&](int begin, int end, int) {
        for (int v = begin; v < end; ++v) {
            Mat3 S = Mat3::Zero();
            for (int i = cornerOffsets_[v]; i < cornerOffsets_[v + 1]; ++i)
                S += faceCovariance[corners_[i] / 3];
            if (!warmStart) R[v].setIdentity();
            if (!refineRotation(S, R[v], tolerance)) R[v] = bestRotation(S);
            if (curvature) {
                const Mat3 B = S.transpose() * R[v].transpose();
                const Mat3 H = B.trace() * Mat3::Identity() - 0.5 * (B + B.transpose());
                (*curvature)[v] = positiveDefinite(H) ? Mat3(H.inverse()) : Mat3::Zero();
            }
        }
    });
}

void ArapEnergy::couplingBlocks(int v, const Mat3& Rv,
                                std::vector<std::pair<int, Mat3>>& blocks) const {
    const TriMesh& rest = *rest_;
    blocks.clear();
    for (int i = cornerOffsets_[v]; i < cornerOffsets_[v + 1]; ++i) {
        const int f = corners_[i] / 3;
        for (int c = 0; c < 3; ++c) {
            const Vec3 e = Rv * restEdge_[3 * f + c];
            const double w = cotangent_(f, c);
            Mat3 cross;  // [R_v e⁰]×, so that the block times x_j is (R_v e⁰) × x_j
            cross << 0, -e.z(), e.y(), e.z(), 0, -e.x(), -e.y(), e.x(), 0;
            blocks.emplace_back(rest.F(f, (c + 1) % 3), w * cross);
            blocks.emplace_back(rest.F(f, (c + 2) % 3), -w * cross);
        }
    }
}

void ArapEnergy::vertexEdges(int v, std::vector<std::tuple<int, int, double>>& edges) const {
    const TriMesh& rest = *rest_;
    edges.clear();
    for (int i = cornerOffsets_[v]; i < cornerOffsets_[v + 1]; ++i) {
        const int f = corners_[i] / 3;
        for (int c = 0; c < 3; ++c)
            edges.emplace_back(rest.F(f, (c + 1) % 3), rest.F(f, (c + 2) % 3), cotangent_(f, c));
    }
}

double ArapEnergy::energy(const Positions& V, const std::vector<Mat3>& R) const {
    const TriMesh& rest = *rest_;
    std::vector<double> partial(solverThreadCount(), 0.0);
    parallelFor(rest.faceCount(), [&](int begin, int end, int t) {
        double e = 0;
        for (int f = begin; f < end; ++f)
            for (int c = 0; c < 3; ++c) {
                const int j = rest.F(f, (c + 1) % 3), k = rest.F(f, (c + 2) % 3);
                const Vec3& e0 = restEdge_[3 * f + c];
                const Vec3 d = V.row(j) - V.row(k);
                for (int i = 0; i < 3; ++i)
                    e += cotangent_(f, c) * (d - R[rest.F(f, i)] * e0).squaredNorm();
            }
        partial[t] = e;
    });
    double e = 0;
    for (double x : partial) e += x;
    return e;
}

void ArapEnergy::turnCornerEdges(const std::vector<Mat3>& R, std::vector<Vec3>& cornerEdges) const {
    const TriMesh& rest = *rest_;
    cornerEdges.resize(3 * rest.faceCount());
    parallelFor(rest.faceCount(), [&](int begin, int end, int) {
        for (int f = begin; f < end; ++f) {
            const Mat3 sum = R[rest.F(f, 0)] + R[rest.F(f, 1)] + R[rest.F(f, 2)];
            for (int c = 0; c < 3; ++c) cornerEdges[3 * f + c] = sum * cornerRest_[3 * f + c];
        }
    });
}

Eigen::MatrixXd ArapEnergy::rotatedRestEdges(const std::vector<Mat3>& R) const {
    std::vector<Vec3> cornerEdges;
    turnCornerEdges(R, cornerEdges);
    Eigen::MatrixXd b(rest_->vertexCount(), 3);
    // Gathered per vertex: corner c of face f touches the edges opposite corners c+1 (where the
    // vertex is the edge's second end) and c+2 (its first end).
    parallelFor(rest_->vertexCount(), [&](int begin, int end, int) {
        for (int v = begin; v < end; ++v) b.row(v) = rotatedRestEdges(v, cornerEdges).transpose();
    });
    return b;
}

}  // namespace boneless
