// The rest pose's Gauss–Newton system: the iterative path's preconditioner is made from it.

#include "ReconstructionImpl.h"
#include "boneless/Error.h"

namespace boneless {

void Reconstruction::Impl::prepareRestSystem(bool factor) {
    const int K = static_cast<int>(markers.size());
    Positions restMarkers(K, 3);
    for (int k = 0; k < K; ++k) restMarkers.row(k) = rest.V.row(markers[k]);
    Eigen::VectorXd gradient;
    auto build = [&] {
        linearise(rest.V, restMarkers);
        assemble(rest.V, restMarkers, gradient);
        if (rigid()) addRotationCoupling();
        for (int v = 0; v < rest.vertexCount(); ++v)
            if (topology->isIsolated(v)) system->pin(v);
        if (!softMarkers())
            for (int v : markers) system->pin(v);
    };
    build();
    const double term = tikhonov();
    if (!factor) {
        system->addToDiagonal(term);
    } else if (!system->factorize(term)) {
        build();
        if (!system->factorize(term * 1e4))
            throw SolverError("the rest pose's Gauss–Newton matrix is not positive definite");
    }
    systemHoldsRestFactor = true;
}

}  // namespace boneless
