#pragma once

#include <Eigen/Core>

#include "boneless/TriMesh.h"

namespace boneless {

// Armijo backtracking along `step` (3·#V, xyz per vertex) from V, whose energy is E and whose
// directional derivative along the step is slope (< 0). Halves the step until the energy drops by
// at least 1e-4·α·slope, at most 12 times, so that an iteration never raises the energy. On success
// `trial` holds the accepted pose and `accepted` its energy; `energyOf(trial)` is evaluated once
// per try (the iterative path linearises there too, so the winner's linearisation comes for free).
// acceptedAlpha, when given, receives the accepted fraction of the step.
template <class EnergyOf>
bool armijoBacktrack(const Positions& V, const Eigen::VectorXd& step, double E, double slope,
                     EnergyOf&& energyOf, Positions& trial, double& accepted,
                     double* acceptedAlpha = nullptr) {
    const int n = static_cast<int>(V.rows());
    trial.resize(n, 3);
    double alpha = 1.0;
    for (int tries = 0; tries < 12; ++tries, alpha *= 0.5) {
        for (int v = 0; v < n; ++v)
            trial.row(v) = V.row(v) + alpha * step.segment<3>(3 * v).transpose();
        const double e = energyOf(trial);
        if (e <= E + 1e-4 * alpha * slope) {
            accepted = e;
            if (acceptedAlpha) *acceptedAlpha = alpha;
            return true;
        }
    }
    return false;
}

}  // namespace boneless
