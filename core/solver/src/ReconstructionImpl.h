#pragma once

// The state behind boneless::Reconstruction: its local/global method (LocalGlobalMethod) and its
// exact Gauss–Newton method (the problem in Reconstruction.cpp, its iteration and direct solver in
// ExactMethod.cpp).

#include <functional>
#include <initializer_list>
#include <memory>
#include <optional>
#include <vector>

#include "ArapEnergy.h"
#include "BlockSystem.h"
#include "CarriedParts.h"
#include "LocalGlobalMethod.h"
#include "MarkerPatch.h"
#include "OrientationGuard.h"
#include "boneless/Reconstruction.h"

namespace boneless {

inline bool rowIsFinite(const Positions& P, int r) {
    return P.row(r).allFinite();
}

struct Reconstruction::Impl {
    Impl();
    ~Impl();

    TriMesh rest;
    std::unique_ptr<MeshTopology> topology;
    std::unique_ptr<ShapeEncoding> encoding;
    std::vector<SurfacePoint> points;
    std::vector<int> markers;          // each marker's (nearest) vertex
    std::vector<MarkerPatch> patches;  // each marker's surface (Method::LocalGlobal)
    std::vector<int> markerOf;         // vertex -> marker index, or -1
    Positions restMarkers;             // where the markers sit on the rest pose (K by 3)
    std::vector<int> residualOf;       // residual -> vertex
    std::vector<int> residualIndex;    // vertex -> residual, or -1
    SolverOptions options;
    // When some components hold no marker: the method runs on the others (`solved`, so that
    // their answer is theirs alone) and carries these with them. Only the state above is kept.
    std::unique_ptr<CarriedParts> carried;
    std::unique_ptr<Reconstruction> solved;
    std::unique_ptr<LocalGlobalMethod> localGlobal;  // Method::LocalGlobal
    // Method::Exact:
    std::unique_ptr<BlockSystem> system;
    std::unique_ptr<ArapEnergy> foldGuardTerm;      // its ARAP term, when options.foldGuard > 0
    std::unique_ptr<OrientationGuard> orientation;  // when options.orientationGuard > 0

    // Per-iteration scratch, kept to avoid reallocations per frame.
    std::vector<Vec3> residual;
    std::vector<Mat3> jacobian;  // per residual, at its vertex's ring offsets in the topology
    std::vector<Mat3> rotations;
    std::vector<Mat3> rotationCurvature;  // C_v of each fitted rotation (ArapEnergy::fitRotations)
    std::vector<OrientationGuard::Term> orientationTerms;

    bool foldGuardOn() const { return options.foldGuard > 0; }
    bool softMarkers() const { return options.constraints == SolverOptions::Constraints::Soft; }
    double offset(size_t k) const {
        return k < options.markerOffsets.size() ? options.markerOffsets[k] : 0.0;
    }
    // Where marker k sits for the pose V: its vertex, plus its offset along the ring's normal.
    Vec3 markerPoint(size_t k, const Positions& V, std::vector<Mat3>* dn = nullptr) const;
    double markerEnergy(const Positions& V, const Positions& targets) const;
    double foldGuardEnergy(const Positions& V, std::vector<Mat3>& R,
                           std::vector<Mat3>* curvature = nullptr) const;
    // (Re)builds or drops the orientation guard for the current options.
    void updateOrientationGuard();
    // At the last linearisation, whether the orientation guard has a face turned over.
    bool anyTurnedOver() const {
        return orientation && orientation->anyTurnedOver(orientationTerms);
    }
    double energy(const Positions& V, const Positions& targets) const;

    // Fills residuals and Jacobians, fits the fold guard's rotations (with their curvature, for
    // addRotationCoupling()) and the orientation guard's terms; returns the energy.
    double linearise(const Positions& V, const Positions& targets);
    // Assembles AᵀA and Aᵀr for the current linearisation into the block system.
    void assemble(const Positions& V, const Positions& targets, Eigen::VectorXd& gradient);
    // One stencil per residual (its vertex and ring), one per face: the system's structure.
    Stencils stencils() const;
    // Adds the fold guard's rotation coupling, −2α Σ_v G_vᵀ C_v G_v, to the assembled matrix: the
    // part of its exact Hessian that fixed rotations miss (ArapEnergy::addRotationCoupling), at
    // the last linearisation. Indefinite far from a minimum.
    void addRotationCoupling();
    // Which fold-guard Hessian an assembled matrix holds: its rotations held (Gauss–Newton), or
    // their derivative added (exact).
    enum class GuardHessian { GaussNewton, Exact };
    // The Tikhonov term every factorisation of the system adds, and every solve with an earlier
    // factor must add too: it keeps directions the markers do not pin down (a component
    // without markers, a ring-less vertex) from making the matrix singular.
    double tikhonov() const { return 1e-9 * system->meanDiagonal(); }
    // The exact method's last factorisation was made with no orientation-guard term.
    bool factorWithoutOrientationTerms = true;
    // Builds the system with build(kind) and factorises it, for each kind in turn until one is
    // positive definite; the last is retried with a stronger Tikhonov term. Returns the kind
    // factorised, nothing when none could be.
    std::optional<GuardHessian> factorizeFirstOf(std::initializer_list<GuardHessian> kinds,
                                                 const std::function<void(GuardHessian)>& build);
    // The starting pose of a frame: the guess (or the rest pose moved rigidly onto the markers),
    // isolated vertices moved rigidly, hard markers on their targets.
    Positions startingPose(const Positions& targets, const Positions* guess) const;
    // Vertices a step leaves where they are: the isolated ones and, with hard constraints, those
    // on a visible marker.
    std::vector<int> pinnedVertices(const Positions& targets) const;
    // The system of the Gauss–Newton step at V, of the kind of fold-guard Hessian asked, with the
    // pinned vertices' rows made the identity's and their gradient entries cleared.
    void buildSystem(GuardHessian kind, const Positions& V, const Positions& targets,
                     const std::vector<int>& pinned, Eigen::VectorXd& gradient);
    // The direct solver of one step: solves the system that build(kind) makes (and the gradient
    // it fills) by the last factor made in this solve when that serves, else factorises it (the
    // kind wanted first, then the Gauss–Newton one). Returns the kind solved with, nothing when
    // no factorisation succeeded.
    std::optional<GuardHessian> solveStep(GuardHessian wanted,
                                          const std::function<void(GuardHessian)>& build,
                                          const std::vector<int>& pinned, bool& factorisedThisSolve,
                                          Eigen::VectorXd& gradient, Eigen::VectorXd& step,
                                          SolveReport& report);
    // The exact method's Gauss–Newton iteration from the starting pose.
    SolveResult solveExact(const Positions& targets, const Positions* guess,
                           const std::atomic<bool>* stop);
};

}  // namespace boneless
