#include "RingFit.h"

#include "Rotation.h"
#include "boneless/Parallel.h"

namespace boneless {

RingFit::RingFit(const TriMesh& rest, const MeshTopology& topology) : topology_(topology) {
    const int n = rest.vertexCount();
    start_.assign(n + 1, 0);
    for (int v = 0; v < n; ++v) {
        const int valence = topology.valence(v);
        start_[v + 1] = start_[v] + (valence > 0 ? valence + 1 : 0);
    }
    restPoint_.resize(start_[n]);
    parallelFor(n, [&](int begin, int end, int) {
        for (int v = begin; v < end; ++v) {
            const int m = topology.valence(v);
            if (m == 0) continue;
            const int* ring = topology.ring(v);
            Vec3 c = rest.V.row(v).transpose();
            for (int k = 0; k < m; ++k) c += rest.V.row(ring[k]).transpose();
            c /= m + 1;
            Vec3* out = restPoint_.data() + start_[v];
            out[0] = rest.V.row(v).transpose() - c;
            for (int k = 0; k < m; ++k) out[k + 1] = rest.V.row(ring[k]).transpose() - c;
        }
    });
}

void RingFit::fit(int v, const Positions& V, Mat3& rotation, bool warm, double step) const {
    const int m = start_[v + 1] - start_[v];
    if (m == 0) return;
    const Vec3* r = restPoint_.data() + start_[v];
    const int* ring = topology_.ring(v);
    // Σ r_k p_kᵀ: the posed points need no centring, since the r_k sum to zero.
    Mat3 S = r[0] * V.row(v);
    for (int k = 1; k < m; ++k) S.noalias() += r[k] * V.row(ring[k - 1]);
    if (!warm || !refineRotation(S, rotation, step)) rotation = bestRotation(S);
}

void RingFit::fit(const Positions& V, std::vector<Mat3>& rotation, bool warm, double step) const {
    const int n = topology_.vertexCount();
    if (!warm || static_cast<int>(rotation.size()) != n) {
        rotation.assign(n, Mat3::Identity());
        warm = false;
    }
    // A few hundred nanoseconds a vertex: worth a second thread from a coarse level's size on.
    parallelFor(
        n,
        [&](int begin, int end, int) {
            for (int v = begin; v < end; ++v) fit(v, V, rotation[v], warm, step);
        },
        128);
}

}  // namespace boneless
