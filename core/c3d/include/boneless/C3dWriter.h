#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "boneless/C3dTake.h"

namespace boneless {

struct C3dWriteOptions {
    // For more than 65535 frames: POINT:FRAMES holds 65535 and the real count goes to TRIAL
    // (first/last frame as 32-bit) and/or POINT:LONG_FRAMES (float), as different vendors expect.
    bool trialFrameRange = true;
    bool longFrames = true;
};

// Intel processor, float storage, no analog data. Writes take.parameters (groups and parameters
// the take carries, e.g. from a file read earlier) with the POINT, TRIAL and ANALOG entries that
// describe the data replaced from the take itself: labels (LABELS2, ... beyond 255), descriptions,
// rate, units, frame count, point kinds (ANGLES, FORCES, ...). Missing samples get residual -1.
std::vector<std::uint8_t> encodeC3d(const C3dTake& take, const C3dWriteOptions& options = {});
void writeC3d(const C3dTake& take, const std::string& path, const C3dWriteOptions& options = {});

}  // namespace boneless
