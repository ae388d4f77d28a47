#include "boneless/MddWriter.h"

#include <cerrno>
#include <cstdint>
#include <cstring>
#include <filesystem>

#include "boneless/Error.h"
#include "boneless/SpoolFile.h"

namespace boneless {

namespace {

static_assert(sizeof(float) == 4, "MDD stores IEEE single precision");

std::uint32_t bigEndian(std::uint32_t host) {
    unsigned char b[4] = {static_cast<unsigned char>(host >> 24),
                          static_cast<unsigned char>(host >> 16),
                          static_cast<unsigned char>(host >> 8), static_cast<unsigned char>(host)};
    std::uint32_t out;
    std::memcpy(&out, b, 4);
    return out;
}

std::uint32_t fromBigEndian(std::uint32_t stored) {
    unsigned char b[4];
    std::memcpy(b, &stored, 4);
    return std::uint32_t(b[0]) << 24 | std::uint32_t(b[1]) << 16 | std::uint32_t(b[2]) << 8 | b[3];
}

std::uint32_t floatBits(float f) {
    std::uint32_t u;
    std::memcpy(&u, &f, 4);
    return bigEndian(u);
}

float bitsFloat(std::uint32_t stored) {
    const std::uint32_t u = fromBigEndian(stored);
    float f;
    std::memcpy(&f, &u, 4);
    return f;
}

}  // namespace

MddWriter::MddWriter(std::string path, int pointCount)
    : path_(std::move(path)), file_(openSpoolBeside(path_)), points_(pointCount) {}

MddWriter::~MddWriter() {
    if (file_) std::fclose(file_);
}

void MddWriter::append(double seconds, const Positions& positions) {
    if (!file_) throw Error(path_ + ": the point cache is already finished");
    if (positions.rows() != points_)
        throw Error(path_ + ": frame with " + std::to_string(positions.rows()) +
                    " points, the cache holds " + std::to_string(points_));
    std::vector<std::uint32_t> buffer(3 * static_cast<size_t>(points_));
    for (int v = 0; v < points_; ++v)
        for (int c = 0; c < 3; ++c)
            buffer[3 * v + c] = floatBits(static_cast<float>(positions(v, c)));
    if (std::fwrite(buffer.data(), 4, buffer.size(), file_) != buffer.size())
        throw Error(path_ + ": writing failed (" + writeFailure() + ")");
    times_.push_back(static_cast<float>(seconds));
}

void MddWriter::finish() {
    if (!file_) return;
    std::vector<std::uint32_t> header = {bigEndian(static_cast<std::uint32_t>(times_.size())),
                                         bigEndian(static_cast<std::uint32_t>(points_))};
    for (float t : times_) header.push_back(floatBits(t));
    std::string head(header.size() * 4, '\0');
    std::memcpy(head.data(), header.data(), head.size());
    std::FILE* spool = file_;
    file_ = nullptr;
    writeSpooled(path_, head, spool, std::string());
}

std::vector<Positions> readMdd(const std::string& path, std::vector<double>* seconds) {
    std::FILE* f = std::fopen(path.c_str(), "rb");
    if (!f) throw Error(path + ": cannot open the point cache (" + std::strerror(errno) + ")");
    std::uint32_t counts[2];
    if (std::fread(counts, 4, 2, f) != 2) {
        std::fclose(f);
        throw Error(path + ": not an MDD point cache");
    }
    const std::uint32_t frames = fromBigEndian(counts[0]), points = fromBigEndian(counts[1]);
    const auto size = std::filesystem::file_size(path);
    if (8 + 4ull * frames + 12ull * frames * points != size) {
        std::fclose(f);
        throw Error(path + ": an MDD header for " + std::to_string(frames) + " frames of " +
                    std::to_string(points) + " points does not match the file's size");
    }
    std::vector<std::uint32_t> buffer(frames);
    std::fread(buffer.data(), 4, frames, f);
    if (seconds)
        for (std::uint32_t t : buffer) seconds->push_back(bitsFloat(t));
    std::vector<Positions> out;
    buffer.resize(3 * static_cast<size_t>(points));
    for (std::uint32_t s = 0; s < frames; ++s) {
        if (std::fread(buffer.data(), 4, buffer.size(), f) != buffer.size()) {
            std::fclose(f);
            throw Error(path + ": truncated at frame " + std::to_string(s));
        }
        Positions P(points, 3);
        for (std::uint32_t v = 0; v < points; ++v)
            for (int c = 0; c < 3; ++c) P(v, c) = bitsFloat(buffer[3 * v + c]);
        out.push_back(std::move(P));
    }
    std::fclose(f);
    return out;
}

}  // namespace boneless
