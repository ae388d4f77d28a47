#pragma once

#include <cstdio>
#include <functional>
#include <string>

namespace boneless {

// Where a writer puts `path` before renaming it into place: `<path>.tmp<pid>`, beside it (a
// rename only replaces a file atomically on its own disk). A process that is killed or loses its
// machine leaves that file, so this first removes the `<path>.tmp<pid>` and
// `<path>.frames.tmp<pid>` (the frames spool of earlier versions) whose process `pid` no longer
// runs. A running export's temporary, for this path too, and any other file are left alone.
std::string temporaryFor(const std::string& path);

// Removes from `folder` the temporaries killed writers left of the outputs `ours` accepts (by
// file name: "walker.pc2"): each `<output>.tmp<pid>` and `<output>.frames.tmp<pid>` that is a
// regular file and whose process `pid` no longer runs on this machine. A running writer's
// temporary, and any other file, are left alone. Only for a caller that holds the outputs' lock:
// a writer on another machine sharing the folder is not known to be gone.
void removeStaleTemporariesIn(const std::string& folder,
                              const std::function<bool(const std::string& output)>& ours);

// A spool for frames that are copied into `path` at the end, opened for reading and writing: a
// file beside `path` (on its disk, not /tmp's, which may be too small) that has no name, so
// nothing is left behind whatever ends the process. Removes the stale temporaries of `path` as
// temporaryFor does, freeing their disk before a long export. Throws Error naming `path`.
std::FILE* openSpoolBeside(const std::string& path);

// Formats whose header holds the frame count before the frames (MDD, glb) spool the frames to a
// file first, and the solve's sidecar its per-frame figures. This writes `head`, the spool's bytes
// and `tail` to temporaryFor(`path`) and renames it into place; the spool is closed whatever
// happens. Throws Error naming `path` when a write fails.
void writeSpooled(const std::string& path, const std::string& head, std::FILE* spool,
                  const std::string& tail);
// The same with a tail too large to hold (a glb's N × N weight keys): `writeTail` writes it to
// the open file, returning false when a write fails.
void writeSpooled(const std::string& path, const std::string& head, std::FILE* spool,
                  const std::function<bool(std::FILE*)>& writeTail);

}  // namespace boneless
