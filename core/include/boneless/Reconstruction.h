#pragma once

#include <memory>
#include <vector>

#include "boneless/ShapeEncoding.h"
#include "boneless/TriMesh.h"

namespace boneless {

class BlockSystem;
class IterativeSolver;

struct SolverOptions {
    // Hard: marker vertices are placed exactly on their targets. Soft: they are pulled there with
    // weight softWeight (dimensionless: the energy and the pull are both squared lengths).
    enum class Constraints { Hard, Soft };
    Constraints constraints = Constraints::Hard;
    double softWeight = 100.0;
    // The fold guard: weight of a weak as-rigid-as-possible term added to G (0 = the paper's energy
    // alone). G is blind to in-plane affine maps of flat and thin regions, mirror images included,
    // so without it thin parts fold; see README "Solver". 0.01 was the best of 0.001–0.1 on the
    // horse gallop at K = 20, 40, 80 (fewest flips and lowest error together).
    double rigidityWeight = 0.01;
    // The orientation guard (0 = off; the direct and multiresolution methods, whose coarsest level
    // it then solves by the direct method): a one-sided penalty on faces that shrink below
    // orientationThreshold of their rest area or turn over against their neighbourhood, with a
    // dimensionless weight (OrientationGuard.h). Folds the fold guard lets through (slivers, thin
    // parts pulled by a marker) cost this much more.
    double orientationWeight = 0;
    double orientationThreshold = 0.2;
    int maxIterations = 10;
    // Soft constraints only: how far each marker sits off the skin (mesh units, along the outward
    // normal of its vertex's ring, algorithm.md §4.3); empty = every marker on the skin.
    std::vector<double> markerOffsets;
    // Stop once an iteration lowers the energy by less than this fraction.
    double relativeTolerance = 1e-3;

    // How each Gauss–Newton step is solved; both minimise the same energy.
    //  Direct: a sparse Cholesky factorisation of the exact normal matrix per iteration (with
    //    the orientation guard on, the fold guard's exact Hessian near a minimum: README "Solver").
    //  Iterative: conjugate gradients on the same exact system, matrix-free, preconditioned by
    //    the rest pose's normal matrix (factorised once, in prepare()) turned by each vertex's
    //    fitted rotation; no factorisation per frame, so it suits large meshes and warm starts
    //    (or by the last factorisation of a step's own matrix: Preconditioner::LastFactor).
    //  Multiresolution: a hierarchy of coarser meshes (algorithm.md §1.6); the coarsest is
    //    solved to convergence, each finer level starts from the prolonged change, and the input
    //    takes correctionSteps cheap steps, then fineIterations Gauss–Newton steps by conjugate
    //    gradients. Made for sequences: each frame is warm-started from the last at every level.
    enum class Method { Direct, Iterative, Multiresolution, LocalGlobal };
    Method method = Method::Direct;
    // Multiresolution only: the coarsest level's size (at least ten vertices per marker), and
    // the Gauss–Newton steps on each finer level per frame.
    int coarsestVertices = 2000;
    int fineIterations = 1;
    // Multiresolution only: the coarsest level's Gauss–Newton steps per frame at most (it stops
    // sooner once converged, relative decrease below 1e-4: 3 steps a frame on the bench's bend;
    // soft markers with offsets take more). A preview can afford fewer.
    int coarsestIterations = 10;
    // Multiresolution only: cheap steps on the input level per frame, before the fineIterations
    // ones. Each is a block-Jacobi step (it removes the error of the finest scale, which no
    // coarser level sees), then a step along the coarsest level's Gauss–Newton answer to the
    // input's gradient restricted to it and prolonged back (the smooth error, where the coarse
    // and fine energies' minima differ), each with a line search on the input's energy.
    int correctionSteps = 0;
    // Iterative only: stop conjugate gradients once the residual is this fraction of the
    // gradient, or after this many iterations (per Gauss–Newton step).
    double cgTolerance = 1e-2;
    int maxCgIterations = 20;
    // Iterative only: take the step with a factorisation when conjugate gradients miss their
    // tolerance (robust on poses far from the last, costly: off for real-time use).
    bool directFallback = true;
    // Iterative only: those factorised steps use the matrix conjugate gradients solve (the fold
    // guard's exact Hessian once a step has been taken whole, each vertex's share clamped to its
    // positive part where the sum is indefinite) instead of the Gauss–Newton matrix. They then
    // reach the energy's minimum instead of crawling towards it, which is what a reference
    // answer needs; without the orientation guard that minimum flips more faces than stopping
    // early (eval, horse gallop at 40 markers, multiresolution: 470 faces in the worst frame
    // against 252, RMS worst 1.638 against 1.610 %), so solves for users leave it off.
    bool exactFallback = false;
    // Iterative only: which rest-pose matrix is factorised for the preconditioner. Blocks: the
    // exact 3×3-block normal matrix (fewest iterations, slowest to factorise and apply).
    // Scalar: its block traces, one unknown per vertex applied to x, y and z at once (a ninth of
    // the factor, a fraction of the time per application, more iterations).
    // LastFactor: no rest matrix; the last factorisation of a step's own matrix (the one its
    // conjugate gradients solve: the fold guard's exact Hessian once a step has been taken
    // whole, clamped where indefinite; the Gauss–Newton matrix before), made on the first step
    // and whenever conjugate gradients with the one before miss their tolerance within three
    // quarters of a factorisation's cost (at least 4 iterations, at most maxCgIterations). It
    // implies directFallback and exactFallback. Where a pose bends, the rest matrix turned by
    // the rotations misses how the bend softens the energy, and a pose's own matrix changes
    // slowly from frame to frame. Koala bend: frame 41's step, 20 iterations with the rest
    // matrix's traces leave 0.038 % of the diagonal; frame 45's, 5 with the factor made for
    // frame 41's step leave 0.002 %. Memory: a factor of a 100K-face mesh's matrix (0.9 GB).
    // LumpedScalar: Scalar's matrix with the vertex pairs that share no edge moved onto the
    // diagonal, each contribution as its absolute value (at least Scalar's matrix, so positive
    // definite when that is): a factor a quarter the size (koala, 100K faces: factorised in 93
    // against 332 ms) for more iterations. The multiresolution method's input level takes it
    // from 10,000 vertices and Scalar below, whichever of the two is asked for.
    enum class Preconditioner { Blocks, Scalar, LastFactor, LumpedScalar };
    Preconditioner preconditioner = Preconditioner::Scalar;
    // LumpedScalar: the matrix is also cut into this many diagonal blocks, equal ranges of vertex
    // indices, with the pairs between blocks lumped like the dropped ones; the blocks are
    // factorised and solved on the cores at once. It pays where nearby vertices have nearby
    // indices, as in the spatial order the multiresolution method solves a large input in (it
    // takes one block per core there). Koala's input, two blocks: 921 of its 150,000 edges
    // lumped, factors of 0.58M and 0.57M entries against 1.40M.
    int lumpedBlocks = 1;
    // Iterative and the multiresolution method's input level, for sequences (experimental): the
    // motions of the last recycledMotions frames solved in full are kept, and a frame's first
    // step starts from the quadratic model's minimiser over their span. With refreshEvery > 1
    // only every refreshEvery-th frame is solved in full; the others take that one step alone
    // (a few products with the Hessian, no conjugate gradients). What the input level corrects
    // from frame to frame is a drift in the softest part of the spectrum, which conjugate
    // gradients are slowest at and which changes little between frames (README, "Methods and
    // speed"). Koala bend, every other frame projected: a mean of 401 ms a frame instead of 681
    // and 0.122 % from the converged answers instead of 0.163 %; every third frame or every
    // fourth, measured to lose the accuracy (0.38 %, 0.46 %).
    int recycledMotions = 0;
    int refreshEvery = 1;
    // Multiresolution, for sequences (experimental): with keyframeEvery > 1 only every
    // keyframeEvery-th warm-started frame takes steps on the input level (a keyframe). A frame
    // between keyframes adds to its prolongation the input level's correction over the last
    // keyframe interval (the answer's change minus the prolonged change), scaled by how far the
    // coarsest level has moved along that interval's coarsest change (least squares): it costs
    // what prolongation alone costs, and reports NaN energies like it. What the input level
    // corrects from frame to frame is smooth in the motion (README, "Methods and speed"). A
    // jump (a guess that is not the last answer) makes the next frame a keyframe. Koala bend,
    // last factor, every third frame a keyframe: a median of 22 ms a frame, 10 of 13 checked
    // frames within 0.1 % of their minima, but up to 0.22 % where the bend slows down.
    int keyframeEvery = 1;
    // A keyframe whose input steps moved the mesh further than this (RMS, as a fraction of the
    // bounding-box diagonal) makes the next frame a keyframe too: its start, the last interval's
    // extrapolation, was that far off, so the interval no longer predicts the next frames (the
    // bend's fine detail snaps between frames 30 and 31; the coarsest level's motion shows
    // nothing). An a-posteriori test: the frames between the snap and that keyframe are
    // already given. Koala bend, frames 30–40, keyframes converged: 0.25 % → under 0.06 %.
    double keyframeTolerance = 3e-4;
    // A frame whose coarsest level has moved, since the keyframe, more than this share of its
    // move off the last interval's coarsest change is a keyframe: the motion has turned, and the
    // interval's correction belongs to another motion. An a-priori test, from the coarsest level
    // alone. Koala bend: 0.0014–0.082 up to frame 49; at frame 50 the coarsest level snaps
    // (its 10 steps, 0.615 off), and that frame came to 0.171 % from its minimum when extrapolated.
    double keyframeTurn = 0.2;
};

struct SolveReport {
    int iterations = 0;
    // Conjugate-gradient steps over all iterations (direct method: those run with an earlier
    // step's factor, including tries that ended in a factorisation).
    int linearIterations = 0;
    // Steps solved by factorising their matrix (iterative method: that fell back to one).
    int directSteps = 0;
    // At the initial guess (markers already on their targets if hard) and at the answer. NaN, and
    // energies empty, when the solve takes no step on the input mesh (Multiresolution with
    // fineIterations = correctionSteps = 0, or a frame between keyframes): evaluating the input's
    // energy would cost as much as the rest of such a frame; Reconstruction::energy() gives it.
    double energyBefore = 0;
    double energyAfter = 0;
    double milliseconds = 0;
    // The relative-decrease test was met, or (direct method) the step became too small to see.
    bool converged = false;
    std::vector<double> energies;  // after each accepted iteration, energies[0] = energyBefore
};

struct SolveResult {
    Positions V;  // #V by 3
    SolveReport report;
};

// "Prepare once, solve per frame" (libigl's precomputation/solve; CGAL's preprocess/deform):
//   Reconstruction r;  r.prepare(rest, markers);
//   for each frame: result = r.solve(targets, &previous.V);
// It minimises G(V) = ½ Σ_i |v_i − F_i(V)|² (plus the fold guard) over the free vertices by
// Gauss–Newton with the exact Jacobian and a backtracking line search, so that the energy never
// goes up; SolverOptions::method picks how each step's linear system is solved.
class Reconstruction {
  public:
    Reconstruction();
    ~Reconstruction();
    Reconstruction(Reconstruction&&) noexcept;
    Reconstruction& operator=(Reconstruction&&) noexcept;

    // markerVertices: K distinct vertex ids, the k-th marker drives vertex markerVertices[k].
    void prepare(const TriMesh& rest, std::vector<int> markerVertices, SolverOptions options = {});

    // targets: K by 3; a row with a NaN is a missing marker, whose vertex is then solved for like
    // any other. guess: #V by 3 (for instance the previous frame's result); without one the rest
    // pose is moved rigidly onto the markers first.
    SolveResult solve(const Positions& targets, const Positions* guess = nullptr);

    // The energy the solver minimises, for the given targets (soft term included when soft).
    double energy(const Positions& V, const Positions& targets) const;

    const TriMesh& rest() const;
    const ShapeEncoding& encoding() const;
    const std::vector<int>& markerVertices() const;
    const SolverOptions& options() const;
    void setOptions(const SolverOptions& options);

  private:
    struct Impl;
    friend class IterativeSolver;
    friend class MultiresSolver;
    std::unique_ptr<Impl> impl_;
};

// The rigid motion (rotation, translation) that best maps from[k] onto to[k], skipping rows with a
// NaN in either; identity when fewer than three rows remain.
struct RigidMotion {
    Mat3 R = Mat3::Identity();
    Vec3 t = Vec3::Zero();
    Vec3 apply(const Vec3& x) const { return R * x + t; }
};
RigidMotion fitRigidMotion(const Positions& from, const Positions& to);

}  // namespace boneless
