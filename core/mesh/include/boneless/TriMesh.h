#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>  // cross products everywhere

namespace boneless {

using Vec3 = Eigen::Vector3d;
using Mat3 = Eigen::Matrix3d;
using Positions = Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor>;  // #V by 3
using Faces = Eigen::Matrix<int, Eigen::Dynamic, 3, Eigen::RowMajor>;         // #F by 3

// A triangle mesh as the rest of the core sees it: plain arrays, vertex i is the input file's
// vertex i, faces oriented as in the file.
struct TriMesh {
    Positions V;
    Faces F;

    int vertexCount() const { return static_cast<int>(V.rows()); }
    int faceCount() const { return static_cast<int>(F.rows()); }
};

// Length of the diagonal of the axis-aligned bounding box (0 for an empty mesh).
double boundingBoxDiagonal(const Positions& V);

}  // namespace boneless
