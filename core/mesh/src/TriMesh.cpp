#include "boneless/TriMesh.h"

namespace boneless {

double boundingBoxDiagonal(const Positions& V) {
    if (V.rows() == 0) return 0.0;
    return (V.colwise().maxCoeff() - V.colwise().minCoeff()).norm();
}

bool zeroArea(const Vec3& a, const Vec3& b, const Vec3& c, double diagonal) {
    return (b - a).cross(c - a).norm() <= 1e-12 * diagonal * diagonal;
}

}  // namespace boneless
