#include "boneless/MarkerTrack.h"

#include <unistd.h>
#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstring>
#include <limits>
#include <stdexcept>

#include "TrajectoryFilter.h"
#include "boneless/C3dFrameReader.h"
#include "boneless/Error.h"

namespace boneless {

namespace {
// Frames read from the file at a time while spooling: a few MB for a hundred markers.
constexpr std::size_t kSpoolBlock = 2048;
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
}  // namespace

void MarkerTrack::describe(const C3dTake& take, std::size_t frames, std::size_t markers,
                           double lowPassHz) {
    // A cutoff in Hz means nothing without one: the filter said "below 0 Hz at a frame rate of 0".
    if (lowPassHz > 0 && !take.hasFrameRate())
        throw Error(take.file + ": the take has no frame rate (" + take.rateText() +
                    "), so its trajectories cannot be low-pass filtered; set low_pass_hz to 0");
    file_ = take.file;
    rate_ = take.hasFrameRate() ? take.rate : 0;  // 0: no gap is a number of frames long
    unitToMm_ = take.unitToMm;
    vertical_ = take.vertical;
    frames_ = frames;
    markers_ = markers;
}

MarkerTrack::MarkerTrack(const C3dTake& take, const std::vector<std::size_t>& points,
                         double lowPassHz) {
    describe(take, take.frameCount(), points.size(), lowPassHz);
    recorded_ = take.samples;
    columns_ = points;
    for (std::size_t f = 0; f < frames_; ++f)
        for (std::size_t k = 0; k < markers_; ++k)
            if (recorded_.valid(f, columns_[k])) {
                seen_.push_back(static_cast<int>(f));
                break;
            }
    if (lowPassHz > 0) {
        memory_ = C3dSamples(frames_, markers_, C3dSamples::Precision::Double);
        for (std::size_t f = 0; f < frames_; ++f)
            for (std::size_t k = 0; k < markers_; ++k)
                if (const auto p = recorded_.position(f, columns_[k]))
                    memory_.set(f, k, p->x(), p->y(), p->z());
        lowPassFilter(memory_, rate_, lowPassHz);
        layer_ = 1;
    }
}

MarkerTrack::MarkerTrack(const C3dFrameReader& reader, const std::vector<std::size_t>& points,
                         double lowPassHz) {
    describe(reader.take(), reader.frameCount(), points.size(), lowPassHz);
    spool_ = std::tmpfile();
    if (!spool_)
        throw Error(file_ + ": cannot create a temporary file for the take's trajectories: " +
                    std::strerror(errno));
    // The file's frames are stored point by point; the spool turns them marker by marker, so
    // that a marker's whole trajectory can be filtered alone.
    std::vector<double> xyz;
    for (std::size_t first = 0; first < frames_; first += kSpoolBlock) {
        const std::size_t count = std::min(kSpoolBlock, frames_ - first);
        const C3dSamples block = reader.read(first, count);
        for (std::size_t f = 0; f < count; ++f)
            for (std::size_t k = 0; k < markers_; ++k)
                if (block.valid(f, points[k])) {
                    seen_.push_back(static_cast<int>(first + f));
                    break;
                }
        for (std::size_t k = 0; k < markers_; ++k) {
            xyz.assign(3 * count, kNaN);
            for (std::size_t f = 0; f < count; ++f)
                if (const auto p = block.position(f, points[k]))
                    for (int c = 0; c < 3; ++c) xyz[3 * f + c] = (*p)[c];
            spoolColumn(k, first, xyz);
        }
    }
    if (!(lowPassHz > 0)) return;
    // The filter runs over whole runs of a trajectory: one marker's at a time is in memory. The
    // filtered trajectories go to a second layer; the recorded ones stay for the residuals.
    for (std::size_t k = 0; k < markers_; ++k) {
        C3dSamples column(frames_, 1, C3dSamples::Precision::Double);
        for (std::size_t first = 0; first < frames_; first += kSpoolBlock) {
            const std::size_t count = std::min(kSpoolBlock, frames_ - first);
            xyz.assign(3 * count, kNaN);
            unspoolColumn(k, first, xyz);
            for (std::size_t f = 0; f < count; ++f)
                column.set(first + f, 0, xyz[3 * f], xyz[3 * f + 1], xyz[3 * f + 2]);
        }
        lowPassFilter(column, rate_, lowPassHz);
        for (std::size_t first = 0; first < frames_; first += kSpoolBlock) {
            const std::size_t count = std::min(kSpoolBlock, frames_ - first);
            xyz.assign(3 * count, kNaN);
            for (std::size_t f = 0; f < count; ++f)
                if (const auto p = column.position(first + f, 0))
                    for (int c = 0; c < 3; ++c) xyz[3 * f + c] = (*p)[c];
            spoolColumn(markers_ + k, first, xyz);
        }
    }
    layer_ = 1;
}

int MarkerTrack::nearestSeen(int frame) const {
    const auto after = std::lower_bound(seen_.begin(), seen_.end(), frame);
    if (after != seen_.end() && *after == frame) return frame;
    if (after == seen_.begin()) return after == seen_.end() ? -1 : *after;
    const int before = *(after - 1);
    return after == seen_.end() || frame - before <= *after - frame ? before : *after;
}

MarkerTrack::~MarkerTrack() {
    if (spool_) std::fclose(spool_);
}

void MarkerTrack::moveColumn(bool write, std::size_t marker, std::size_t first, double* xyz,
                             std::size_t count) const {
    char* bytes = reinterpret_cast<char*>(xyz);
    const std::size_t size = 3 * count * sizeof(double);
    const off_t offset = static_cast<off_t>((marker * frames_ + first) * 3 * sizeof(double));
    for (std::size_t done = 0; done < size;) {
        const int fd = ::fileno(spool_);
        const ssize_t n = write ? ::pwrite(fd, bytes + done, size - done, offset + done)
                                : ::pread(fd, bytes + done, size - done, offset + done);
        if (n < 0 && errno == EINTR) continue;
        if (n <= 0)
            throw Error(
                file_ + ": cannot " +
                (write ? "write the take's trajectories to" : "read the take's trajectories from") +
                " a temporary file: " +
                (n == 0 ? std::string("it is shorter than written")
                        : std::string(std::strerror(errno))));
        done += static_cast<std::size_t>(n);
    }
}

void MarkerTrack::spoolColumn(std::size_t marker, std::size_t first, std::vector<double>& xyz) {
    moveColumn(true, marker, first, xyz.data(), xyz.size() / 3);
}

void MarkerTrack::unspoolColumn(std::size_t marker, std::size_t first,
                                std::vector<double>& xyz) const {
    moveColumn(false, marker, first, xyz.data(), xyz.size() / 3);
}

C3dSamples MarkerTrack::read(std::size_t first, std::size_t count) const {
    return readLayer(layer_, first, count);
}

C3dSamples MarkerTrack::recorded(std::size_t frame) const {
    return readLayer(0, frame, 1);
}

C3dSamples MarkerTrack::readLayer(std::size_t layer, std::size_t first, std::size_t count) const {
    if (first > frames_ || count > frames_ - first)
        throw std::out_of_range("MarkerTrack: frames " + std::to_string(first) + "+" +
                                std::to_string(count) + " outside " + std::to_string(frames_));
    // Double: the filtered trajectories as computed.
    C3dSamples out(count, markers_, C3dSamples::Precision::Double);
    if (!spool_) {
        for (std::size_t f = 0; f < count; ++f)
            for (std::size_t k = 0; k < markers_; ++k)
                if (const auto p = layer == 0 ? recorded_.position(first + f, columns_[k])
                                              : memory_.position(first + f, k))
                    out.set(f, k, p->x(), p->y(), p->z());
        return out;
    }
    std::vector<double> xyz(3 * count);
    for (std::size_t k = 0; k < markers_; ++k) {
        unspoolColumn(layer * markers_ + k, first, xyz);
        for (std::size_t f = 0; f < count; ++f)  // NaN stays missing
            out.set(f, k, xyz[3 * f], xyz[3 * f + 1], xyz[3 * f + 2]);
    }
    return out;
}

}  // namespace boneless
