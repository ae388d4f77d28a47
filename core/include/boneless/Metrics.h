#pragma once

#include "boneless/TriMesh.h"

namespace boneless {

// Error measures of a reconstruction V against a ground truth T (both #V by 3).
double rmsVertexError(const Positions& V, const Positions& T);
double maxVertexError(const Positions& V, const Positions& T);
// Faces whose normal points against the true face's normal (a fold or a mirrored triangle).
int flippedFaceCount(const Faces& F, const Positions& V, const Positions& T);
// RMS over edges of |len/restLen − 1|: how much a pose stretches or squashes the mesh.
double edgeLengthDistortion(const Faces& F, const Positions& V, const Positions& rest);

}  // namespace boneless
