#pragma once

#include <cstdio>
#include <string>

namespace boneless {

// Formats whose header holds the frame count before the frames (MDD, glb) spool the frames to a
// file first. This writes `head`, the spool's bytes and `tail` to a temporary file beside `path`
// and renames it into place; the spool is closed and removed whatever happens. Throws Error
// naming `path` when a write fails.
void writeSpooled(const std::string& path, const std::string& head, std::FILE* spool,
                  const std::string& spoolPath, const std::string& tail);

}  // namespace boneless
