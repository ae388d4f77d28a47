#pragma once

#include <vector>

#include "boneless/ShapeEncoding.h"
#include "boneless/TriMesh.h"

namespace boneless {

// Keeps faces from turning over (not in the paper). The ARAP fold guard makes a fold cost
// something, but a sliver (the corner of a mouth) or a thin part that a marker pulls hard (a
// finger, a toe) still folds at a price lower than what the markers pay for the alternative.
// This term is a one-sided penalty on each face's orientation:
//   s_f = n_f(V) · u_f / |n⁰_f|,  E = ½ w Ā Σ_f max(0, τ − s_f)²,
// where n_f is the face's (area-scaled) normal, u_f the unit direction it is expected to face and
// s_f its area projected on u_f as a fraction of its rest area. E is zero unless a face has
// shrunk below τ of its area or turned over. Ā, the mean rest face area, makes w dimensionless
// (E is a squared length, like G) and gives every face the same say, sliver or not: a sliver's
// s_f moves fastest, so it is held hardest.
// u_f is the face's rest normal carried by its vertices' rigidly fitted one-rings (the measure
// of Metrics' foldedFaces), so E = 0 means no face turned over by that measure. E is a function
// of V alone; its Gauss–Newton terms hold u_f at the linearisation point, and the line search
// sees the true E. (Tried: u_f's turning added to the gradient exactly, with the same matrix;
// its steps were far too long and sent the CMU take astray.)
class OrientationGuard {
  public:
    OrientationGuard(const TriMesh& rest, double weight, double threshold);

    double energy(const Positions& V) const;

    // The active faces' residuals r_f = √(wĀ)(τ − s_f), E = ½ Σ r_f², and their derivatives
    // with respect to the face's three vertices, u_f held fixed. Returns E.
    struct Term {
        int face;
        double residual;
        Vec3 derivative[3];
    };
    double linearise(const Positions& V, std::vector<Term>& active) const;
    // Adds E's gradient, Σ r_f ∂r_f, to g (3 per vertex), and the Gauss–Newton product
    // Σ ∂r_f (∂r_f · x) to y, for the terms linearise() gave.
    void addGradient(const std::vector<Term>& active, Eigen::VectorXd& g) const;
    void addProduct(const std::vector<Term>& active, const Eigen::VectorXd& x,
                    Eigen::VectorXd& y) const;
    // Whether an active face has turned over (s_f < 0), not just shrunk.
    bool anyTurnedOver(const std::vector<Term>& active) const;

  private:
    // u_f for the pose V, zero where a face has no orientation to keep (no rest area, or a
    // neighbourhood with none).
    std::vector<Vec3> reference(const Positions& V) const;
    // τ − s_f for the direction u, r_f / √(wĀ).
    double gap(const Positions& V, int f, const Vec3& u) const;

    const TriMesh* rest_;
    double scale_;  // √(w Ā)
    double threshold_;
    std::vector<double> restArea2_;  // |n⁰_f|, twice the rest area
};

}  // namespace boneless
