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
};

// Called after each frame is written; return false to stop (the frames written so far stay valid,
// and the sidecar records the take as incomplete).
using ExportProgress = std::function<bool(int done, int total, const FrameReport& last)>;

// The file stem outputs are named after: the group if one is given, else the mesh file's stem.
std::string exportStem(const ExportRequest& request);
// An OBJ sequence's file for take frame `frame`: "<stem>_0042.obj".
std::string objFrameFile(const std::string& stem, int frame);
// The frames of `stem`'s OBJ sequence that `outDir` holds, in no particular order.
std::vector<int> objFramesIn(const std::string& outDir, const std::string& stem);
// The files an export of `stem` writes that `outDir` already holds, whichever format and frames
// wrote them (its sidecar, a point cache or glb, the calibrated rest, OBJ frames in frame order):
// file names, not paths.
std::vector<std::string> exportFilesIn(const std::string& outDir, const std::string& stem);

// Those of exportFilesIn's files that an export wrote, as far as the folder shows: the Boneless
// sidecar, the files it names (its output, its OBJ frames within its "frame_range", its calibrated
// rest), and OBJs starting with the line a solve writes. Not another program's (or the user's own)
// file of an output's name, nor a point cache or glb that the sidecar does not name.
std::vector<std::string> exportFilesWrittenIn(const std::string& outDir, const std::string& stem);

// Whether the OBJ `path` starts with the "# Boneless: " line a solve writes (a frame, the
// calibrated rest).
bool objWrittenBySolve(const std::string& path);

// The files an export of `request` over the take frames [request.first, end) would replace in
// its folder that no Boneless export wrote, by name in the order exportFilesIn gives: an OBJ
// (a frame, the calibrated rest) that does not start with the "# Boneless: " line a solve
// writes (the demo's truth/, another tool's frames), a sidecar that is not a "boneless-solve"
// one, and a point cache or glb that no Boneless sidecar beside it records as its output. An
// earlier export's files, however many runs left them, are not listed, nor the files the
// folder's Boneless sidecar names as its outputs (its OBJ frames within its "frame_range", its
// calibrated rest) however damaged, nor the request's inputs (which exportTake refuses to
// replace, naming both).
std::vector<std::string> filesNoExportWrote(const ExportRequest& request, int end);

// Whether `a` and `b` name one file however each is spelled (relative, through "..", a symbolic or
// hard link); a path that does not exist yet is compared by where it would be.
bool sameFile(const std::string& a, const std::string& b);

// The solve of another take, or of other actors of the same take, that an export of `request`
// would replace: the folder's sidecar (<stem>.json) names another take, or the same take with
// other "subjects" than `subjects` (Correspondence::subjects of the map solved). `solve` refuses
// it unless --force, and the app's Export asks first: one shell loop over takes into one folder
// kept the last take's solve alone, in silence. A sidecar of the same take that names no subjects
// (written before 1 December 2026, or of a take without prefixes) is no other actor's.
struct OtherSolve {
    std::string sidecar;  // its path
    std::string c3d;      // the take it solved, as its sidecar names it
    bool sameTake = false;
    std::vector<std::string> subjects;  // the actors it animates, of the same take
    // Whose solve it is, as messages say it: "subject other of /lib/two.c3d", or
    // "/lib/walk_a.c3d, another take".
    std::string whose() const;
};
std::optional<OtherSolve> otherSolveIn(const ExportRequest& request,
                                       const std::vector<std::string>& subjects);
// Actors as messages name them: "subject walker", "subjects walker, other".
std::string subjectsText(const std::vector<std::string>& subjects);

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
// the body would be 17 cm tall: check its scale ..."), with its height along the guessed up axis,
// or, when the mesh is a body's size in that unit, that the take's markers make it ten or more
// times that ("the take's markers make the body 19 m tall, where the mesh is 1.9 m tall in m:
// check the take's units").
std::string meshScaleWarning(const TriMesh& rest, const Similarity& takeToMesh, double takeUnitToMm,
                             const Vec3& takeUp);

// The mesh axis ("+y", "-z", …) the take's vertical `takeUp` (C3dTake::vertical) maps onto.
std::string guessUpAxis(const Similarity& takeToMesh, const Vec3& takeUp);

// Where a glb's node puts the mesh: its guessed up axis (where `takeUp` goes) onto +Y, its
// guessed unit to metres.
GltfPlacement gltfPlacement(const Similarity& takeToMesh, double takeUnitToMm, const Vec3& takeUp);

}  // namespace boneless
