#pragma once

#include <vector>

#include "boneless/TriMesh.h"

namespace boneless {

// Error measures of a reconstruction V against a ground truth T (both #V by 3).
double rmsVertexError(const Positions& V, const Positions& T);
double maxVertexError(const Positions& V, const Positions& T);
// Faces whose normal points against the true face's normal (a fold or a mirrored triangle).
int flippedFaceCount(const Faces& F, const Positions& V, const Positions& T);
// Faces folded over relative to their own neighbourhood, for poses with no ground truth: each
// vertex's one-ring is fitted rigidly from `rest` to V, and a face counts when its posed normal
// points against its rest normal carried by those local rotations. A limb that turns as a whole,
// however far, folds nothing.
std::vector<int> foldedFaces(const Faces& F, const Positions& V, const Positions& rest);
// Per face, its rest normal (length twice the rest area) carried into V by the one-ring rigid fits
// of its three vertices, summed: the direction foldedFaces() expects the posed face to face.
std::vector<Eigen::Vector3d> carriedRestNormals(const Faces& F, const Positions& V,
                                                const Positions& rest);
inline int foldedFaceCount(const Faces& F, const Positions& V, const Positions& rest) {
    return static_cast<int>(foldedFaces(F, V, rest).size());
}
// RMS over edges of |len/restLen − 1|: how much a pose stretches or squashes the mesh.
double edgeLengthDistortion(const Faces& F, const Positions& V, const Positions& rest);
// Share (0..1) of interior edges whose signed dihedral angle differs from its rest value by more
// than `degrees`: a kink gauge, which neither the strain nor the fold count sees. A rigid motion
// bends nothing; a sheet folded along one line bends that line's edges only.
double bentEdgeShare(const Faces& F, const Positions& V, const Positions& rest, double degrees);

}  // namespace boneless
