#pragma once

#include <vector>

#include "boneless/MeshTopology.h"
#include "boneless/Reconstruction.h"

namespace boneless {

// How much a pose dents the surface around each marker (docs/markers.md). Around a marker's
// point, within a radius, each encoded vertex's offset from its ring's weighted centre,
// (L V)_i with the encoding's projected mean-value weights, is a discrete mean curvature
// (at rest it lies along the normal). A marker's ratio is the region's mean of it posed over
// its mean at rest, each taken along the vertex's ring normal; a region flatter at rest than kFlat
// of its edge length counts as that flat, so that a flat patch gently bent is not a dent.
class DentGauge {
  public:
    // rest, topology and encoding must outlive it; radius in mesh units.
    DentGauge(const TriMesh& rest, const MeshTopology& topology, const ShapeEncoding& encoding,
              const std::vector<SurfacePoint>& markers, double radius);
    // The worst marker's ratio in V (1 at rest).
    double worstRatio(const Positions& V) const;
    // Each marker's ratio in V.
    std::vector<double> ratios(const Positions& V) const;

    static constexpr double kFlat = 0.02;

  private:
    double meanCurvature(int marker, const Positions& V) const;

    const MeshTopology& topology_;
    const ShapeEncoding& encoding_;
    std::vector<std::vector<int>> regions_;
    std::vector<double> restMean_;  // per marker, floored
};

}  // namespace boneless
