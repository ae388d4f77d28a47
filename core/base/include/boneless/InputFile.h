#pragma once

#include <string>

namespace boneless {

// Why `path` is no `kind` file ("mesh", "C3D", "correspondence") to read, for a loader to refuse
// it by what it is before opening it: "is a directory, not a C3D file", or "is not a regular
// file" for a FIFO (whose opening waits for a writer for ever), a socket or a device, "is a link to
// /takes/gone.c3d, which does not exist" for a link whose target is gone (where a relative link
// leads, from the link's folder). Empty for a regular file or a link to one, and for a path that
// cannot be looked at: opening it says why (no such file, permission).
std::string notARegularFile(const std::string& path, const std::string& kind);

}  // namespace boneless
