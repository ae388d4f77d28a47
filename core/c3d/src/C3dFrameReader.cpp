#include "boneless/C3dFrameReader.h"

#include <fcntl.h>
#include <sys/mman.h>
#include <sys/stat.h>
#include <unistd.h>
#include <cerrno>
#include <cstring>
#include <stdexcept>
#include <vector>

#include "C3dDetail.h"
#include "boneless/InputFile.h"

namespace boneless {

using namespace c3d_detail;

namespace {
[[noreturn]] void failSystem(const std::string& path, const char* what) {
    throw C3dError(path, C3dError::kNoOffset,
                   std::string(what) + " (" + std::strerror(errno) + ")");
}
}  // namespace

namespace c3d_detail {

PointLayout readFileLayout(int fd, std::size_t size, const std::string& path,
                           const C3dReadOptions& options, C3dTake& take) {
    void* map = size ? ::mmap(nullptr, size, PROT_READ, MAP_PRIVATE, fd, 0) : nullptr;
    if (map == MAP_FAILED) failSystem(path, "cannot map");
    try {
        const PointLayout L =
            readTakeLayout({static_cast<const std::uint8_t*>(map), size, path}, options, take);
        if (map) ::munmap(map, size);
        return L;
    } catch (...) {
        if (map) ::munmap(map, size);
        throw;
    }
}

void readFileBytes(int fd, const std::string& path, std::size_t offset, std::uint8_t* out,
                   std::size_t n) {
    for (std::size_t done = 0; done < n;) {
        const ssize_t got = ::pread(fd, out + done, n - done, offset + done);
        if (got < 0 && errno == EINTR) continue;
        if (got <= 0)
            throw C3dError(path, offset + done,
                           got == 0 ? std::string("the file became shorter while being read")
                                    : std::string("read error: ") + std::strerror(errno));
        done += static_cast<std::size_t>(got);
    }
}

}  // namespace c3d_detail

C3dFrameReader::C3dFrameReader(const std::string& path, const C3dReadOptions& options)
    : options_(options) {
    if (const std::string why = notARegularFile(path, "C3D"); !why.empty())
        throw C3dError(path, C3dError::kNoOffset, why);
    fd_ = ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
    if (fd_ < 0) failSystem(path, "cannot open the take");
    try {
        struct stat st {};
        if (::fstat(fd_, &st) != 0) failSystem(path, "cannot determine the file size");
        const std::size_t size = static_cast<std::size_t>(st.st_size);
        const PointLayout L = readFileLayout(fd_, size, path, options, take_);
        frames_ = L.frames;
        points_ = L.points;
        dataStart_ = L.dataStart;
        frameBytes_ = L.frameBytes();
        analogWords_ = L.analogWords;
        scale_ = L.scale;
        take_.samples = C3dSamples(0, points_);
        const auto frameAt = [this](std::size_t f) { return read(f, 1); };
        setVertical(take_, frames_, frameAt);
        take_.markerSpan = measureMarkerSpan(take_, frames_, frameAt);
        if (!take_.markerSpan.doubt.empty()) take_.warnings.push_back(take_.markerSpan.doubt);
    } catch (...) {
        ::close(fd_);
        throw;
    }
}

C3dFrameReader::~C3dFrameReader() {
    ::close(fd_);
}

C3dSamples C3dFrameReader::read(std::size_t first, std::size_t count) const {
    if (first > frames_ || count > frames_ - first)
        throw std::out_of_range("C3dFrameReader: frames " + std::to_string(first) + "+" +
                                std::to_string(count) + " outside " + std::to_string(frames_));
    C3dSamples samples(count, points_);
    if (count == 0 || points_ == 0) return samples;
    std::vector<std::uint8_t> bytes(count * frameBytes_);
    readFileBytes(fd_, take_.file, dataStart_ + first * frameBytes_, bytes.data(), bytes.size());
    PointLayout L;
    L.frames = count;
    L.points = points_;
    L.analogWords = analogWords_;
    L.storage = take_.storage;
    L.scale = scale_;
    L.processor = take_.processor;
    L.keepZeroSamples = options_.keepZeroSamples;
    decodePoints({bytes.data(), bytes.size(), take_.file}, L, samples);
    return samples;
}

}  // namespace boneless
