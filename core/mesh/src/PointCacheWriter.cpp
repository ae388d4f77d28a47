#include "boneless/PointCacheWriter.h"

#include <cerrno>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <vector>

#include "boneless/Error.h"
#include "boneless/SpoolFile.h"

namespace boneless {

namespace {

static_assert(sizeof(float) == 4, "PC2 stores IEEE single precision");

constexpr char kSignature[12] = "POINTCACHE2";  // with its terminating NUL: 12 bytes
constexpr long kSampleCountOffset = 28;

// PC2 is little-endian; so is every machine Boneless is built for, which this checks.
bool littleEndian() {
    const std::uint16_t one = 1;
    unsigned char first;
    std::memcpy(&first, &one, 1);
    return first == 1;
}

}  // namespace

PointCacheWriter::PointCacheWriter(std::string path, int pointCount, double startFrame,
                                   double sampleRate)
    : path_(std::move(path)), points_(pointCount) {
    if (!littleEndian()) throw Error(path_ + ": PC2 writing needs a little-endian machine");
    temporary_ = temporaryFor(path_);
    file_ = std::fopen(temporary_.c_str(), "wb");
    // The user's file and the system's reason: the temporary beside it is ours, not theirs.
    if (!file_) throw Error(path_ + ": cannot be written (" + std::strerror(errno) + ")");
    const std::int32_t version = 1, points = pointCount, samples = 0;
    const float start = static_cast<float>(startFrame), rate = static_cast<float>(sampleRate);
    errno = 0;
    if (std::fwrite(kSignature, 1, sizeof kSignature, file_) != sizeof kSignature ||
        std::fwrite(&version, 4, 1, file_) != 1 || std::fwrite(&points, 4, 1, file_) != 1 ||
        std::fwrite(&start, 4, 1, file_) != 1 || std::fwrite(&rate, 4, 1, file_) != 1 ||
        std::fwrite(&samples, 4, 1, file_) != 1) {
        const std::string why = writeFailure();
        std::fclose(file_);
        file_ = nullptr;
        std::remove(temporary_.c_str());
        throw Error(path_ + ": cannot be written (" + why + ")");
    }
}

PointCacheWriter::~PointCacheWriter() {
    if (file_) {
        std::fclose(file_);
        std::remove(temporary_.c_str());
    }
}

void PointCacheWriter::append(const Positions& positions) {
    if (!file_) throw Error(path_ + ": the point cache is already finished");
    if (positions.rows() != points_)
        throw Error(path_ + ": frame with " + std::to_string(positions.rows()) +
                    " points, the cache holds " + std::to_string(points_));
    std::vector<float> buffer(3 * static_cast<size_t>(points_));
    for (int v = 0; v < points_; ++v)
        for (int c = 0; c < 3; ++c) buffer[3 * v + c] = static_cast<float>(positions(v, c));
    if (std::fwrite(buffer.data(), sizeof(float), buffer.size(), file_) != buffer.size())
        throw Error(path_ + ": writing failed (" + writeFailure() + ")");
    ++frames_;
}

void PointCacheWriter::finish() {
    if (!file_) return;
    const std::int32_t samples = frames_;
    // The frames buffered since the last append reach the disk at fclose: a full disk fails
    // there, and says so by errno as any write does.
    errno = 0;
    const bool ok = std::fseek(file_, kSampleCountOffset, SEEK_SET) == 0 &&
                    std::fwrite(&samples, 4, 1, file_) == 1;
    std::string why = ok ? "" : writeFailure();
    errno = 0;
    const bool closed = std::fclose(file_) == 0;
    if (ok && !closed) why = writeFailure();
    file_ = nullptr;
    std::error_code ec;
    if (ok && closed) std::filesystem::rename(temporary_, path_, ec);
    if (ec) why = ec.message();
    if (!ok || !closed || ec) {
        std::remove(temporary_.c_str());
        throw Error(path_ + ": cannot be written (" + why + ")");
    }
}

std::vector<Positions> readPointCache(const std::string& path, double* startFrame) {
    std::FILE* f = std::fopen(path.c_str(), "rb");
    if (!f) throw Error(path + ": cannot open the point cache (" + std::strerror(errno) + ")");
    char signature[12];
    std::int32_t version = 0, points = 0, samples = 0;
    float start = 0, rate = 0;
    const bool header = std::fread(signature, 1, 12, f) == 12 &&
                        std::fread(&version, 4, 1, f) == 1 && std::fread(&points, 4, 1, f) == 1 &&
                        std::fread(&start, 4, 1, f) == 1 && std::fread(&rate, 4, 1, f) == 1 &&
                        std::fread(&samples, 4, 1, f) == 1;
    if (!header || std::memcmp(signature, kSignature, 12) != 0 || points < 0 || samples < 0) {
        std::fclose(f);
        throw Error(path + ": not a PC2 point cache");
    }
    std::vector<Positions> frames;
    std::vector<float> buffer(3 * static_cast<size_t>(points));
    for (int s = 0; s < samples; ++s) {
        if (std::fread(buffer.data(), sizeof(float), buffer.size(), f) != buffer.size()) {
            std::fclose(f);
            throw Error(path + ": truncated at frame " + std::to_string(s));
        }
        Positions P(points, 3);
        for (int v = 0; v < points; ++v)
            for (int c = 0; c < 3; ++c) P(v, c) = buffer[3 * v + c];
        frames.push_back(std::move(P));
    }
    std::fclose(f);
    if (startFrame) *startFrame = start;
    return frames;
}

}  // namespace boneless
