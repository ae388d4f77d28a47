#pragma once

#include <string>
#include <vector>

#include "boneless/Reconstruction.h"
#include "boneless/TriMesh.h"

namespace boneless {

// Whether a take's frames are solved against the rest mesh as given ("none") or against the mesh
// first fitted to the actor at the calibration frame ("shape"): limb lengths and proportions
// follow the actor, so later frames do not stretch the mesh to make up the difference.
enum class CalibrateMode { None, Shape };
// The mode's name everywhere a user meets it (the CLI's --calibrate, the sidecar's and the
// project's "calibrate"); parseCalibrateMode() takes it back (false for anything else).
const char* calibrateModeName(CalibrateMode mode);
bool parseCalibrateMode(const std::string& name, CalibrateMode& mode);

// A marker the mesh can only meet by tearing its shape: a calibration refuses it, naming it.
// Reachable markers of a real actor stretch their neighbourhood by tens of percent at most.
constexpr double kUnreachableStrain = 1.0;  // an edge at the marker at twice its rest length
constexpr double kUnreachableMm = 300.0;    // the marker this far from where its neighbours put it

// The rest shape fitted to the markers at one frame: `solver` (prepared on the rest mesh with
// the markers, soft, offsets set) solves `targets` (K by 3, mesh units, NaN rows missing), and
// its answer becomes the calibrated rest. Throws Error naming every marker that could only be
// met by tearing the mesh (labels[k] names marker k; mmPerMeshUnit converts for the message).
Positions fitActorShape(Reconstruction& solver, const Positions& targets,
                        const std::vector<std::string>& labels, double mmPerMeshUnit);

// Per-edge strain |len/restLen − 1| against a rest, one entry per face corner's edge (interior
// edges twice): the distribution the sidecar summarises. The rest lengths are measured once, for
// all the frames of a take.
class EdgeStrain {
  public:
    EdgeStrain(const Faces& F, const Positions& rest);      // rest: #V by 3
    std::vector<double> strains(const Positions& V) const;  // V: #V by 3, posed
  private:
    std::vector<int> ends_;  // 2 per edge with a length at rest
    std::vector<double> restLength_;
};
// The root mean square of the values (0 when empty): of the strains, edgeLengthDistortion().
double rootMeanSquare(const std::vector<double>& values);
// The q-quantile (0..1) of the values (nearest rank; 0 when empty).
double quantile(std::vector<double> values, double q);

}  // namespace boneless
