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
    std::vector<char> fixed(rest.vertexCount(), 0);
    for (int v = 0; v < rest.vertexCount(); ++v) fixed[v] = topology->isIsolated(v);
    if (!softMarkers())
        for (int v : markers) fixed[v] = 1;
    auto build = [&](auto& target) {
        assembleInto(target, rest.V, restMarkers, gradient);
        if (rigid()) addRotationCouplingTo(target, false);
        for (int v = 0; v < rest.vertexCount(); ++v)
            if (fixed[v]) target.pin(v);
    };
    const char* const indefinite = "the rest pose's Gauss–Newton matrix is not positive definite";
    if (scalarPreconditioner()) {
        // Only the trace of each block is kept: assembled as such, the 3n×3n matrix is never
        // made (it was 630 of the 720 ms a 100K-face input took to prepare). Lumped onto the
        // edges' pairs (LumpedScalar), its factor is a quarter of the full one's, and it is at
        // least the full matrix (see ScalarSystem): positive definite when that is.
        const StencilPattern::Lumping lumping{*topology, fixed};
        const bool lumped = options.preconditioner == SolverOptions::Preconditioner::LumpedScalar;
        restScalar = std::make_unique<ScalarSystem>(rest.vertexCount(), stencils(),
                                                    lumped ? &lumping : nullptr);
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
