#pragma once

#include "boneless/ShapeEncoding.h"

namespace boneless {

// The rotation R maximising tr(R S) (the transposed orthogonal polar factor of S), by scaled
// Newton iterations where S is well conditioned, by an SVD otherwise.
Mat3 bestRotation(const Mat3& S);

// The same maximiser refined from R by Newton's method on rotations, a 3×3 solve per step: from a
// nearby R (the last iteration's) one or two steps. Returns false when it does not converge; the
// caller then uses bestRotation(). It stops once a step turns R by less than tolerance (radians).
bool refineRotation(const Mat3& S, Mat3& R, double tolerance = 1e-10);

// Whether the symmetric 3×3 H is positive definite (leading minors).
bool positiveDefinite(const Mat3& H);

}  // namespace boneless
