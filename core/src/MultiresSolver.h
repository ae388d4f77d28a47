#pragma once

#include <memory>
#include <optional>
#include <vector>

#include "VertexOrder.h"
#include "boneless/MeshHierarchy.h"
#include "boneless/Reconstruction.h"

namespace boneless {

// SolverOptions::Method::Multiresolution (algorithm.md §1.6): the same energy, reached through a
// hierarchy of coarser meshes made by independent-set half-edge collapses.
//  - The coarsest level (a few thousand vertices) is solved to convergence by Gauss–Newton
//    (conjugate gradients, a factorisation when they stall; with the orientation guard on, the
//    direct method with the guard): it carries the large, smooth part of each frame's motion,
//    which is what conjugate gradients on the full mesh are slowest at. Its
//    fold guard is weighted by √(input vertices / coarsest vertices), the ratio of their edge
//    lengths: measured to bring its minimum closer to the input's (a quarter to a third less error
//    after prolongation on 20K–100K faces).
//  - Each finer level starts from its own last answer plus the prolonged change of the level
//    below (P(X_{l+1}) − P(X_{l+1}^last)), where P places every removed vertex explicitly at
//    F_r of its coarser ring. The detail a level added last frame is kept instead of being
//    recomputed from the coarse shape, so only the frame's change has to be corrected.
//  - The input level then takes correctionSteps cheap steps (a block-Jacobi step, then a
//    two-level step: its gradient restricted through the prolongation's Jacobian, the coarsest
//    level's Gauss–Newton system solved for it, the answer prolonged back, a line search on the
//    input's energy) and fineIterations Gauss–Newton steps (conjugate gradients with the rotated
//    rest factorisation; its rest system is only made when there are such steps). The levels
//    between are prolonged through only: steps there with a cheap local preconditioner were
//    measured to leave the error where it was (it is smooth: the coarse and fine energies' minima
//    differ slightly), at a high price. A coarse-grid correction of the full approximation
//    scheme (the coarsest energy minus <τ, X>, τ from the input's restricted gradient) was
//    measured to make it worse: without smoothing first, the restricted gradient is dominated by
//    the finest scale's error, and the coarsest level's soft modes amplify it.
// Where prolongation alone stands (koala, 100K faces, bend frame 40, 0.42 % RMS from the answer
// of the bench's earlier reference, which had not converged; 0.51 % from the minimum): the
// coarsest level's own vertices are 0.40 % off; the converged answer's coarsest
// vertices, prolonged, would give 0.088 %. So the gap is the coarsest minimum, not the
// prolongation. Minimising the input's energy over the prolongation's range does not close it
// (8 Gauss–Newton steps with the exact restricted Hessian: 0.41 → 0.44 %), because the removed
// vertices keep their rest encoding; the answer's detail is relaxed, and only the input level's
// own steps find it. Without the fold guard the gap is 0.18 %.
// The solver keeps every level's last answer. A guess that is not the last answer (a jump in the
// timeline) restarts the levels from the guess.
class MultiresSolver {
  public:
    MultiresSolver(const TriMesh& rest, const std::vector<int>& markers,
                   const SolverOptions& options);
    SolveResult solve(const Positions& targets, const Positions* guess);
    // The input's energy and encoding, in the caller's vertex order.
    double energy(const Positions& V, const Positions& targets) const;
    const ShapeEncoding& encoding() const;

    // The input level (the coarsest when the mesh is already small), in order_.
    const Reconstruction& fine() const { return hierarchy_->levelCount() == 1 ? coarsest_ : fine_; }
    int levelCount() const { return hierarchy_->levelCount(); }
    const MeshHierarchy& hierarchy() const { return *hierarchy_; }

  private:
    SolveResult solveInOrder(const Positions& targets, const Positions* guess);
    // Level l's positions from level l+1's: survivors copied, removed vertices decoded.
    void prolong(int l, const Positions& coarse, Positions& fine) const;
    // prolong()'s Jacobian at `fine` (a prolongation of level l+1's positions): each removed
    // vertex's J_rk, at the topology's ring offsets.
    std::vector<Mat3> prolongationJacobian(int l, const Positions& fine) const;
    // Its transpose: a gradient over level l's vertices becomes one over level l+1's.
    void restrictGradient(int l, const std::vector<Mat3>& jacobian, const Positions& g,
                          Positions& out) const;
    // It, applied to level l+1's displacement d.
    void prolongLinear(int l, const std::vector<Mat3>& jacobian, const Positions& d,
                       Positions& out) const;
    // SolverOptions::correctionSteps on the input level's pose V; prolonged[l] is level l's
    // prolongation of this frame's level l+1 (where the prolongation's Jacobians are taken).
    // Returns the input's energy at the final V.
    double correctionSteps(const Positions& targets, const std::vector<Positions>& prolonged,
                           Positions& V, SolveReport& report);

    // Level l's rows of a pose of the input mesh.
    Positions restrictTo(int l, const Positions& input) const;
    void restartFrom(const Positions& guess);
    const ShapeEncoding& encoding(int l) const;

    // The hierarchy, then the coarsest level (and the encodings of the levels between); and the
    // input level, on the other core.
    void prepareCoarsest(const TriMesh& rest, const std::vector<int>& markers,
                         const SolverOptions& options);
    void prepareInput(const TriMesh& rest, const std::vector<int>& markers,
                      const SolverOptions& options);

    // The levels work in this order of the vertices: the caller's unless the mesh is large.
    VertexOrder order_;
    // The input's encoding in the caller's order, when order_ is not the identity.
    std::unique_ptr<MeshTopology> userTopology_;
    std::unique_ptr<ShapeEncoding> userEncoding_;
    std::optional<MeshHierarchy> hierarchy_;
    Reconstruction coarsest_, fine_;  // the two levels that are solved
    // Levels 1 .. L−2, which are only prolonged through.
    std::vector<std::unique_ptr<MeshTopology>> topologies_;
    std::vector<std::unique_ptr<ShapeEncoding>> encodings_;
    std::vector<Positions> last_;  // per level, the last frame's answer
    // Per level but the coarsest, the prolongation of the level below's last answer (the
    // answer without its detail): the next frame adds the change from it.
    std::vector<Positions> lastProlonged_;

    // SolverOptions::keyframeEvery. A frame between keyframes takes the input's correction
    // over the last interval (the answer's change minus the prolongation's, which the warm
    // start already carries) times the coarsest level's progress along that interval.
    struct Keyframe {
        Positions fine, prolonged, coarsest;  // answer[0], prolonged[0], answer[L − 1]
    };
    // After a keyframe's input steps; `warm`: it continued the sequence of the last keyframe.
    void keepKeyframe(const std::vector<Positions>& answer, const Positions& prolonged, bool warm);
    // How the coarsest level has moved since the keyframe: `along` the interval's coarsest change
    // (least squares), and the share of the move that lies `off` it.
    struct Progress {
        double along = 0, off = 0;
    };
    Progress coarsestProgress(const Positions& coarsest) const;
    void extrapolateCorrection(std::vector<Positions>& answer, double along);
    std::optional<Keyframe> keyframe_;  // the last one
    Positions intervalCorrection_;      // over the interval that ended at it
    Positions intervalCoarsestChange_;
    double appliedAlong_ = 0;  // the multiple of intervalCorrection_ added since the keyframe
    int sinceKeyframe_ = 0;
    double keyframeMove_ = 0;  // RMS of what the last keyframe's input steps moved
    double diagonal_ = 0;      // the rest mesh's bounding-box diagonal
};

}  // namespace boneless
