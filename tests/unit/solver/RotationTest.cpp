// The local step's rotation fit: Newton on rotations (refineRotation) against the SVD's answer.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <random>

#include "Rotation.h"

namespace boneless::testing {
namespace {

Mat3 randomRotation(std::mt19937& rng) {
    std::normal_distribution<double> n;
    return Eigen::Quaterniond(n(rng), n(rng), n(rng), n(rng)).normalized().toRotationMatrix();
}

// tr(R M Qᵀ) with M symmetric positive semi-definite is largest at R = Q: S = M Qᵀ has Q as its
// answer whatever M is, and a flat one-ring's S is nearly rank 2.
Mat3 covariance(const Mat3& Q, const Vec3& spread, const Mat3& axes) {
    return axes * spread.asDiagonal() * axes.transpose() * Q.transpose();
}

bool isRotation(const Mat3& R) {
    return (R.transpose() * R - Mat3::Identity()).norm() < 1e-9 && R.determinant() > 0;
}

TEST(RotationFit, NewtonFromANearbyRotationReachesTheBestRotation) {
    std::mt19937 rng(7);
    for (int i = 0; i < 200; ++i) {
        const Mat3 Q = randomRotation(rng);
        const Mat3 S = covariance(Q, Vec3(3.0, 2.0, 1.0), randomRotation(rng));
        const Vec3 axis = Vec3::Random().normalized();
        Mat3 R = Eigen::AngleAxisd(0.3, axis).toRotationMatrix() * Q;
        ASSERT_TRUE(refineRotation(S, R, 1e-10)) << "case " << i;
        EXPECT_TRUE(isRotation(R));
        EXPECT_LT((R - Q).norm(), 1e-8) << "case " << i;
        EXPECT_LT((R - bestRotation(S)).norm(), 1e-8) << "case " << i;
    }
}

TEST(RotationFit, NewtonFromTheIdentityReachesTheBestRotationOfAFlatRing) {
    std::mt19937 rng(11);
    int converged = 0;
    for (int i = 0; i < 200; ++i) {
        const Mat3 Q = randomRotation(rng);
        // A flat ring: no spread along its normal.
        const Mat3 S = covariance(Q, Vec3(2.0, 1.0, 0.0), randomRotation(rng));
        Mat3 R = Mat3::Identity();
        if (!refineRotation(S, R, 1e-10)) continue;  // the caller falls back to the SVD
        ++converged;
        EXPECT_TRUE(isRotation(R));
        EXPECT_LT((R - Q).norm(), 1e-7) << "case " << i;
    }
    // From the identity, up to half a turn away, Newton with its gradient steps mostly gets there.
    EXPECT_GT(converged, 150);
}

TEST(RotationFit, AStepSmallerThanTheToleranceEndsTheFitCloseToTheAnswer) {
    std::mt19937 rng(3);
    const Mat3 Q = randomRotation(rng);
    const Mat3 S = covariance(Q, Vec3(1.0, 1.0, 0.5), randomRotation(rng));
    Mat3 R = Eigen::AngleAxisd(0.2, Vec3::UnitY()).toRotationMatrix() * Q;
    ASSERT_TRUE(refineRotation(S, R, 1e-2));
    // Quadratic convergence: the last step was under 0.01 rad, so what is left is far under it.
    EXPECT_LT(Eigen::AngleAxisd(R * Q.transpose()).angle(), 1e-3);
}

TEST(RotationFit, AZeroCovarianceHasNoAnswer) {
    Mat3 R = Mat3::Identity();
    EXPECT_FALSE(refineRotation(Mat3::Zero(), R));
}

}  // namespace
}  // namespace boneless::testing
