#pragma once

#include <Eigen/Sparse>
#include <tuple>
#include <vector>

#include "boneless/ShapeEncoding.h"
#include "boneless/TriMesh.h"

namespace boneless {

// The as-rigid-as-possible energy (Sorkine & Alexa 2007), spokes-and-rims form with cotangent
// weights: E(V, R) = Σ_f Σ_{edges jk of f} w_jk^f Σ_{i ∈ f} |(v_j − v_k) − R_i (v⁰_j − v⁰_k)|².
// Shared by the ARAP baseline and by the solver's fold guard, which adds a weak multiple of it.
class ArapEnergy {
  public:
    explicit ArapEnergy(const TriMesh& rest);

    // Each vertex's rotation that minimises E for the given V (the "local step"). warmStart: R
    // already holds rotations close to the answer (the last pose's), so fewer Newton
    // steps are needed; the answer is the same.
    // curvature (optional): per vertex, the inverse of the 3×3 Hessian of tr(R S_v) over
    // rotations at the fitted R_v (zero where it is not positive definite), which is what
    // the exact method's rotation coupling (couplingBlocks()) needs.
    // tolerance: the last Newton step's angle (radians) at which a rotation counts as fitted.
    void fitRotations(const Positions& V, std::vector<Mat3>& R, bool warmStart = false,
                      std::vector<Mat3>* curvature = nullptr, double tolerance = 1e-10) const;
    double energy(const Positions& V, const std::vector<Mat3>& R) const;
    // b with ∇_V E = 2 (3 L V − b) for fixed R: the rotated rest edges, summed per vertex.
    Eigen::MatrixXd rotatedRestEdges(const std::vector<Mat3>& R) const;
    // The same for vertex v, from turnCornerEdges()'s output, so that a caller can gather it
    // into its own per-vertex loop.
    Vec3 rotatedRestEdges(int v, const std::vector<Vec3>& cornerEdges) const {
        Vec3 s = Vec3::Zero();
        for (int i = cornerOffsets_[v]; i < cornerOffsets_[v + 1]; ++i)
            s += cornerEdges[corners_[i]];
        return s;
    }
    // Each face corner's rest edge (corner c of face f at 3 f + c) turned by R_a + R_b + R_c over
    // the face's corners: a vertex's gather then reads a vector a corner, not a matrix.
    void turnCornerEdges(const std::vector<Mat3>& R, std::vector<Vec3>& cornerEdges) const;
    // L = Σ w (e_j − e_k)(e_j − e_k)ᵀ: positive semidefinite (it is the Dirichlet energy).
    const Eigen::SparseMatrix<double>& laplacian() const { return laplacian_; }
    // G_v as 3×3 blocks (vertex, block; a vertex may repeat) for v's fitted rotation R_v, so that
    // an assembled Hessian can hold the coupling term too (with C_v from fitRotations()).
    void couplingBlocks(int v, const Mat3& Rv, std::vector<std::pair<int, Mat3>>& blocks) const;
    // The edges (j, k, w) of v's faces: the terms of v's own rotation, whose Hessian for fixed
    // rotations is 2 Σ w (e_j − e_k)(e_j − e_k)ᵀ ⊗ I (v's share of 6 L ⊗ I).
    void vertexEdges(int v, std::vector<std::tuple<int, int, double>>& edges) const;
    // Half the cotangent of face f's angle at corner c: the weight of the edge opposite c.
    double cotangent(int f, int c) const { return cotangent_(f, c); }

  private:
    void buildLaplacian();

    const TriMesh* rest_;
    Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor> cotangent_;  // half cot, per corner
    Eigen::SparseMatrix<double> laplacian_;
    std::vector<Vec3> restEdge_;  // per face corner: rest edge opposite it, v⁰_j − v⁰_k
    // Per face corner c: w_{c+2} e⁰_{c+2} − w_{c+1} e⁰_{c+1}, the rest edges its vertex's share of
    // rotatedRestEdges() turns.
    std::vector<Vec3> cornerRest_;
    // Corners (3 f + c) around each vertex, CSR, so that per-vertex sums need no shared writes.
    std::vector<int> cornerOffsets_, corners_;
};

}  // namespace boneless
