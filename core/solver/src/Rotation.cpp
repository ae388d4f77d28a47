#include "Rotation.h"

#include <Eigen/Geometry>
#include <Eigen/LU>
#include <Eigen/SVD>
#include <cmath>

namespace boneless {

// The rotation R maximising tr(R S), i.e. the transposed orthogonal polar factor of S. Scaled
// Newton iterations (Higham) converge quadratically and cost a 3×3 inverse each, a fraction of a
// 3×3 SVD; a reflection or a near-singular S, which Newton cannot sort out, goes to the SVD.
Mat3 bestRotation(const Mat3& S) {
    const double scale = S.norm();
    const double det = S.determinant();
    if (scale > 0 && det > 1e-6 * scale * scale * scale) {
        Mat3 X = S / scale;
        for (int it = 0; it < 30; ++it) {
            const double d = X.determinant();
            const double gamma = std::pow(std::abs(d), -1.0 / 3.0);
            const Mat3 next = 0.5 * (gamma * X + X.inverse().transpose() / gamma);
            const double change = (next - X).squaredNorm();
            X = next;
            if (change < 1e-20) return X.transpose();
        }
    }
    Eigen::JacobiSVD<Mat3> svd(S, Eigen::ComputeFullU | Eigen::ComputeFullV);
    Mat3 U = svd.matrixU();
    Mat3 R = svd.matrixV() * U.transpose();
    if (R.determinant() < 0) {
        U.col(2) *= -1;  // the smallest singular value's direction takes the reflection
        R = svd.matrixV() * U.transpose();
    }
    return R;
}

bool positiveDefinite(const Mat3& H) {
    return H(0, 0) > 0 && H(0, 0) * H(1, 1) - H(0, 1) * H(1, 0) > 0 && H.determinant() > 0;
}

// Newton's method for the maximiser of tr(R S) over rotations, from R: with R ← exp([δ]) R,
// tr(R S) ≈ f + δ·g − ½ δᵀHδ where g = Σ r_i × a_i (a_i the columns of Sᵀ), B = Sᵀ Rᵀ and
// H = tr(B) I − sym(B). H is positive definite exactly around the maximum (the only local
// maximum), so convergence with H positive definite is the answer. Quadratic convergence, a 3×3
// solve per step: several times cheaper than a 3×3 SVD, and unlike polar-decomposition Newton it
// does not stall on the nearly rank-2 S of a flat one-ring. Returns false when it does not
// converge (the caller then uses the SVD).
bool refineRotation(const Mat3& S, Mat3& R, double tolerance) {
    const Mat3 A = S.transpose();
    const double scale = A.norm();
    if (!(scale > 0)) return false;
    for (int it = 0; it < 30; ++it) {
        Vec3 g = Vec3::Zero();
        for (int i = 0; i < 3; ++i) g += R.col(i).cross(A.col(i));
        const Mat3 B = A * R.transpose();
        const Mat3 H = B.trace() * Mat3::Identity() - 0.5 * (B + B.transpose());
        const bool newton = positiveDefinite(H);
        // Away from the maximum: a gradient step scaled like the Hessian (Müller et al. 2016).
        const Vec3 d =
            newton ? Vec3(H.inverse() * g) : Vec3(g / (std::abs(B.trace()) + 1e-9 * scale));
        const double angle = d.norm();
        if (!std::isfinite(angle)) return false;
        // The Cayley map: a rotation that agrees with exp([d]) to second order, without
        // trigonometry, so Newton still converges quadratically.
        if (angle > 0)
            R = Eigen::Quaterniond(1.0, 0.5 * d.x(), 0.5 * d.y(), 0.5 * d.z())
                    .normalized()
                    .toRotationMatrix() *
                R;
        if (newton && angle < tolerance) return true;
    }
    return false;
}

}  // namespace boneless
