#pragma once

#include <vector>

#include "boneless/MeshTopology.h"
#include "boneless/ShapeEncoding.h"

namespace boneless {

// Each vertex's ring (its neighbours and itself) fitted rigidly from rest to a pose: the rotation
// that best turns the rest points about their centroid onto the posed ones (uniform weights).
// The local step's rotation for the Laplacian term, and the frame Metrics' folded faces are
// judged in.
class RingFit {
  public:
    // rest and topology must outlive it.
    RingFit(const TriMesh& rest, const MeshTopology& topology);

    // rotation[v] for every vertex with a ring (isolated ones are left as they are). warm:
    // Newton steps from rotation[v] until a step turns it by less than `step` radians; cold:
    // the closed form.
    void fit(const Positions& V, std::vector<Mat3>& rotation, bool warm, double step) const;
    void fit(int v, const Positions& V, Mat3& rotation, bool warm, double step) const;

  private:
    const MeshTopology& topology_;
    std::vector<int> start_;       // CSR over ring + centre, empty for an isolated vertex
    std::vector<Vec3> restPoint_;  // the rest points minus their centroid, centre first
};

}  // namespace boneless
