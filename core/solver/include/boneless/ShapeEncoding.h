#pragma once

#include <Eigen/Core>
#include <vector>

#include "boneless/MeshTopology.h"
#include "boneless/TriMesh.h"

namespace boneless {

// Kraevoy & Sheffer's local shape code (docs/algorithm.md §2). Each vertex i is stored relative to
// its one-ring p_1..p_m: the ring's area-weighted normal n_i, the plane through the ring's centroid
// l_i, signed mean-value weights w_ik of v_i projected into that plane, and the height h_i of v_i
// above it. Decoding F_i(V) = Σ w_ik p'_k + h_i n_i depends only on the ring, so the code is
// invariant under rigid motions and reproduces the rest pose exactly.
class ShapeEncoding {
  public:
    enum class Kind : char {
        Full,      // encoded against its ring; carries a residual
        Unencoded  // isolated, valence < 3, or a ring with no area: no residual of its own
    };

    ShapeEncoding(const TriMesh& rest, const MeshTopology& topology);

    const MeshTopology& topology() const { return *topology_; }
    int vertexCount() const { return static_cast<int>(kind_.size()); }
    Kind kind(int v) const { return kind_[v]; }
    bool encoded(int v) const { return kind_[v] == Kind::Full; }
    double height(int v) const { return height_[v]; }
    // Weights aligned with topology().ring(v).
    const double* weights(int v) const { return weights_.data() + topology_->offsets()[v]; }
    int encodedCount() const;

    // F_i(V), the position the ring of v asks for.
    Vec3 decode(int v, const Positions& V) const;
    // F_i(V) and J_ik = ∂F_i/∂p_k for every ring neighbour k (exact, §1.4). Returns false when the
    // ring has collapsed (|N| ≈ 0); then J holds the frozen-normal part only.
    bool decodeWithJacobian(int v, const Positions& V, Vec3& F, std::vector<Mat3>& J) const;

    // The unit normal n_i(V) of v's ring polygon and ∂n_i/∂p_k for each ring neighbour (zero
    // blocks when the ring has collapsed). Markers off the skin sit along it.
    Vec3 ringNormal(int v, const Positions& V, std::vector<Mat3>* dn = nullptr) const;

  private:
    const MeshTopology* topology_;
    std::vector<Kind> kind_;
    std::vector<double> weights_;
    std::vector<double> height_;
};

// Signed mean-value coordinates (Hormann & Floater 2006) of x with respect to the planar polygon
// p[0..m-1] in the plane with unit normal n. Exact on vertices and edges; valid outside the polygon
// and for non-convex polygons. Falls back to the least-norm affine weights when mean-value weights
// do not exist (their sum vanishes). Always reproduces x: Σ w_k p_k = x for planar input.
void meanValueWeights(const Vec3* p, int m, const Vec3& x, const Vec3& n, double* w);

}  // namespace boneless
