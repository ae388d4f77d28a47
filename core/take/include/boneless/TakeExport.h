#pragma once

#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "boneless/C3dTake.h"
#include "boneless/Correspondence.h"
#include "boneless/ExportFormat.h"
#include "boneless/GltfWriter.h"
#include "boneless/TakeSolver.h"
#include "boneless/TriMesh.h"

namespace boneless {

class C3dFrameReader;

// What `boneless-cli solve` and the application's export both write, so that the two produce the
// same files: DIR/<stem>_<frame:04>.obj (input vertex order, same faces) or one DIR/<stem>.pc2,
// .mdd or .glb, plus the sidecar DIR/<stem>.json (fps, frame range, whether the run completed,
// units, up axis, sources, alignment, options (TakeOptionsJson), per-frame residuals). Every file
// appears atomically, the sidecar last.
struct ExportRequest {
    // As the user named them; recorded in the sidecar and the OBJ comments.
    std::string meshPath, group, c3dPath, mapPath;
    std::string outDir;
    ExportFormat format = ExportFormat::Obj;
    int first = 0;  // 0-based take frames [first, end); end < 0 = to the take's end
    int end = -1;
    TakeSolveOptions options;
    // The rest these very inputs and options fit, fitted already (the app's solver holds it): the
    // solve starts from it rather than fitting it again. Unlike options.calibratedRest, a rest the
    // user gave, it leaves the sidecar's calibration.overridden false.
    std::optional<Positions> fittedRest;
    // Also write DIR/<stem>_calibrated_rest.obj, the rest fitted to the actor (input vertex
    // order and faces), and name it in the sidecar.
    bool writeCalibratedRest = false;
};

struct ExportResult {
    int first = 0;
    int framesWritten = 0;
    bool cancelled = false;
    // How many solvers solved frames at once, each prepared on its own (one per core, as memory
    // allows, and one alone for a take too short to repay preparing another).
    int workers = 0;
    std::string sidecarPath;
    // Runs of frames [first, last] that show no marker and hold a neighbour's pose (as the
    // sidecar's summary "frames_held" lists them).
    std::vector<std::pair<int, int>> held;
    // Stopped once the solver was prepared, before anything was written: the folder is as it
    // was, an earlier export in it whole.
    bool wroteNothing() const { return cancelled && sidecarPath.empty(); }
};

// Called once the solver is prepared, with done 0, before anything is written (false: stop, the
// folder as it was), then after each frame is written; return false to stop (the frames written
// so far stay valid, and the sidecar records the take as incomplete).
using ExportProgress = std::function<bool(int done, int total, const FrameReport& last)>;

// Told the alignment once it is found, before the first frame is solved.
using ExportCalibrated = std::function<void(const Calibration&)>;

// Solves and writes the frames. Throws Error naming the file or option for bad input, and, before
// solving, naming both files when an output (the sidecar, the frames, the calibrated rest) would
// replace one of the request's inputs.
ExportResult exportTake(const TriMesh& mesh, const C3dTake& take, const Correspondence& map,
                        const ExportRequest& request, const ExportProgress& progress = {},
                        const ExportCalibrated& calibrated = {});
// The same for a take streamed from its file (what `boneless-cli solve` does): memory does not
// grow with the take's length, and the files are the ones the take read whole gives.
ExportResult exportTake(const TriMesh& mesh, const C3dFrameReader& take, const Correspondence& map,
                        const ExportRequest& request, const ExportProgress& progress = {},
                        const ExportCalibrated& calibrated = {});

// What the sidecar's "source_fingerprints" records of an input file, so that a later run can tell
// it changed since it was solved: with `contents`, its size and a hash of its bytes (FNV-1a, 64
// bits); else its size and modification time, for files too large to read twice (a take).
// "unreadable" when it cannot be read.
std::string fileFingerprint(const std::string& path, bool contents);

// The nearest of mm/cm/dm/m to the mesh's unit, from how many mesh units a millimetre is.
const char* guessMeshUnits(double meshUnitsPerMm);

// "" when the mesh, read in its guessed unit, is about the size of the actor the take aligns onto
// it; else a warning that no common unit makes it a body's size ("mesh units look like m, but
// the body would be 17 cm tall: check the mesh's scale ..."), with its height along the guessed up
// axis, or, when the mesh is a body's size in that unit, that the take's markers make it ten or
// more times that ("the take's markers make the body 19 m tall, where the mesh is 1.9 m tall in m:
// check the take's units").
std::string meshScaleWarning(const TriMesh& rest, const Similarity& takeToMesh, double takeUnitToMm,
                             const Vec3& takeUp);

// The mesh axis ("+y", "-z", …) the take's vertical `takeUp` (C3dTake::vertical) maps onto.
std::string guessUpAxis(const Similarity& takeToMesh, const Vec3& takeUp);

// Where a glb's node puts the mesh: its guessed up axis (where `takeUp` goes) onto +Y, its
// guessed unit to metres.
GltfPlacement gltfPlacement(const Similarity& takeToMesh, double takeUnitToMm, const Vec3& takeUp);

}  // namespace boneless
