#include "boneless/ShapeEncoding.h"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>

namespace boneless {

namespace {

Mat3 cross(const Vec3& a) {
    Mat3 m;
    m << 0, -a.z(), a.y(), a.z(), 0, -a.x(), -a.y(), a.x(), 0;
    return m;
}

// Affine weights of least norm: Σw = 1, Σ w p = x. They exist whenever the projected ring spans the
// plane, and they reproduce linear functions exactly, which is all rest-pose reproduction needs.
void leastNormAffineWeights(const Vec3* p, int m, const Vec3& x, double* w) {
    Eigen::MatrixXd A(4, m);
    for (int k = 0; k < m; ++k) A.col(k) << p[k], 1.0;
    Eigen::Vector4d b;
    b << x, 1.0;
    Eigen::VectorXd sol = A.completeOrthogonalDecomposition().solve(b);
    for (int k = 0; k < m; ++k) w[k] = sol[k];
}

}  // namespace

void meanValueWeights(const Vec3* p, int m, const Vec3& x, const Vec3& n, double* w) {
    std::vector<Vec3> s(m);
    std::vector<double> r(m), tanHalf(m);
    double scale = 0;
    for (int k = 0; k < m; ++k) {
        s[k] = p[k] - x;
        r[k] = s[k].norm();
        scale = std::max(scale, r[k]);
    }
    const double eps = 1e-12 * std::max(scale, 1e-300);
    std::fill(w, w + m, 0.0);
    for (int k = 0; k < m; ++k)
        if (r[k] <= eps) {
            w[k] = 1.0;
            return;
        }
    for (int k = 0; k < m; ++k) {
        const int k1 = (k + 1) % m;
        const double A = s[k].cross(s[k1]).dot(n);
        const double D = s[k].dot(s[k1]);
        const double rr = r[k] * r[k1];
        if (std::abs(A) <= 1e-12 * rr && D < 0) {
            // x lies on edge (k, k1): linear interpolation is the limit of the weights there.
            w[k] = r[k1] / (r[k] + r[k1]);
            w[k1] = r[k] / (r[k] + r[k1]);
            return;
        }
        // tan(α/2) in whichever of its two forms is well conditioned for this angle.
        tanHalf[k] = D >= 0 ? A / (rr + D) : (rr - D) / A;
    }
    double sum = 0;
    for (int k = 0; k < m; ++k) {
        w[k] = (tanHalf[(k + m - 1) % m] + tanHalf[k]) / r[k];
        sum += w[k];
    }
    double magnitude = 0;
    for (int k = 0; k < m; ++k) magnitude += std::abs(w[k]);
    if (!(std::abs(sum) > 1e-8 * magnitude) || !std::isfinite(sum)) {
        leastNormAffineWeights(p, m, x, w);
        return;
    }
    for (int k = 0; k < m; ++k) w[k] /= sum;
}

ShapeEncoding::ShapeEncoding(const TriMesh& rest, const MeshTopology& topology)
    : topology_(&topology),
      kind_(topology.vertexCount(), Kind::Unencoded),
      weights_(topology.neighbours().size(), 0.0),
      height_(topology.vertexCount(), 0.0) {
    // Ring areas are compared with the squared mean edge length: a ring whose normal is this
    // small is a collapsed one, and its normal would be noise.
    double meanEdge2 = 0;
    long edges = 0;
    for (int v = 0; v < topology.vertexCount(); ++v)
        for (int k = 0; k < topology.valence(v); ++k) {
            meanEdge2 += (rest.V.row(topology.ring(v)[k]) - rest.V.row(v)).squaredNorm();
            ++edges;
        }
    meanEdge2 = edges ? meanEdge2 / edges : 1.0;

    std::vector<Vec3> p;
    for (int v = 0; v < topology.vertexCount(); ++v) {
        const int m = topology.valence(v);
        if (m < 3) continue;
        const int* ring = topology.ring(v);
        p.resize(m);
        Vec3 centroid = Vec3::Zero(), N = Vec3::Zero();
        for (int k = 0; k < m; ++k) centroid += rest.V.row(ring[k]).transpose();
        centroid /= m;
        for (int k = 0; k < m; ++k)
            N += rest.V.row(ring[k]).transpose().cross(rest.V.row(ring[(k + 1) % m]).transpose());
        const double area = N.norm();
        if (!(area > 1e-10 * meanEdge2)) continue;
        const Vec3 n = N / area;
        for (int k = 0; k < m; ++k) {
            Vec3 q = rest.V.row(ring[k]).transpose();
            p[k] = q - (q - centroid).dot(n) * n;
        }
        const Vec3 x = rest.V.row(v).transpose();
        const Vec3 xp = x - (x - centroid).dot(n) * n;
        double* w = weights_.data() + topology.offsets()[v];
        meanValueWeights(p.data(), m, xp, n, w);
        if (!std::all_of(w, w + m, [](double a) { return std::isfinite(a); })) continue;
        height_[v] = (x - centroid).dot(n);
        kind_[v] = Kind::Full;
    }
}

int ShapeEncoding::encodedCount() const {
    return static_cast<int>(std::count(kind_.begin(), kind_.end(), Kind::Full));
}

namespace {

// What decoding needs of a ring in pose V: centroid l, mean-value combination q, normal N.
struct RingState {
    Vec3 l = Vec3::Zero(), q = Vec3::Zero(), N = Vec3::Zero();
    double length = 0;  // |N|
    bool healthy = false;
    Vec3 n = Vec3::Zero();
};

RingState ringState(const int* ring, int m, const double* w, const Positions& V) {
    RingState r;
    for (int k = 0; k < m; ++k) {
        const Vec3 pk = V.row(ring[k]).transpose();
        r.l += pk;
        r.q += w[k] * pk;
        r.N += pk.cross(V.row(ring[(k + 1) % m]).transpose());
    }
    r.l /= m;
    r.length = r.N.norm();
    r.healthy = r.length > 1e-300 && std::isfinite(r.length);
    if (r.healthy) r.n = r.N / r.length;
    return r;
}

}  // namespace

Vec3 ShapeEncoding::decode(int v, const Positions& V) const {
    const RingState r = ringState(topology_->ring(v), topology_->valence(v), weights(v), V);
    return r.q + (height_[v] - (r.q - r.l).dot(r.n)) * r.n;
}

bool ShapeEncoding::decodeWithJacobian(int v, const Positions& V, Vec3& F,
                                       std::vector<Mat3>& J) const {
    const int m = topology_->valence(v);
    const int* ring = topology_->ring(v);
    const double* w = weights(v);
    J.resize(m);
    const RingState r = ringState(ring, m, w, V);
    const Vec3 &l = r.l, &q = r.q, &n = r.n;
    const double len = r.length;
    const bool healthy = r.healthy;
    const double s = height_[v] - (q - l).dot(n);
    F = q + s * n;
    const Mat3 nnT = n * n.transpose();
    const Mat3 P = Mat3::Identity() - nnT;
    const Vec3 t = P * (q - l);
    const Mat3 normalPart = healthy ? Mat3((s * P - n * t.transpose()) / len) : Mat3::Zero();
    for (int k = 0; k < m; ++k) {
        J[k] = w[k] * Mat3::Identity() - (w[k] - 1.0 / m) * nnT;
        const Vec3 d =
            V.row(ring[(k + m - 1) % m]).transpose() - V.row(ring[(k + 1) % m]).transpose();
        J[k] += normalPart * cross(d);
    }
    return healthy;
}

Vec3 ShapeEncoding::ringNormal(int v, const Positions& V, std::vector<Mat3>* dn) const {
    const int m = topology_->valence(v);
    const int* ring = topology_->ring(v);
    const RingState r = ringState(ring, m, weights(v), V);
    if (dn) {
        dn->assign(m, Mat3::Zero());
        if (r.healthy) {
            const Mat3 P = Mat3::Identity() - r.n * r.n.transpose();
            for (int k = 0; k < m; ++k) {
                const Vec3 d =
                    V.row(ring[(k + m - 1) % m]).transpose() - V.row(ring[(k + 1) % m]).transpose();
                (*dn)[k] = P * cross(d) / r.length;
            }
        }
    }
    return r.n;
}

}  // namespace boneless
