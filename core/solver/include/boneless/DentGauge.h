#pragma once

#include <vector>

#include "boneless/MeshTopology.h"
#include "boneless/Reconstruction.h"

namespace boneless {

// How much a pose dents the surface around each marker (docs/markers.md). Around a marker's
// point, within a radius, each encoded vertex's offset from its ring's weighted centre,
// (L V)_i with the encoding's projected mean-value weights, is a discrete mean curvature
// (at rest it lies along the normal). A marker's ratio is the region's mean of it posed over
// its mean at rest, each taken along the vertex's ring normal. A region flatter at rest than a
// sphere kFlatRadii times the radius (judged by each ring's shortest edge) counts as that curved:
// a dent has the marker's size, and a flat patch bent gently (a flank or a hip front as the trunk
// bends) is not one, however flat it was. The floor is a curvature, so a finer mesh of the same
// body gets the same ratios.
class DentGauge {
  public:
    // rest, topology and encoding must outlive it; radius in mesh units.
    DentGauge(const TriMesh& rest, const MeshTopology& topology, const ShapeEncoding& encoding,
              const std::vector<SurfacePoint>& markers, double radius);
    // The worst marker's ratio in V (1 at rest).
    double worstRatio(const Positions& V) const;
    // Each marker's ratio in V.
    std::vector<double> ratios(const Positions& V) const;

    static constexpr double kFlatRadii = 6.0;

  private:
    double meanCurvature(int marker, const Positions& V) const;

    const MeshTopology& topology_;
    const ShapeEncoding& encoding_;
    std::vector<std::vector<int>> regions_;
    std::vector<double> restMean_;  // per marker, floored
};

}  // namespace boneless
