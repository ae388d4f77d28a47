#pragma once

// A C3D file read a range of frames at a time, for takes too long to hold in memory.

#include <cstddef>
#include <string>

#include "boneless/C3dReader.h"
#include "boneless/C3dTake.h"

namespace boneless {

class C3dFrameReader {
  public:
    // Validates the header and parameters as readC3d does (same warnings, same refusals, the
    // same frames kept of a truncated file) without reading the 3D data. Throws C3dError.
    explicit C3dFrameReader(const std::string& path, const C3dReadOptions& options = {});
    ~C3dFrameReader();
    C3dFrameReader(const C3dFrameReader&) = delete;
    C3dFrameReader& operator=(const C3dFrameReader&) = delete;

    // The take without its samples (they hold no frames): file, rate, units, points, parameters.
    // Its warnings lack what only decoding finds (non-finite or (0,0,0) samples).
    const C3dTake& take() const { return take_; }
    std::size_t frameCount() const { return frames_; }
    // setTakeUnits on take(): its samples, read later, are in the units it then says.
    void setUnits(const std::string& units, const std::string& from) {
        setTakeUnits(take_, units, from);
    }
    // Frames [first, first + count) of every point, as readC3d gives them. Safe to call from
    // several threads. Throws C3dError when the file can no longer be read.
    C3dSamples read(std::size_t first, std::size_t count) const;

  private:
    C3dTake take_;
    C3dReadOptions options_;
    int fd_ = -1;
    std::size_t frames_ = 0, points_ = 0, dataStart_ = 0, frameBytes_ = 0, analogWords_ = 0;
    double scale_ = 1.0;
};

}  // namespace boneless
