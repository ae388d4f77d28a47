#pragma once

// Internal pieces of the C3D reader, shared between its source files; not installed.

#include <cstdint>
#include <functional>
#include <string>
#include <string_view>
#include <vector>

#include "boneless/C3dError.h"
#include "boneless/C3dNumbers.h"
#include "boneless/C3dParameters.h"
#include "boneless/C3dReader.h"
#include "boneless/C3dTake.h"

namespace boneless::c3d_detail {

constexpr std::size_t kBlock = 512;

struct Source {
    const std::uint8_t* data;
    std::size_t size;
    const std::string& file;

    [[noreturn]] void fail(std::uint64_t offset, std::string cause) const {
        throw C3dError(file, offset, std::move(cause));
    }
};

struct HeaderWords {
    std::uint8_t parameterBlock = 0;          // word 1, low byte
    std::uint16_t pointCount = 0;             // word 2
    std::uint16_t analogPerFrame = 0;         // word 3: channels x samples per frame
    std::uint16_t firstFrame = 0;             // word 4
    std::uint16_t lastFrame = 0;              // word 5
    float scale = 0.0f;                       // words 7-8
    std::uint16_t dataStartBlock = 0;         // word 9
    std::uint16_t analogSamplesPerFrame = 0;  // word 10
    float rate = 0.0f;                        // words 11-12
};

// UTF-8 of a string read from the file: as is when it is already UTF-8, else decoded as Latin-1
// (every byte sequence is valid Latin-1) and wasLatin1 set.
std::string textFromC3d(std::string_view raw, bool& wasLatin1);
// The file's bytes for a UTF-8 string; in Latin-1, characters it cannot hold become '?'.
std::string textToC3d(std::string_view utf8, C3dTextEncoding encoding);

HeaderWords readHeaderWords(const Source& src, C3dProcessor proc);
// Without a parameter section the processor is unknown: pick the one whose header reads sanely.
C3dProcessor guessHeaderProcessor(const Source& src);

// Parses the records starting 4 bytes after start, up to limit (exclusive). limitWhat names what
// lies at limit, for messages ("the 3D data section", "the end of the file").
C3dParameters readParameterSection(const Source& src, std::size_t start, std::size_t limit,
                                   const char* limitWhat, C3dProcessor proc, int declaredBlocks,
                                   std::vector<std::string>& warnings);

struct PointLayout {
    std::size_t dataStart = 0;  // byte offset of frame 0
    std::size_t frames = 0;
    std::size_t points = 0;
    std::size_t analogWords = 0;  // analog values following the points in each frame
    C3dStorage storage = C3dStorage::Float;
    double scale = 1.0;  // POINT:SCALE
    C3dProcessor processor = C3dProcessor::Intel;
    bool keepZeroSamples = false;

    std::size_t wordBytes() const { return storage == C3dStorage::Int16 ? 2 : 4; }
    std::size_t frameBytes() const { return (points * 4 + analogWords) * wordBytes(); }
};

struct DecodeStats {
    std::size_t nonFinite = 0;    // valid residual but NaN/Inf coordinates
    std::size_t zeroSamples = 0;  // (0,0,0) with a valid residual
};

// Decodes layout.frames frames into samples' frames from firstFrame on. The caller guarantees
// dataStart + frames * frameBytes() <= src.size.
DecodeStats decodePoints(const Source& src, const PointLayout& layout, C3dSamples& samples,
                         std::size_t firstFrame = 0);

// Everything of a take but its samples: validates the header and parameters, fills `take`
// (file, header fields, parameters, points, warnings) and returns where the frames lie, the
// complete frames only. Throws C3dError as readC3dMemory does.
PointLayout readTakeLayout(const Source& src, const C3dReadOptions& options, C3dTake& take);
// readTakeLayout of the open file fd (size bytes): on a mapping of it, of which the header and
// the parameters alone are read, so the 3D data is not brought into memory.
PointLayout readFileLayout(int fd, std::size_t size, const std::string& path,
                           const C3dReadOptions& options, C3dTake& take);
// n bytes of fd from offset, with pread: a file cut short meanwhile throws, where a mapping of
// it would have ended the program (SIGBUS).
void readFileBytes(int fd, const std::string& path, std::size_t offset, std::uint8_t* out,
                   std::size_t n);
// The warnings readC3dMemory gives for what decoding the samples found.
void noteDecodeStats(const DecodeStats& stats, const C3dReadOptions& options,
                     std::vector<std::string>& warnings);

// Sets take.vertical from POINT:Y_SCREEN and the markers of `frames` frames spread over the take
// (frameAt(f) gives frame f alone), with a warning when the markers reverse the file's axis. Both
// readers judge the same frames, so a take streamed and one read whole get the same vertical.
void setVertical(C3dTake& take, std::size_t frames,
                 const std::function<C3dSamples(std::size_t frame)>& frameAt);

// The span of the markers of up to 256 of `frames` frames spread over the take (frameAt as
// setVertical's, the same frames), read by both readers into C3dTake::markerSpan.
MarkerSpan measureMarkerSpan(const C3dTake& take, std::size_t frames,
                             const std::function<C3dSamples(std::size_t frame)>& frameAt);
// The span `stored` (in the take's coordinates as stored) judged in the take's units, and by what
// set them (C3dTake::unitsFrom): its mm, and the doubt when it is no body's.
MarkerSpan judgeMarkerSpan(const C3dTake& take, double stored);
// What the reader warns of the file's POINT:UNITS (none, or a name it does not know), or "".
std::string fileUnitsWarning(const C3dTake& take);

// Fills kind (and subject/name) of every point from POINT:ANGLES, FORCES, ... and known
// model-output names.
void classifyPoints(const C3dParameters& params, std::vector<C3dPoint>& points);

}  // namespace boneless::c3d_detail
