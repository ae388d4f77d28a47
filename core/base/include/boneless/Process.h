#pragma once

namespace boneless {

// Whether process `pid` has ended, on this machine: the owner of a temporary file or of an
// autosave is known to be gone only then. A zombie (ended, not yet reaped by its parent: for a
// moment after a kill -9) has ended. With `startTime` (processStartTime's, as recorded), a process
// that started at another time has the id now and the one meant is gone. False for a running
// process, ours included, and for one we may not signal.
bool processIsGone(long pid, unsigned long long startTime = 0);

// When process `pid` started, in clock ticks since the machine booted (Linux: /proc/PID/stat's
// starttime); 0 where that cannot be read. With the id it names one process: an id is given again
// once its process has ended, a start time with it is not.
unsigned long long processStartTime(long pid);

}  // namespace boneless
