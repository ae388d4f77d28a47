#pragma once

#include <Eigen/Sparse>
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

    // Each vertex's rotation that minimises E for the given V (the "local step").
    void fitRotations(const Positions& V, std::vector<Mat3>& R) const;
    double energy(const Positions& V, const std::vector<Mat3>& R) const;
    // b with ∇_V E = 2 (3 L V − b) for fixed R: the rotated rest edges, summed per vertex.
    Eigen::MatrixXd rotatedRestEdges(const std::vector<Mat3>& R) const;
    // L = Σ w (e_j − e_k)(e_j − e_k)ᵀ: positive semidefinite (it is the Dirichlet energy).
    const Eigen::SparseMatrix<double>& laplacian() const { return laplacian_; }
    // Half the cotangent of face f's angle at corner c: the weight of the edge opposite c.
    double cotangent(int f, int c) const { return cotangent_(f, c); }

  private:
    const TriMesh* rest_;
    Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor> cotangent_;  // half cot, per corner
    Eigen::SparseMatrix<double> laplacian_;
};

}  // namespace boneless
