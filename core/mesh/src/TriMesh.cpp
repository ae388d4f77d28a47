#include "boneless/TriMesh.h"

namespace boneless {

double boundingBoxDiagonal(const Positions& V) {
    if (V.rows() == 0) return 0.0;
    return (V.colwise().maxCoeff() - V.colwise().minCoeff()).norm();
}

}  // namespace boneless
