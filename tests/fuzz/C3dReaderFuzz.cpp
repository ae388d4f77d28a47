// libFuzzer target for the C3D reader. Any input must either read or raise C3dError; a crash,
// a sanitizer report or any other exception is a bug. What reads must also survive the writer
// and read back with the same shape.

#include <cstdint>
#include <cstdlib>
#include <stdexcept>

#include "boneless/C3dReader.h"
#include "boneless/C3dWriter.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    using namespace boneless;
    C3dTake take;
    try {
        C3dReadOptions options;
        options.keepZeroSamples = (size & 1) != 0;  // both paths, deterministically per input
        take = readC3dMemory(data, size, "fuzz.c3d", options);
    } catch (const C3dError&) {
        return 0;
    }
    if (take.samples.points() != take.points.size()) std::abort();
    // The round trip is linear in the point count, which a 1 KB header can set to 65535; past a
    // few thousand points it only slows the run without reaching new code.
    if (take.points.size() > 2048) return 0;
    std::vector<std::uint8_t> again;
    try {
        again = encodeC3d(take);
    } catch (const std::invalid_argument&) {
        return 0;  // e.g. a parameter the file could hold but one 16-bit record offset cannot
    }
    const C3dTake back = readC3dMemory(again.data(), again.size(), "fuzz-rewritten.c3d");
    if (back.frameCount() != take.frameCount() || back.points.size() != take.points.size())
        std::abort();
    if (back.samples.missingCount() < take.samples.missingCount()) std::abort();
    return 0;
}
