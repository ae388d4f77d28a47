#pragma once

#include <cstdint>
#include <string>
#include <vector>

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
// The units setTakeUnits takes by their symbols: mm, cm, dm, m, in, ft.
const std::vector<std::string>& c3dUnitSymbols();
// The take's POINT:UNITS as the file stores it (UTF-8), "" when it has none.
std::string c3dFileUnits(const C3dTake& take);

// Says a read take's coordinates are in `units` (one of c3dUnitSymbols(), or "file": the file's
// POINT:UNITS, millimetres without one; nothing for a take in them), as `from` says
// ("--take-units"; ignored for "file"), and judges its marker span in them again, without reading a
// frame: the doubt among its warnings is replaced, as is the reader's "no POINT:UNITS; assuming
// millimetres". A take whose file states other units than its coordinates are in (CMU 85_02 in
// metres under "mm") is solved so without editing the file. Throws C3dError naming the file for
// units it does not know.
void setTakeUnits(C3dTake& take, const std::string& units, const std::string& from);

}  // namespace boneless
