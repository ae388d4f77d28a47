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
        if (rigid()) addRestRotationCoupling();
        for (int v = 0; v < rest.vertexCount(); ++v)
            if (topology->isIsolated(v)) system->pin(v);
        if (!softMarkers())
            for (int v : markers) system->pin(v);
    };
    build();
    const double tikhonov = 1e-9 * system->meanDiagonal();
    if (!factor) {
        system->addToDiagonal(tikhonov);
    } else if (!system->factorize(tikhonov)) {
        build();
        if (!system->factorize(tikhonov * 1e4))
            throw SolverError("the rest pose's Gauss–Newton matrix is not positive definite");
    }
    systemHoldsRestFactor = true;
}

void Reconstruction::Impl::addRestRotationCoupling() {
    // −2α Σ_v G_vᵀ C_v G_v (ArapEnergy::addRotationCoupling) at the rest pose, placed in the
    // stencil of v's own residual: G_v only touches v and its ring.
    std::vector<std::pair<int, Mat3>> blocks;
    std::vector<Mat3> G;
    Mat3 C;
    const double scale = -2.0 * options.rigidityWeight;
    for (int v = 0; v < rest.vertexCount(); ++v) {
        const int r = residualIndex[v];
        if (r < 0 || !rigidity->restCouplingBlocks(v, blocks, C)) continue;
        const int m = topology->valence(v);
        const int* ring = topology->ring(v);
        G.assign(m + 1, Mat3::Zero());
        bool inside = true;
        for (const auto& [u, block] : blocks) {
            int slot = u == v ? 0 : -1;
            for (int k = 0; k < m && slot < 0; ++k)
                if (ring[k] == u) slot = k + 1;
            if (slot < 0)
                inside = false;
            else
                G[slot] += block;
        }
        if (!inside) continue;  // a face around v that is not in its ring: leave it out
        for (int a = 0; a <= m; ++a)
            for (int b = 0; b <= m; ++b) system->add(r, a, b, scale * G[a].transpose() * C * G[b]);
    }
}

}  // namespace boneless
