#include "ArapEnergy.h"

#include <Eigen/LU>
#include <Eigen/SVD>

namespace boneless {

ArapEnergy::ArapEnergy(const TriMesh& rest) : rest_(&rest) {
    const int n = rest.vertexCount();
    cotangent_.resize(rest.faceCount(), 3);
    std::vector<Eigen::Triplet<double>> t;
    t.reserve(12 * rest.faceCount());
    for (int f = 0; f < rest.faceCount(); ++f)
        for (int c = 0; c < 3; ++c) {
            const int o = rest.F(f, c), j = rest.F(f, (c + 1) % 3), k = rest.F(f, (c + 2) % 3);
            const Vec3 a = rest.V.row(j) - rest.V.row(o), b = rest.V.row(k) - rest.V.row(o);
            const double sine = a.cross(b).norm();
            // A zero-area face has no angles to keep; it contributes nothing.
            const double w = sine > 1e-300 ? 0.5 * a.dot(b) / sine : 0.0;
            cotangent_(f, c) = w;
            t.emplace_back(j, j, w);
            t.emplace_back(k, k, w);
            t.emplace_back(j, k, -w);
            t.emplace_back(k, j, -w);
        }
    laplacian_.resize(n, n);
    laplacian_.setFromTriplets(t.begin(), t.end());
}

void ArapEnergy::fitRotations(const Positions& V, std::vector<Mat3>& R) const {
    const TriMesh& rest = *rest_;
    const int n = rest.vertexCount();
    std::vector<Mat3> S(n, Mat3::Zero());
    for (int f = 0; f < rest.faceCount(); ++f) {
        Mat3 cov = Mat3::Zero();
        for (int c = 0; c < 3; ++c) {
            const int j = rest.F(f, (c + 1) % 3), k = rest.F(f, (c + 2) % 3);
            const Vec3 e0 = rest.V.row(j) - rest.V.row(k);
            const Vec3 e = V.row(j) - V.row(k);
            cov += cotangent_(f, c) * e0 * e.transpose();
        }
        for (int c = 0; c < 3; ++c) S[rest.F(f, c)] += cov;
    }
    R.resize(n);
    for (int v = 0; v < n; ++v) {
        Eigen::JacobiSVD<Mat3> svd(S[v], Eigen::ComputeFullU | Eigen::ComputeFullV);
        Mat3 U = svd.matrixU();
        R[v] = svd.matrixV() * U.transpose();
        if (R[v].determinant() < 0) {
            U.col(2) *= -1;  // the smallest singular value's direction takes the reflection
            R[v] = svd.matrixV() * U.transpose();
        }
    }
}

double ArapEnergy::energy(const Positions& V, const std::vector<Mat3>& R) const {
    const TriMesh& rest = *rest_;
    double e = 0;
    for (int f = 0; f < rest.faceCount(); ++f)
        for (int c = 0; c < 3; ++c) {
            const int j = rest.F(f, (c + 1) % 3), k = rest.F(f, (c + 2) % 3);
            const Vec3 e0 = rest.V.row(j) - rest.V.row(k);
            const Vec3 d = V.row(j) - V.row(k);
            for (int i = 0; i < 3; ++i)
                e += cotangent_(f, c) * (d - R[rest.F(f, i)] * e0).squaredNorm();
        }
    return e;
}

Eigen::MatrixXd ArapEnergy::rotatedRestEdges(const std::vector<Mat3>& R) const {
    const TriMesh& rest = *rest_;
    Eigen::MatrixXd b = Eigen::MatrixXd::Zero(rest.vertexCount(), 3);
    for (int f = 0; f < rest.faceCount(); ++f) {
        const Mat3 Rsum = R[rest.F(f, 0)] + R[rest.F(f, 1)] + R[rest.F(f, 2)];
        for (int c = 0; c < 3; ++c) {
            const int j = rest.F(f, (c + 1) % 3), k = rest.F(f, (c + 2) % 3);
            const Vec3 e0 = rest.V.row(j) - rest.V.row(k);
            const Vec3 rotated = cotangent_(f, c) * (Rsum * e0);
            b.row(j) += rotated.transpose();
            b.row(k) -= rotated.transpose();
        }
    }
    return b;
}

}  // namespace boneless
