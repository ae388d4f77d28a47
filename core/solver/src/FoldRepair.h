#pragma once

#include <Eigen/Sparse>
#include <vector>

#include "RingFit.h"

namespace boneless {

// Unfolds the faces a local/global answer leaves turned over. A face is folded when its normal
// points against its rest normal carried by its vertices' fitted ring rotations (the measure of
// Metrics' foldedFaces). Where the arm presses on the body, or a marker pulls a thin part, the
// global step's compromise can turn a few faces over; no rotation the local step fits is a
// reflection, but nothing in the quadratic forbids one. Around each fold, a patch of a few rings
// is solved again, the rest held: the global step's own quadratic (its matrix and right-hand
// side, so the rest of the answer is what it was) plus a one-sided penalty on each face's
// projected area falling below a fifth of its rest area,
//   w Ā Σ_f max(0, τ − s_f)²,  s_f = n_f(V) · u_f / |n⁰_f|,
// by Gauss–Newton steps with a backtracking line search. u_f, the rest normal carried by the
// ring rotations, is held during those steps and refitted after them, as the measure refits it:
// a fold drags its own rings' rotations along, so an unfolded patch is checked again in its new
// rotations and solved again if need be. Ā is the mean rest face area, so w is dimensionless,
// and a sliver is held as hard as any face.
class FoldRepair {
  public:
    // rest and rings must outlive it.
    FoldRepair(const TriMesh& rest, const RingFit& rings);
    // Folds are judged in ring rotations fitted until a Newton step turns them by less than this
    // (radians): about 1e-12 rad, as a fresh fit would judge a face on the edge of folding.
    static constexpr double kCountStep = 1e-6;

    // What the global step minimised: VᵀAV − 2 Vᵀrhs (A: #V by #V, this frame's: without the
    // pull of its missing soft markers; rhs: #V by 3).
    struct Quadratic {
        const Eigen::SparseMatrix<double>& A;
        const Eigen::MatrixXd& rhs;
        // A's row v times V, minus rhs's row.
        Vec3 gradient(int v, const Positions& V) const;
    };
    // V: the answer (#V by 3), changed in place; pinned: vertices that must not move;
    // rotations: each vertex's ring rotation fitted to V, kept fitted to it. Returns how many
    // faces are still folded.
    int repair(Positions& V, const Quadratic& q, const std::vector<char>& pinned,
               std::vector<Mat3>& rotations) const;

    // The faces folded in V for these ring rotations: their projected area below `margin` of
    // the rest area (0: turned over).
    std::vector<int> folded(const Positions& V, const std::vector<Mat3>& rotations,
                            double margin = 0) const;

  private:
    // s_f for the carried direction u_f (unit, or zero for a face with nothing to keep).
    double projectedArea(const Positions& V, int f, const Vec3& u) const;
    Vec3 carriedNormal(int f, const std::vector<Mat3>& rotations) const;
    // One patch around `faces`, `rings` rings wide: Gauss–Newton until no face in it folds.
    void solvePatch(Positions& V, const Quadratic& q, const std::vector<char>& pinned,
                    std::vector<Mat3>& rotations, const std::vector<int>& faces, int rings) const;
    struct Patch {
        std::vector<int> vertices;              // free, moved
        std::vector<int> local;                 // vertex -> index in vertices, or −1
        std::vector<int> faces;                 // whose carried normal the vertices can change
        std::vector<double> threshold;          // τ per face, raised for one that folds again
        std::vector<Eigen::Triplet<double>> A;  // A over the vertices (scalar)
    };
    // The penalty with w Ā = scale.
    double penalty(const Positions& V, const Patch& patch, const std::vector<Mat3>& rotations,
                   double scale) const;
    // Gauss–Newton steps on the patch, the rotations (so each u_f) held.
    void solveHeld(Positions& V, const Quadratic& q, const Patch& patch,
                   const std::vector<Mat3>& rotations, double scale) const;
    // The faces in groups that share vertices.
    std::vector<std::vector<int>> clusters(const std::vector<int>& faces) const;
    // The vertices within `rings` rings of `seeds` (seeds included).
    std::vector<int> grow(std::vector<int> seeds, int rings) const;

    const TriMesh& rest_;
    const RingFit& rings_;
    std::vector<int> cornerStart_, cornerFace_;  // vertex -> its faces (CSR)
    std::vector<Vec3> restNormal_;               // per face, length twice its area
    double scale_ = 0;                           // w Ā
};

}  // namespace boneless
