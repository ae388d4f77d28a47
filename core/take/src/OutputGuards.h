#pragma once

// The export's guards of its output folder, private to core/take: the lock, the refusal to write
// over an input, and the removal of what a failed take wrote.

#include <filesystem>
#include <string>
#include <vector>

#include "boneless/TakeExport.h"

namespace boneless {

// Held from before the solver is prepared until the sidecar is written: two runs solving into one
// folder's files at once (two batch runs, a shard started twice) interleaved their frames under
// the sidecar of whichever finished last, which then said complete; and taken after preparing,
// the second run threw away seconds to minutes of work per take. An advisory lock on a hidden
// file beside the sidecar: the kernel lets go when its holder dies, whatever killed it. Makes the
// output folder, and removes what it made if it is still empty when let go (a solve that failed
// before writing).
class OutputLock {
  public:
    explicit OutputLock(const ExportRequest& request);
    ~OutputLock();
    OutputLock(const OutputLock&) = delete;
    OutputLock& operator=(const OutputLock&) = delete;

  private:
    std::string outDir_, path_;
    std::filesystem::path made_;  // the first folder of outDir_ this made; empty if none
    int fd_ = -1;
};

// A file written over an input would destroy it: the map clob/walker.json beside clob/walker.obj
// was replaced by the sidecar of a solve into clob. `frames`: the take's frame count.
void refuseOutputsOverInputs(const ExportRequest& request, int frames);

// Removes the files a failed take wrote (its OBJ frames, its calibrated rest: "" for none) and
// says so, for the take's error: "the 9 OBJ frames this run wrote were removed", or "".
std::string removeWritten(const std::vector<std::filesystem::path>& frames,
                          const std::filesystem::path& rest);

}  // namespace boneless
