// The rest pose's Gauss–Newton system: the iterative path's preconditioner is made from it.

#include "ReconstructionImpl.h"
#include "boneless/Error.h"

namespace boneless {

void Reconstruction::Impl::prepareRestSystem() {
    const int K = static_cast<int>(markers.size());
    Positions restMarkers(K, 3);
    for (int k = 0; k < K; ++k) restMarkers.row(k) = rest.V.row(markers[k]);
    Eigen::VectorXd gradient;
    linearise(rest.V, restMarkers);
    auto build = [&](auto& target) {
        assembleInto(target, rest.V, restMarkers, gradient);
        if (rigid()) addRotationCouplingTo(target, false);
        for (int v = 0; v < rest.vertexCount(); ++v)
            if (topology->isIsolated(v)) target.pin(v);
        if (!softMarkers())
            for (int v : markers) target.pin(v);
    };
    const char* const indefinite = "the rest pose's Gauss–Newton matrix is not positive definite";
    if (options.preconditioner == SolverOptions::Preconditioner::Scalar) {
        // Only the trace of each block is kept: assembled as such, the 3n×3n matrix is never
        // made (it was 630 of the 720 ms a 100K-face input took to prepare).
        restScalar = std::make_unique<ScalarSystem>(rest.vertexCount(), stencils());
        build(*restScalar);
        const double term = 1e-9 * restScalar->meanDiagonal();
        if (!restScalar->factorize(term) && !restScalar->factorize(term * 1e4))
            throw SolverError(indefinite);
    } else {
        restScalar.reset();  // left by a change of options: no longer used
        if (!system) buildBlockSystem();
        system->clear();
        build(*system);
        const double term = tikhonov();
        if (!system->factorize(term)) {
            system->clear();
            build(*system);
            if (!system->factorize(term * 1e4)) throw SolverError(indefinite);
        }
    }
    systemHoldsRestFactor = true;
}

}  // namespace boneless
