#pragma once

#include <atomic>
#include <memory>
#include <string>
#include <vector>

#include "boneless/RigidFit.h"
#include "boneless/ShapeEncoding.h"
#include "boneless/TriMesh.h"

namespace boneless {

// A point of the mesh surface where a marker sits: a vertex, or a point of a face by barycentric
// coordinates of its corners.
struct SurfacePoint {
    int vertex = -1;  // the point itself when face < 0; otherwise the corner nearest the point
    int face = -1;
    Vec3 barycentric = Vec3(1, 0, 0);
};

// The point's position in V (its vertex, or the barycentric mix of its face's corners).
Vec3 surfacePosition(const TriMesh& mesh, const Positions& V, const SurfacePoint& p);
Vec3 surfacePosition(const Faces& F, const Positions& V, const SurfacePoint& p);  // F: #F by 3
// The point of face `face` (a row of F) nearest x, as V poses the face (#V by 3): its
// barycentric coordinates, and its vertex the corner nearest x. A click's hit on a drawn
// triangle names the same point of the surface in any pose.
SurfacePoint surfacePointAt(const Faces& F, const Positions& V, int face, const Vec3& x);
// The point's rest normal: its corners' ring normals mixed barycentrically, normalised (zero
// when none of them has a ring).
Vec3 surfaceNormal(const TriMesh& mesh, const ShapeEncoding& encoding, const SurfacePoint& p);
// The vertices within `radius` of the point (straight-line distance in the rest pose), reached
// over edges through such vertices from its corners, which are always in.
std::vector<int> surfaceDisk(const TriMesh& mesh, const MeshTopology& topology,
                             const SurfacePoint& p, double radius);

// The connected components of the mesh that hold none of the marker vertices, when some do (0
// when every one does, or none): Reconstruction solves the others and carries each of these
// rigidly with the part of them nearest to it at rest (eyes and teeth with the head).
int componentsWithoutMarkers(const TriMesh& mesh, const std::vector<int>& markerVertices);

// What a caller chooses, one line each with its units. Users meet these under one name (core's
// TakeOptionsJson: the JSON key and CLI flag in brackets); docs/solver.md says why each exists.
struct SolverOptions {
    // [solver] LocalGlobal: each frame from its own markers (coarse level from the rest pose moved
    // rigidly onto them, local/global iterations on one factorisation, folds repaired locally;
    // fast). Exact: Gauss–Newton on the seed energy with both guards, from a guess (a take's is
    // its LocalGlobal answer): the energy's minimum, slower.
    enum class Method { LocalGlobal, Exact };
    Method method = Method::LocalGlobal;
    // Hard: marker vertices are placed on their targets (eval). Soft: pulled there (takes).
    enum class Constraints { Hard, Soft };
    Constraints constraints = Constraints::Hard;
    double markerWeight = 100.0;  // [marker_weight] soft only: the pull (dimensionless)
    // Soft only: each marker's distance off the skin, along its rest normal (mesh units).
    std::vector<double> markerOffsets;

    // Exact only.
    int maxIterations = 10;  // [max_iterations] Gauss–Newton steps per frame, at most
    // [relative_tolerance] a frame stops once a step lowers its energy by less than this fraction
    // of it (0: it runs until max_iterations, or until no step lowers the energy).
    double relativeTolerance = 1e-3;
    // [fold_guard] weight of an ARAP term that keeps flat, thin parts from folding, relative to
    // the shape term (dimensionless; 0 = off).
    double foldGuard = 0.01;
    // [orientation_guard] weight of a penalty on faces below 1/5 of their rest area or turned,
    // relative to the shape term (dimensionless; 0 = off).
    double orientationGuard = 0;
};

// The method's name everywhere a user meets it (--solver, the "solver" key): "local-global",
// "exact"; parseMethod() takes those back (false for anything else).
const char* methodName(SolverOptions::Method method);
bool parseMethod(const std::string& name, SolverOptions::Method& method);

struct SolveReport {
    int iterations = 0;       // on the input mesh
    double milliseconds = 0;  // this solve() call, wall clock; the preparation is not in it
    // The last step moved no vertex by more than 1e-7 of the bounding-box diagonal, or (Exact)
    // the relative-decrease test was met.
    bool converged = false;
    // The caller's stop flag was raised: the solve returned early and its positions are not an
    // answer.
    bool stopped = false;
    // LocalGlobal only (−1 otherwise): faces the answer leaves folded over against their own
    // neighbourhood (Metrics' foldedFaces, judged in each vertex's whole ring), on the solved
    // components: a carried one moves rigidly and cannot fold.
    int foldedFaces = -1;
    // Exact only (NaN and empty for LocalGlobal): the energy at the guess and at the answer, and
    // after each accepted step (energies[0] = energyBefore); the steps that factorised their
    // matrix, and the conjugate-gradient iterations of the steps solved with an earlier step's
    // factor as a preconditioner.
    double energyBefore = 0;
    double energyAfter = 0;
    std::vector<double> energies;
    int directSteps = 0;
    int linearIterations = 0;
};

struct SolveResult {
    Positions V;  // #V by 3
    SolveReport report;
};

// "Prepare once, solve per frame" (libigl's precomputation/solve; CGAL's preprocess/deform):
//   Reconstruction r;  r.prepare(rest, markers);
//   for each frame: result = r.solve(targets);
// Every vertex keeps its shape relative to its one-ring (Kraevoy & Sheffer's encoding) while the
// marker vertices go where the markers are; SolverOptions::method says how. A component with no
// marker is not solved: it follows the nearest marked part rigidly (componentsWithoutMarkers).
class Reconstruction {
  public:
    Reconstruction();
    ~Reconstruction();
    Reconstruction(Reconstruction&&) noexcept;
    Reconstruction& operator=(Reconstruction&&) noexcept;

    // The expensive call, once per mesh and marker set: shape encoding, coarse level and one
    // sparse factorisation (0.4 s on a 100K-face mesh, docs/benchmarks.md). markerVertices: K
    // distinct vertex ids, the k-th marker drives vertex markerVertices[k]. Throws SolverError
    // naming the marker for an id out of range or carried twice, and for offsets or face points
    // with hard constraints.
    void prepare(const TriMesh& rest, std::vector<int> markerVertices, SolverOptions options = {});
    // The same with each marker at a surface point (their vertices distinct). The exact method
    // pulls each point's vertex.
    void prepare(const TriMesh& rest, std::vector<SurfacePoint> markers,
                 SolverOptions options = {});

    // Per frame (LocalGlobal: tens of ms on a 100K-face mesh; Exact: seconds). targets: K by 3, in
    // the rest mesh's units; a row with a NaN is a missing marker, whose vertex is then solved for
    // like any other. guess (Exact only; LocalGlobal needs none): #V by 3, where Gauss–Newton
    // starts; without one, the rest pose moved rigidly onto the markers. stop (optional): read
    // between iterations; once true, the solve returns at once with report.stopped (for a caller
    // whose request has been superseded, such as a scrub that moved on). Throws SolverError before
    // prepare(), or when targets is not K rows or guess not #V rows.
    SolveResult solve(const Positions& targets, const Positions* guess = nullptr,
                      const std::atomic<bool>* stop = nullptr);

    // The energy the method minimises at V, for the given targets (soft term included when soft;
    // LocalGlobal: its global step's, for rotations fitted to V).
    double energy(const Positions& V, const Positions& targets) const;

    const TriMesh& rest() const;
    const ShapeEncoding& encoding() const;
    const std::vector<int>& markerVertices() const;  // each marker's (nearest) vertex
    // Where each marker sits on the pose V (K by 3): on its surface, plus its offset along its
    // rest normal turned as the surface around it turned.
    Positions markerPositions(const Positions& V) const;
    const SolverOptions& options() const;
    // Cheap for the exact method's knobs and the offsets; prepares again (expensive) when the
    // method, the constraints or LocalGlobal's marker weight change.
    void setOptions(const SolverOptions& options);

  private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
};

}  // namespace boneless
