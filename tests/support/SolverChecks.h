#pragma once

// Invariant checks shared by the solver methods' tests.
#include <gtest/gtest.h>

#include <random>

#include "TestMeshes.h"
#include "boneless/Reconstruction.h"

namespace boneless::testing {

// Three random rigid motions of the markers; for each, the prepared solver must give back the
// rest mesh moved the same way when solved cold, when started from that pose turned a further
// `degreesAway` (a jump in the timeline), and when warm-started from its own answer.
inline void expectRigidMotionsRecovered(Reconstruction& solver, const TriMesh& mesh,
                                        const std::vector<int>& markers, std::mt19937& rng,
                                        double degreesAway) {
    const double tolerance = 1e-6 * boundingBoxDiagonal(mesh.V);
    const Eigen::Matrix3d away =
        Eigen::AngleAxisd(degreesAway * M_PI / 180, Eigen::Vector3d(1, 2, 3).normalized()).matrix();
    for (int trial = 0; trial < 3; ++trial) {
        const Eigen::Matrix3d R = randomRotation(rng);
        const Eigen::Vector3d t(trial, 1.0, -0.5);
        const Positions expected = moved(mesh.V, R, t);
        const Positions targets = rows(expected, markers);
        const SolveResult cold = solver.solve(targets);
        EXPECT_LE(maxDistance(cold.V, expected), tolerance) << "cold, trial " << trial;
        const Positions previous = moved(mesh.V, away * R, t);
        const SolveResult jump = solver.solve(targets, &previous);
        EXPECT_LE(maxDistance(jump.V, expected), tolerance) << "jump, trial " << trial;
        const SolveResult warm = solver.solve(targets, &jump.V);
        EXPECT_LE(maxDistance(warm.V, expected), tolerance) << "warm, trial " << trial;
    }
}

}  // namespace boneless::testing
