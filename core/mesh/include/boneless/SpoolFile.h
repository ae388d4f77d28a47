#pragma once

#include <cstdio>
#include <string>

namespace boneless {

// Formats whose header holds the frame count before the frames (MDD, glb) spool the frames to a
// file first, and the solve's sidecar its per-frame figures. This writes `head`, the spool's bytes
// and `tail` to a temporary file beside `path` and renames it into place; the spool is closed and
// removed whatever happens. Throws Error naming `path` when a write fails. spoolPath is empty for
// an unnamed spool (std::tmpfile).
void writeSpooled(const std::string& path, const std::string& head, std::FILE* spool,
                  const std::string& spoolPath, const std::string& tail);

}  // namespace boneless
