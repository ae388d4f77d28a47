// Reading a C3D file: locate the sections, reconcile the header with the parameters, decode.

#include "boneless/C3dReader.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstring>

#include "C3dTakeLayout.h"
#include "boneless/InputFile.h"

namespace boneless {

using namespace c3d_detail;

namespace c3d_detail {

// One section per thing the header and the parameters both describe (C3dTakeLayout.h); the order
// is the order of the warnings.
PointLayout readTakeLayout(const Source& src, const C3dReadOptions& options, C3dTake& take) {
    const FileStart start = readFileStart(src, take);
    const HeaderWords& h = start.header;
    const C3dParameters& ps = take.parameters;
    auto& warn = take.warnings;

    const std::size_t points = pointCount(ps, h, warn);
    const double scale = pointScale(ps, h, warn);
    take.rate = frameRate(ps, h, warn);
    // Text leaves the reader as UTF-8; latin1 records that some of it had to be converted.
    bool latin1 = false;
    readUnits(ps, take, latin1);
    const AnalogFrame analog = readAnalog(ps, h, take.rate, take);
    const std::size_t declaredFrames = declaredFrameCount(ps, h, take);

    PointLayout L;
    L.points = points;
    L.processor = start.processor;
    L.keepZeroSamples = options.keepZeroSamples;
    L.analogWords = analog.words();
    chooseStorage(src, h, scale, L, take);
    L.dataStart = chooseDataStart(src, ps, h, start.headerDataStart, L, warn);
    reconcileStorage(src, h, declaredFrames, L, take);
    reconcileAnalogWords(src, h, analog, declaredFrames, L, warn);
    keepCompleteFrames(src, declaredFrames, L, warn);

    readLabels(ps, points, take, latin1);
    classifyPoints(ps, take.points);
    return L;
}

void noteDecodeStats(const DecodeStats& stats, const C3dReadOptions& options,
                     std::vector<std::string>& warn) {
    if (stats.nonFinite > 0)
        warn.push_back(std::to_string(stats.nonFinite) +
                       " samples have non-finite coordinates; treated as missing");
    if (stats.zeroSamples > 0 && !options.keepZeroSamples)
        warn.push_back(std::to_string(stats.zeroSamples) +
                       " samples are exactly (0, 0, 0); treated as missing");
}

}  // namespace c3d_detail

namespace {

// What a take decoded still needs: the warnings of what decoding found, its vertical axis and
// its markers' span, judged on the take in memory.
void finishTake(C3dTake& take, const DecodeStats& stats, const C3dReadOptions& options) {
    noteDecodeStats(stats, options, take.warnings);
    const std::size_t frames = take.samples.frames();
    const auto frameAt = [&take](std::size_t f) {
        C3dSamples frame(1, take.samples.points());
        for (std::size_t k = 0; k < frame.points(); ++k)
            if (const auto p = take.samples.position(f, k)) frame.set(0, k, p->x(), p->y(), p->z());
        return frame;
    };
    setVertical(take, frames, frameAt);
    // A take in other units than it says, warned of where every reader of the file sees it.
    take.markerSpan = measureMarkerSpan(take, frames, frameAt);
    if (!take.markerSpan.doubt.empty()) take.warnings.push_back(take.markerSpan.doubt);
}

// Frames read and decoded at a time: the file is never held whole beside its samples (a 112 MB
// take held inspect at twice its size).
constexpr std::size_t kChunkBytes = std::size_t(4) << 20;

}  // namespace

C3dTake readC3dMemory(const std::uint8_t* data, std::size_t size, const std::string& name,
                      const C3dReadOptions& options) {
    const Source src{data, size, name};
    C3dTake take;
    const PointLayout L = readTakeLayout(src, options, take);
    take.samples = C3dSamples(L.frames, L.points);
    finishTake(take, decodePoints(src, L, take.samples), options);
    return take;
}

C3dTake readC3d(const std::string& path, const C3dReadOptions& options) {
    if (const std::string why = notARegularFile(path, "C3D"); !why.empty())
        throw C3dError(path, C3dError::kNoOffset, why);
    const int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
    if (fd < 0)
        throw C3dError(path, C3dError::kNoOffset,
                       std::string("cannot open the take (") + std::strerror(errno) + ")");
    const struct Closer {
        int fd;
        ~Closer() { ::close(fd); }
    } closer{fd};
    struct stat st {};
    if (::fstat(fd, &st) != 0)
        throw C3dError(
            path, C3dError::kNoOffset,
            std::string("cannot determine the file size (") + std::strerror(errno) + ")");
    C3dTake take;
    const PointLayout L =
        readFileLayout(fd, static_cast<std::size_t>(st.st_size), path, options, take);
    take.samples = C3dSamples(L.frames, L.points);
    DecodeStats stats;
    if (L.points > 0) {
        const std::size_t frameBytes = L.frameBytes();
        const std::size_t chunk = std::max<std::size_t>(1, kChunkBytes / frameBytes);
        std::vector<std::uint8_t> bytes;
        for (std::size_t first = 0; first < L.frames; first += chunk) {
            PointLayout part = L;
            part.frames = std::min(chunk, L.frames - first);
            part.dataStart = 0;
            bytes.resize(part.frames * frameBytes);
            readFileBytes(fd, path, L.dataStart + first * frameBytes, bytes.data(), bytes.size());
            const DecodeStats got =
                decodePoints({bytes.data(), bytes.size(), path}, part, take.samples, first);
            stats.nonFinite += got.nonFinite;
            stats.zeroSamples += got.zeroSamples;
        }
    }
    finishTake(take, stats, options);
    return take;
}

}  // namespace boneless
