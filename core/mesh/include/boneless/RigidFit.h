#pragma once

#include "boneless/TriMesh.h"

namespace boneless {

// x ↦ R x + t.
struct RigidMotion {
    Mat3 R = Mat3::Identity();
    Vec3 t = Vec3::Zero();
    Vec3 apply(const Vec3& x) const { return R * x + t; }
};

// x ↦ scale · R x + t: how a take's coordinates map onto the rest mesh's.
struct Similarity {
    double scale = 1.0;
    Mat3 R = Mat3::Identity();
    Vec3 t = Vec3::Zero();
    Vec3 apply(const Vec3& x) const { return scale * (R * x) + t; }
};

// Both fits are least squares (Umeyama 1991) from from[k] onto to[k], #K by 3 each; rows with a
// NaN in either are skipped.

// The rigid motion; with fewer than three usable rows, the mean translation (identity for none).
RigidMotion fitRigidMotion(const Positions& from, const Positions& to);

// The similarity. Throws Error when fewer than three usable rows remain or they are collinear,
// since the scale and rotation are then undetermined.
Similarity fitSimilarity(const Positions& from, const Positions& to);

// RMS distance between the mapped `from` rows and the `to` rows (finite rows only; infinity for
// none).
double alignmentResidual(const Similarity& s, const Positions& from, const Positions& to);

}  // namespace boneless
