#pragma once

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "boneless/C3dTake.h"
#include "boneless/Error.h"
#include "boneless/TakeExport.h"

// Thrown by runTakeJob when Ctrl-C or SIGTERM stopped it: a batch stops there rather than going on,
// and the exit status is a shell's for the signal, 128 + `signal` (130, 143).
struct TakeJobInterrupted : boneless::Error {
    TakeJobInterrupted(const std::string& message, int signal) : Error(message), signal(signal) {}
    int signal;
};

// While one is alive, Ctrl-C (SIGINT) and SIGTERM (what Slurm, timeout and systemd send) are
// recorded instead of killing the process: a take stops after the frames being solved (killed
// outright, a run left its spool file behind and no sidecar), and a batch between takes still
// sums up. Nested ones share the outermost's record.
class StopSignals {
  public:
    StopSignals();
    ~StopSignals();
    StopSignals(const StopSignals&) = delete;
    StopSignals& operator=(const StopSignals&) = delete;
    static int received();  // the signal, 0 while none has come
    // Throws TakeJobInterrupted ("interrupted " + when) once a signal has come.
    static void throwIfReceived(
        const std::string& when = "before any frame was written: the output folder is as it was");

  private:
    void (*sigint_)(int) = nullptr;
    void (*sigterm_)(int) = nullptr;
};

// One take solved into one output folder: what `solve` runs once and `batch` runs per manifest
// entry, so both read their inputs, align, solve and write the same way.
struct TakeJob {
    std::string mesh, group, c3d, map, out, format = "obj", frames;
    bool writeCalibratedRest = false;
    // Replace files of the outputs' names in `out` that no Boneless export wrote (the demo's
    // truth/, another tool's frames), and the solve of another take: without it, such files
    // refuse the job before it solves.
    bool force = false;
    // Replace the solve of another take that `out` holds without `force`: batch's, which refuses
    // two entries into one out before solving and solves an entry whose take changed again.
    bool replacesOtherTakes = false;
    // The solve options given (core's table, TakeOptionsJson: flags and manifest keys alike);
    // the others keep TakeSolveOptions' defaults.
    nlohmann::json options = nlohmann::json::object();
};

// The solver and format options of `solve` (everything but the input and output paths): one
// flag per option of core's table, named as its JSON key.
void addTakeJobOptions(CLI::App* command, TakeJob& job);

// Checks the map against the mesh read from `meshPath` (Correspondence::checkMesh), and when the
// map was made on another OBJ group than `group`, says which --group to open the mesh with (with
// `keys`, the "group" of a manifest's entry, as batch reads it).
void checkMapFitsMesh(const boneless::Correspondence& map, const boneless::TriMesh& mesh,
                      const std::string& meshPath, const std::string& group, bool keys = false);

// A take whose markers span no body in the units it states (C3dTake::markerSpan) is refused before
// the mesh is read or the solver prepared: solved, CMU 85_02 in metres under "mm" aligned "at
// 10 mm" hundreds of metres off after 250 s. `outcome` says what was not done ("nothing was
// solved"); the fix offered first is the take_units option, as a flag or, with `keys`, as a
// manifest's key.
void refuseDoubtfulUnits(const boneless::C3dTake& take, const std::string& outcome,
                         bool keys = false);

// setTakeUnits with the take_units of `options` (the flags given, as TakeJob::options), named as
// --take-units; nothing for "file".
void applyTakeUnits(boneless::C3dTake& take, const nlohmann::json& options);
// How the option is named: --take-units, or with `keys` "take_units" (a manifest's key).
std::string takeUnitsName(bool keys);
// The take's units as messages give them: "mm", or "m (--take-units; the file says mm)" when
// set otherwise than by the file.
std::string unitsText(const boneless::C3dTake& take);

// Where the job's sidecar goes: OUT/<stem>.json.
std::string takeJobSidecar(const TakeJob& job);

// Reads the inputs, solves and writes. Progress and the mesh's warnings go to stderr unless
// `quiet`; with `meshWarnings`, the warnings go there instead. The take's warnings (a truncated
// file, ...) go to stderr, quiet or not, or to `takeWarnings` when given; the sidecar records them
// too. A map with entries `map suggest` marked for review is solved as it is, with a warning
// naming them, on stderr, quiet or not, or in `mapWarnings` when given, as are the map's own
// warnings (a version 1 entry's "face"). A note on the job's frames
// (a range cut at the take's end), and one on an earlier export's files left beside the outputs,
// go to stderr as solve's "note: ...", or to `takeNotes` when given, in the same words; so does
// the warning of frames that show no marker, to `takeWarnings`. Ctrl-C or SIGTERM stops
// after the frames being solved and throws TakeJobInterrupted (the sidecar records the take as
// incomplete, and solving it again starts from its first frame). Throws Error naming the file or
// option for bad input.
boneless::ExportResult runTakeJob(const TakeJob& job, bool quiet,
                                  std::vector<std::string>* meshWarnings = nullptr,
                                  std::vector<std::string>* takeWarnings = nullptr,
                                  std::vector<std::string>* mapWarnings = nullptr,
                                  std::vector<std::string>* takeNotes = nullptr);
