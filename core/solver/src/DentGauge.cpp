#include "boneless/DentGauge.h"

#include <algorithm>
#include <limits>

namespace boneless {

DentGauge::DentGauge(const TriMesh& rest, const MeshTopology& topology,
                     const ShapeEncoding& encoding, const std::vector<SurfacePoint>& markers,
                     double radius)
    : topology_(topology), encoding_(encoding) {
    for (const SurfacePoint& p : markers) {
        std::vector<int> region;
        for (int v : surfaceDisk(rest, topology, p, radius))
            if (encoding.encoded(v)) region.push_back(v);
        regions_.push_back(std::move(region));
        const int k = static_cast<int>(regions_.size()) - 1;
        // On a sphere of radius R a vertex lies Σ w_j e_j²/(2R) off its ring's centre, at least
        // e²/(2R) for its shortest ring edge e: the region's floor is that for R = kFlatRadii ×
        // radius, averaged like the gauge. The shortest edge keeps it below a thin part's own
        // curvature where the rings are long along the part.
        double floor = 0;
        for (int v : regions_[k]) {
            double shortest = std::numeric_limits<double>::infinity();
            for (int j = 0; j < topology.valence(v); ++j)
                shortest = std::min(
                    shortest, (rest.V.row(v) - rest.V.row(topology.ring(v)[j])).squaredNorm());
            if (topology.valence(v) > 0) floor += shortest / (2 * kFlatRadii * radius);
        }
        if (!regions_[k].empty()) floor /= static_cast<double>(regions_[k].size());
        restMean_.push_back(std::max(meanCurvature(k, rest.V), floor));
    }
}

double DentGauge::meanCurvature(int marker, const Positions& V) const {
    const std::vector<int>& region = regions_[marker];
    if (region.empty()) return 0;
    double sum = 0;
    for (int v : region) {
        Vec3 delta = V.row(v).transpose();
        const int* ring = topology_.ring(v);
        const double* w = encoding_.weights(v);
        for (int j = 0; j < topology_.valence(v); ++j) delta -= w[j] * V.row(ring[j]).transpose();
        // Along the ring's normal: a stretched or sheared ring moves its centre sideways, which
        // is no dent.
        sum += std::abs(delta.dot(encoding_.ringNormal(v, V)));
    }
    return sum / static_cast<double>(region.size());
}

std::vector<double> DentGauge::ratios(const Positions& V) const {
    std::vector<double> out(regions_.size(), 1.0);
    for (size_t k = 0; k < regions_.size(); ++k)
        if (restMean_[k] > 0) out[k] = meanCurvature(static_cast<int>(k), V) / restMean_[k];
    return out;
}

double DentGauge::worstRatio(const Positions& V) const {
    const std::vector<double> r = ratios(V);
    return r.empty() ? 1.0 : *std::max_element(r.begin(), r.end());
}

}  // namespace boneless
