#include "Rotation.h"

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
// tr(R S) ≈ f + δ·g − ½ δᵀHδ where, with B = Sᵀ Rᵀ, [g]× = B − Bᵀ and H = tr(B) I − sym(B).
// H is positive definite exactly around the maximum (the only local maximum), so convergence
// with H positive definite is the answer. Quadratic convergence, a 3×3 solve per step: several
// times cheaper than a 3×3 SVD, and unlike polar-decomposition Newton it does not stall on the
// nearly rank-2 S of a flat one-ring. Returns false when it does not converge (the caller then
// uses the SVD). This runs for every vertex twice an iteration: it is written out by hand.
bool refineRotation(const Mat3& S, Mat3& R, double tolerance) {
    Mat3 B = S.transpose() * R.transpose();
    for (int it = 0; it < 30; ++it) {
        const Vec3 g(B(2, 1) - B(1, 2), B(0, 2) - B(2, 0), B(1, 0) - B(0, 1));
        const double t = B.trace();
        // H, symmetric, and its cofactors: H⁻¹ = C / det, positive definite by leading minors.
        const double h00 = t - B(0, 0), h11 = t - B(1, 1), h22 = t - B(2, 2);
        const double h01 = -0.5 * (B(0, 1) + B(1, 0)), h02 = -0.5 * (B(0, 2) + B(2, 0)),
                     h12 = -0.5 * (B(1, 2) + B(2, 1));
        const double c00 = h11 * h22 - h12 * h12, c01 = h02 * h12 - h01 * h22,
                     c02 = h01 * h12 - h02 * h11, c11 = h00 * h22 - h02 * h02,
                     c12 = h01 * h02 - h00 * h12, c22 = h00 * h11 - h01 * h01;
        const double det = h00 * c00 + h01 * c01 + h02 * c02;
        const bool newton = h00 > 0 && c22 > 0 && det > 0;
        // Away from the maximum: a gradient step scaled like the Hessian (Müller et al. 2016).
        const Vec3 d = newton ? Vec3(Vec3(c00 * g.x() + c01 * g.y() + c02 * g.z(),
                                          c01 * g.x() + c11 * g.y() + c12 * g.z(),
                                          c02 * g.x() + c12 * g.y() + c22 * g.z()) /
                                     det)
                              : Vec3(g / (std::abs(t) + 1e-9 * S.norm()));
        const double angle2 = d.squaredNorm();
        if (!std::isfinite(angle2)) return false;  // S is zero or not finite
        if (angle2 > 0) {
            // The Cayley map (the unit quaternion (1, d/2)): I + 2([w]× + [w]×²) / (1 + |w|²)
            // with w = d/2 agrees with exp([d]) to second order, without trigonometry, so Newton
            // still converges quadratically.
            const Vec3 w = 0.5 * d;
            const double k = 2.0 / (1.0 + 0.25 * angle2);
            Mat3 Q;
            Q << 1 - k * (w.y() * w.y() + w.z() * w.z()), k * (w.x() * w.y() - w.z()),
                k * (w.x() * w.z() + w.y()), k * (w.x() * w.y() + w.z()),
                1 - k * (w.x() * w.x() + w.z() * w.z()), k * (w.y() * w.z() - w.x()),
                k * (w.x() * w.z() - w.y()), k * (w.y() * w.z() + w.x()),
                1 - k * (w.x() * w.x() + w.y() * w.y());
            R = Q * R;
            if (newton && angle2 < tolerance * tolerance) return true;
            B = B * Q.transpose();
        } else if (newton) {
            return true;
        }
    }
    return false;
}

}  // namespace boneless
