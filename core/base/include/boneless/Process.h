#pragma once

namespace boneless {

// Whether process `pid` has ended, on this machine: the owner of a temporary file or of an
// autosave is known to be gone only then. False for a running process, ours included, and for one
// we may not signal.
bool processIsGone(long pid);

}  // namespace boneless
