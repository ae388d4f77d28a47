#include "boneless/TriMesh.h"

namespace boneless {

void followWelds(const TriMesh& mesh, Positions& V) {
    for (size_t v = 0; v < mesh.weldedTo.size(); ++v)
        if (mesh.weldedTo[v] != static_cast<int>(v)) V.row(v) = V.row(mesh.weldedTo[v]);
}

double boundingBoxDiagonal(const Positions& V) {
    if (V.rows() == 0) return 0.0;
    return (V.colwise().maxCoeff() - V.colwise().minCoeff()).norm();
}

double boundingBoxDiagonal(const Positions& V, const Faces& F) {
    if (F.size() == 0) return 0.0;
    Vec3 low = V.row(F(0, 0)).transpose(), high = low;
    for (Eigen::Index i = 0; i < F.size(); ++i) {
        const Vec3 p = V.row(F.data()[i]).transpose();
        low = low.cwiseMin(p);
        high = high.cwiseMax(p);
    }
    return (high - low).norm();
}

bool zeroArea(const Vec3& a, const Vec3& b, const Vec3& c, double diagonal) {
    return (b - a).cross(c - a).norm() <= 1e-12 * diagonal * diagonal;
}

}  // namespace boneless
