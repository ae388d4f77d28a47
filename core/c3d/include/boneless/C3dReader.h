#pragma once

#include <cstdint>
#include <string>

#include "boneless/C3dError.h"
#include "boneless/C3dTake.h"

namespace boneless {

struct C3dReadOptions {
    // Some exporters write gaps as (0,0,0) with a valid residual; by default such samples are
    // missing. Set to keep them as positions at the origin.
    bool keepZeroSamples = false;
};

// Throws C3dError naming the file, the byte offset and the cause; never reads out of bounds.
C3dTake readC3d(const std::string& path, const C3dReadOptions& options = {});
// The same from memory; name is used in messages and C3dTake::file.
C3dTake readC3dMemory(const std::uint8_t* data, std::size_t size, const std::string& name,
                      const C3dReadOptions& options = {});

// Unit string -> millimetres per unit ("mm", "cm", "m", "mete", "meters", "in", ...);
// nullopt when unknown.
std::optional<double> c3dUnitToMm(std::string_view units);

}  // namespace boneless
