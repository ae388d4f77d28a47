#pragma once

#include <memory>
#include <optional>
#include <vector>

#include "boneless/Alignment.h"
#include "boneless/C3dTake.h"
#include "boneless/Correspondence.h"
#include "boneless/Reconstruction.h"

namespace boneless {

struct TakeSolveOptions {
    double markerWeight = 100.0;  // soft-constraint weight (dimensionless)
    int continuationSteps = 4;    // the first frame is approached from the aligned rest pose
    // On a mesh at least twice the multiresolution solver's coarsest level (SolverOptions::
    // coarsestVertices, at least ten vertices per marker), the coarsest level leads: it follows
    // the take too, and each frame's solve on the full mesh starts from the last answer moved by
    // the coarsest level's change since the last frame, prolonged. The continuation to the first
    // frame runs on the coarsest level alone. Without it, a frame far from the last (a jump in
    // the timeline, a fast move) starts with its markers far off, and the first Gauss–Newton
    // step distorts what the next ones have to repair (README "Solver").
    bool coarsestLeads = true;
    double lowPassHz = 0.0;               // 0 = no filtering of the trajectories
    int calibrationFrame = -1;            // -1 = chosen automatically (see calibrate())
    std::optional<Similarity> alignment;  // overrides the automatic alignment
    // Constraints and offsets are set by the TakeSolver. The orientation guard is on: a real
    // take on a mesh that was not made for its actor strains the mesh, and slivers (the corners
    // of a mouth) and thin parts a marker pulls (fingers, toes) fold under the fold guard alone.
    SolverOptions solver = [] {
        SolverOptions s;
        s.orientationWeight = 100.0;
        return s;
    }();
};

// How well a solved frame meets its markers.
struct FrameReport {
    int frame = 0;
    int visibleMarkers = 0;
    double residualRmsMm = 0, residualMaxMm = 0;  // marker to its predicted position, mm
    int iterations = 0;                           // Gauss–Newton steps on the full mesh
    double milliseconds = 0;
};

// Turns a take into an animation of the rest mesh: aligns the take onto the mesh (a similarity
// applied to the take, never to the mesh, so the encoding's heights keep their meaning), filters
// the trajectories if asked, and solves frames in order, each warm-started from the previous one,
// with soft constraints that model each marker's offset from the skin. Missing markers drop out
// of their frame.
class TakeSolver {
  public:
    TakeSolver(const TriMesh& rest, const C3dTake& take, const Correspondence& map,
               TakeSolveOptions options = {});

    const Calibration& calibration() const { return calibration_; }
    int frameCount() const { return static_cast<int>(take_.frameCount()); }
    // The markers' targets at `frame` in mesh coordinates (K by 3, NaN rows where missing).
    Positions targets(int frame) const;
    // Solves `frame`, starting from the last frame solved (or by continuation from the rest pose
    // for the first). Never returns NaN: a frame that fails keeps the previous shape.
    Positions solve(int frame, FrameReport& report);
    // The energy solve(frame) minimises, at V (#V by 3): shape, fold guards and marker pull.
    double energy(int frame, const Positions& V) const { return solver_.energy(V, targets(frame)); }
    // Where each marker sits on the posed mesh V: its vertex plus its offset along the normal.
    Positions predictedMarkers(const Positions& V) const;

  private:
    // The first frame's starting pose: the rest pose aligned, then the continuation on the
    // coarsest level when it leads (see continuationSteps and coarsestLeads).
    SolveResult solveFirst(const Positions& targets);
    // Whether the coarsest level leads for these targets; (re)builds its solver for their
    // visible markers.
    bool coarsestLeadsFor(const Positions& targets);
    // V, the last answer, moved by the coarsest level's change from the last frame to `targets`
    // when it leads; V untouched when it does not.
    void leadFromLast(const Positions& targets, Positions& V);
    // How many of the coarsest level's markers `targets` (K by 3) has.
    int seenBy(const Positions& targets) const;
    // The coarsest level's answer to `targets` from `guess`, a pose of the full mesh.
    Positions solveCoarsest(const Positions& targets, const Positions& guess);

    TriMesh rest_;
    C3dTake take_;
    std::vector<std::size_t> points_;
    TakeSolveOptions options_;
    Calibration calibration_;
    Reconstruction solver_;
    // The coarsest level's solver (a marker missing from a frame must not shape the hierarchy,
    // so it is built for the visible markers, coarsestMarkers_), its last answer (a pose of the
    // full mesh) and the targets of the last frame solved.
    std::unique_ptr<Reconstruction> coarsest_;
    std::vector<int> coarsestMarkers_;
    std::optional<Positions> coarsestLast_;
    bool coarsestFailed_ = false;  // its hierarchy could not be made: the take goes without
    Positions previousTargets_;
    std::optional<Positions> previous_;
    double meshUnitsPerMm_ = 1.0;
};

}  // namespace boneless
