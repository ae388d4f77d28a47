#pragma once

#include <Eigen/CholmodSupport>
#include <Eigen/Core>
#include <memory>
#include <vector>

#include "ReconstructionImpl.h"

namespace boneless {

// Gauss–Newton on the same energy as the direct path (G, soft marker term, fold guard), with each
// step's system H δ = −g solved by preconditioned conjugate gradients instead of a factorisation:
// - H·x is applied matrix-free from the per-ring Jacobians (A x, then Aᵀ of that, plus the fold
//   guard's 6αL, and once a step has been taken whole, near the minimum, the derivative of its
//   fitted rotations, which makes the last steps converge quadratically), gathered per vertex so
//   that both cores can work without write conflicts; plus the orientation guard's active faces
//   (a multiresolution input level's: a solve of this class's own refuses the guard);
// - the preconditioner is the rest pose's H, factorised once, turned by the fold guard's fitted
//   rotations: R H_rest⁻¹ Rᵀ with R = blockdiag(R_v). The encoding is rigid-invariant, so for a
//   pose that is a rotation of the rest pose this is H⁻¹ exactly, and close to it for a pose made
//   of pieces that turn (a bending limb), which is what mocap frames are.
// The energy is evaluated together with the next linearisation (one pass per trial point).
// With Preconditioner::LastFactor there is no rest matrix: the preconditioner is the last
// factorisation of a step's own matrix (made by directStep() on the first step, and again when
// conjugate gradients with it miss their tolerance within a share of a factorisation's cost).
// When conjugate gradients miss their tolerance within the budget (a pose far from the last one,
// where the rest-pose preconditioner is poor), that step is taken with a factorisation instead
// (of the Gauss–Newton matrix, or with SolverOptions::exactFallback of the matrix they were
// solving; see directStep()), so a hard frame costs what the direct path costs rather than
// accuracy.
class IterativeSolver {
  public:
    explicit IterativeSolver(Reconstruction::Impl& problem);
    SolveResult solve(const Positions& targets, const Positions* guess);
    // The energy at V and its gradient (3 per vertex, zero on the vertices the targets pin).
    // lastSolved: V is what the last solve() returned for these targets, whose linearisation is
    // kept, so that only the gradient is left to compute.
    double gradientAt(const Positions& V, const Positions& targets, Eigen::VectorXd& g,
                      bool lastSolved);

    // The Gauss–Newton system of the pose last linearised (by solve(), gradientAt() or
    // keepTried()), H x = −g, by preconditioned conjugate gradients; x: start and answer.
    int solveAtCurrent(const Eigen::VectorXd& g, Eigen::VectorXd& x) {
        return conjugateGradients(current_, g, x);
    }
    // Whether solve()'s guess is near the minimum (a prolongation of a converged coarser level),
    // so that the fold guard's exact Hessian is used from the first step (see solve()).
    void setStartsNearMinimum(bool near) { startsNearMinimum_ = near; }
    // SolverOptions::recycledMotions: the motions kept belong to the sequence solved so far. A
    // solve whose guess is not the last answer (a jump in the timeline) forgets them, unless the
    // caller tells the jumps itself (a multiresolution input level, whose guess is a
    // prolongation, never the last answer) and calls forgetMotions().
    void setCallerTellsJumps(bool tells) { callerTellsJumps_ = tells; }
    void forgetMotions() {
        recycled_.clear();
        frames_ = 0;
    }
    // Preconditioner::LastFactor: the system's factor is no longer this solver's (the direct
    // method or a change of options replaced or outdated it); the next step factorises.
    void forgetFactor() { ownFactor_ = false; }
    // The energy of a trial pose (for a line search), and making the last trial the current pose.
    double tryPose(const Positions& V, const Positions& targets) {
        return evaluate(V, targets, trial_, false);
    }
    void keepTried() { std::swap(current_, trial_); }
    // d = −D⁻¹ g with D the 3×3 diagonal blocks of the current pose's Gauss–Newton matrix (the
    // fold guard's with its rotations held): a smoother of the high-frequency error.
    void blockJacobi(const Eigen::VectorXd& g, Eigen::VectorXd& d) const;

  private:
    // Everything known about one pose: residuals, ring Jacobians (CSR, aligned with the
    // topology's neighbour lists), fitted rotations, soft-marker normal derivatives, the energy.
    struct Linearisation {
        std::vector<Vec3> residual;
        std::vector<Mat3> jacobian;
        std::vector<Mat3> rotation;
        std::vector<Mat3> curvature;  // the fold guard's, see ArapEnergy::addRotationCoupling
        std::vector<std::vector<Mat3>> markerDn;
        std::vector<Vec3> markerMiss;
        std::vector<char> markerObserved;
        std::vector<OrientationGuard::Term> orientation;  // the orientation guard's active faces
        double energy = 0;
        // ArapEnergy::rotatedCouplingEdges of `rotation`, made by the first product that needs
        // them.
        mutable std::vector<Vec3> couplingEdges;
        mutable bool couplingEdgesValid = false;
    };

    double evaluate(const Positions& V, const Positions& targets, Linearisation& L,
                    bool withCurvature = true);
    void pinFor(const Positions& targets);
    void gradient(const Positions& V, const Linearisation& L, Eigen::VectorXd& g) const;
    void multiply(const Linearisation& L, const Eigen::VectorXd& x, Eigen::VectorXd& y);
    void precondition(const Linearisation& L, const Eigen::VectorXd& r, Eigen::VectorXd& z) const;
    int conjugateGradients(const Linearisation& L, const Eigen::VectorXd& g, Eigen::VectorXd& x);
    void zeroPinned(Eigen::VectorXd& x) const;
    // One step by a numeric factorisation of the current H (with exactFallback, the fold guard's
    // exact Hessian when conjugate gradients use it, clamped per vertex where it is indefinite),
    // for the frames where conjugate gradients do not converge within their budget.
    bool directStep(const Positions& V, const Positions& targets, Eigen::VectorXd& step);

    Reconstruction::Impl& p_;  // the direct fallback uses its system
    bool cgConverged_ = false;
    bool lastFactor() const {
        return p_.options.preconditioner == SolverOptions::Preconditioner::LastFactor;
    }
    // The system holds a factor that directStep() made (Preconditioner::LastFactor's).
    bool ownFactor_ = false;
    // multiply() includes the fold guard's rotation coupling (see solve()).
    bool exactGuardHessian_ = true;
    bool startsNearMinimum_ = false;
    int n_ = 0;
    // incoming_[inOffsets_[v] .. inOffsets_[v+1]): the Jacobian slots J_uk whose ring neighbour k
    // is v, with their residual vertex u. Aᵀ is applied by gathering over them.
    std::vector<int> inOffsets_, inSlot_, inVertex_;
    std::vector<char> pinned_;
    std::vector<std::vector<Mat3>> scratchJ_;  // per thread
    std::vector<double> laplacianDiagonal_;
    Linearisation current_, trial_;
    Eigen::VectorXd ax_, cgR_, cgZ_, cgP_, cgHp_;
    mutable Eigen::VectorXd rotated_;
    Eigen::VectorXd lastMotion_;  // the last frame's free-vertex motion, the next CG's start
    std::vector<Eigen::VectorXd> recycled_;  // the last full frames' motions, newest last
    long frames_ = 0;                        // solves since the motions were last forgotten
    Positions lastAnswer_;                   // with recycled motions, to tell a jump
    bool callerTellsJumps_ = false;
    // The minimiser of the current pose's quadratic model (the Hessian multiply() applies) over
    // the span of recycled_; directions of non-positive curvature are left out.
    void recycledStart(const Eigen::VectorXd& g, Eigen::VectorXd& step);
    mutable Eigen::MatrixXd scalarRhs_;  // Preconditioner::Scalar's and LumpedScalar's, #V by 3
};

}  // namespace boneless
