// The rest pose's Gauss–Newton system: the iterative path's preconditioner is made from it.

#include <algorithm>

#include "Parallel.h"
#include "ReconstructionImpl.h"
#include "boneless/Error.h"

namespace boneless {

void Reconstruction::Impl::prepareRestSystem() {
    const int K = static_cast<int>(markers.size());
    Positions restMarkers(K, 3);
    for (int k = 0; k < K; ++k) restMarkers.row(k) = rest.V.row(markers[k]);
    linearise(rest.V, restMarkers);
    std::vector<char> fixed(rest.vertexCount(), 0);
    for (int v = 0; v < rest.vertexCount(); ++v) fixed[v] = topology->isIsolated(v);
    if (!softMarkers())
        for (int v : markers) fixed[v] = 1;
    auto pinFixed = [&](auto& target) {
        for (int v = 0; v < rest.vertexCount(); ++v)
            if (fixed[v]) target.pin(v);
    };
    auto build = [&](auto& target) {
        assembleInto(target, rest.V, restMarkers, nullptr);
        if (rigid()) addRotationCouplingTo(target, false);
        pinFixed(target);
    };
    const char* const indefinite = "the rest pose's Gauss–Newton matrix is not positive definite";
    if (scalarPreconditioner()) {
        // Only the trace of each block is kept: assembled as such, the 3n×3n matrix is never
        // made (it was 630 of the 720 ms a 100K-face input took to prepare). Lumped onto the
        // edges' pairs (LumpedScalar), its factor is a quarter of the full one's, and it is at
        // least the full matrix (see ScalarSystem): positive definite when that is.
        StencilPattern::Lumping lumping{*topology, fixed};
        const int n = rest.vertexCount();
        const int blocks = std::clamp(options.lumpedBlocks, 1, std::max(n, 1));
        if (blocks > 1)
            for (int k = 0; k <= blocks; ++k)
                lumping.blockStarts.push_back(static_cast<int>(static_cast<long>(n) * k / blocks));
        const bool lumped = options.preconditioner == SolverOptions::Preconditioner::LumpedScalar;
        restScalar = std::make_unique<ScalarSystem>(rest.vertexCount(), stencils(),
                                                    lumped ? &lumping : nullptr);
        // A large mesh's assembly is split between the cores: the residuals' terms and then the
        // factorisation's analysis (it needs the pattern only) on one, the fold guard's rotation
        // coupling on the other, added after.
        constexpr int splitFrom = 10000;
        if (n >= splitFrom) {
            ScalarSystem::Part coupling(*restScalar);
            runOnWorkers(2, [&](int task) {
                if (task == 1) {
                    if (rigid()) addRotationCouplingTo(coupling, false);
                    return;
                }
                assembleInto(*restScalar, rest.V, restMarkers, nullptr);
                restScalar->analyse();
            });
            restScalar->add(coupling);
            pinFixed(*restScalar);
        } else {
            build(*restScalar);
        }
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
