#pragma once

#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <vector>

#include "boneless/ActorCalibration.h"
#include "boneless/Alignment.h"
#include "boneless/C3dTake.h"
#include "boneless/Correspondence.h"
#include "boneless/MarkerTrack.h"
#include "boneless/MeshTopology.h"
#include "boneless/Reconstruction.h"

namespace boneless {

class C3dFrameReader;
class DentGauge;

struct TakeSolveOptions {
    double markerWeight = 100.0;  // soft-constraint weight (dimensionless)
    double lowPassHz = 0.0;       // 0 = no filtering of the trajectories
    // A marker missing for at most this long (seconds) is placed on its trajectory across the
    // gap: each frame is solved from its own markers, so without this a limb whose markers are
    // all occluded would fall back to its rest shape. 0 = off. Longer gaps stay missing.
    double fillGapSeconds = 0.2;
    int calibrationFrame = -1;  // -1 = chosen automatically (see calibrate())
    // The mesh's up (a signed coordinate axis), where the take's vertical goes; unset: the axis
    // nearest where the alignment at the calibration frame puts it, wrong for an actor lying there.
    std::optional<Vec3> meshUp;
    std::optional<Similarity> alignment;  // overrides the automatic alignment
    // The units the take's coordinates are in: "file" (its POINT:UNITS) or a c3dUnitSymbols()
    // one, applied where the take is read (setTakeUnits); the export checks they were.
    std::string takeUnits = "file";
    // Shape: the rest mesh is first fitted to the actor at the calibration frame, and every frame
    // is solved against that calibrated rest (see docs/calibration.md). None: against the rest.
    CalibrateMode calibrate = CalibrateMode::Shape;
    // Overrides the fit (#V by 3): a project's saved calibrated rest, or another worker's.
    std::optional<Positions> calibratedRest;
    // Constraints and offsets are set by the TakeSolver. With the exact method, each frame's
    // local/global answer is refined, with the orientation guard on: a real take on a mesh that
    // was not made for its actor strains the mesh, and slivers (the corners of a mouth) and thin
    // parts a marker pulls (fingers, toes) fold under the fold guard alone.
    SolverOptions solver = [] {
        SolverOptions s;
        s.orientationGuard = 100.0;
        return s;
    }();
};

// How well a solved frame meets its markers.
struct FrameReport {
    int frame = 0;
    int visibleMarkers = 0;
    double residualRmsMm = 0, residualMaxMm = 0;  // marker to its predicted position, mm
    int iterations = 0;                           // iterations on the full mesh
    int foldedFaces = -1;  // as SolveReport::foldedFaces (−1: not counted by the method)
    // The worst marker's dent: around each marker, the surface's mean curvature posed over its
    // mean curvature at rest (DentGauge; 1 at rest).
    double dentRatio = 1.0;
    bool stopped = false;  // as SolveReport::stopped: the positions are not an answer
    // The frame whose pose this one holds, since it shows no marker to pull to (−1: none held).
    int heldFrom = -1;
    double milliseconds = 0;
};

// The map's markers as the solver takes them, one per entry in order.
std::vector<SurfacePoint> surfacePoints(const Correspondence& map);
SurfacePoint surfacePoint(const MarkerMapping& entry);  // one entry's

// Turns a take into an animation of the rest mesh: aligns the take onto the mesh (a similarity
// applied to the take, never to the mesh, so the encoding's heights keep their meaning), filters
// the trajectories if asked, fits the rest mesh to the actor at the calibration frame (unless
// told not to), and solves any frame from its own markers, with soft constraints
// that model each marker's offset from the skin. Missing markers drop out of their frame. A
// frame's answer is the same whatever frames were solved before it, in any order.
class TakeSolver {
  public:
    TakeSolver(const TriMesh& rest, const C3dTake& take, const Correspondence& map,
               TakeSolveOptions options = {});
    // The same for a take streamed from its file: memory does not grow with the take's length,
    // and every frame's answer is the one the take read whole gives.
    TakeSolver(const TriMesh& rest, const C3dFrameReader& take, const Correspondence& map,
               TakeSolveOptions options = {});
    // Another solver of the same take and map as `same`, sharing its trajectories (read and
    // filtered once): for workers. options.lowPassHz is `same`'s.
    TakeSolver(const TriMesh& rest, const TakeSolver& same, const Correspondence& map,
               TakeSolveOptions options);
    ~TakeSolver();
    // How far about each marker's point the dent ratio looks (mm): past the one ring of a
    // 13K-vertex human, whose edges are about 15 mm.
    static constexpr double kDentRadiusMm = 25.0;

    const Calibration& calibration() const { return calibration_; }
    // What frames are solved against: the calibrated rest when calibrating, else the rest mesh.
    const TriMesh& rest() const { return rest_; }
    int frameCount() const { return static_cast<int>(track_->frames()); }
    // The markers' targets at `frame` in mesh coordinates (K by 3, NaN rows where missing); with
    // `filled`, a marker in a short gap has its place on its trajectory (what solve() pulls to).
    Positions targets(int frame, bool filled = false) const;
    // Solves `frame`. Never returns NaN: a frame that cannot be solved (too few markers) gives
    // the rest pose moved rigidly onto what markers it has. stop: as Reconstruction::solve's.
    Positions solve(int frame, FrameReport& report, const std::atomic<bool>* stop = nullptr);
    // The local/global energy at V (#V by 3) for the frame's markers: shape, ARAP term and
    // marker pull.
    double energy(int frame, const Positions& V) const { return solver_.energy(V, targets(frame)); }
    // Where each marker sits on the posed mesh V: its surface point plus its offset along its
    // rest normal, turned with the surface around it.
    Positions predictedMarkers(const Positions& V) const;

  private:
    void prepare(const Correspondence& map);
    // The track's markers at `frame` (K by 3, NaN rows where missing), and with `filled` the
    // short gaps filled, read through a window of frames about it.
    Positions trackFrame(int frame, bool filled) const;
    // The markers at `frame` as recorded, before any low-pass filter, in mesh coordinates.
    Positions recorded(int frame) const;

    TriMesh rest_;
    std::shared_ptr<const MarkerTrack> track_;
    mutable std::mutex windowMutex_;
    mutable C3dSamples window_;  // frames [windowFirst_, windowFirst_ + window_.frames())
    mutable std::size_t windowFirst_ = 0;
    TakeSolveOptions options_;
    Calibration calibration_;
    Reconstruction solver_;                  // local/global
    std::unique_ptr<Reconstruction> exact_;  // the exact method, when asked for
    double meshUnitsPerMm_ = 1.0;
    std::unique_ptr<MeshTopology> topology_;  // the rest's, for the alignment and dent gauge
    std::unique_ptr<ShapeEncoding> encoding_;
    std::unique_ptr<DentGauge> dents_;
};

}  // namespace boneless
