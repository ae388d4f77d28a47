#pragma once

// The output folder of an export: the files an export of a stem writes there, which of them a
// Boneless export wrote, and whose solve the folder holds. The solve and batch refuse, and the
// app's Export asks, before replacing what no export of this take wrote.

#include <optional>
#include <string>
#include <vector>

#include "boneless/TakeExport.h"

namespace boneless {

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

}  // namespace boneless
