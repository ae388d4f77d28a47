#pragma once

#include <cstddef>
#include <cstdio>
#include <memory>
#include <string>
#include <vector>

#include "boneless/C3dTake.h"

namespace boneless {

class C3dFrameReader;

// The trajectories of a take's mapped markers as the TakeSolver solves from them (one column per
// mapped point, in the take's units), low-pass filtered when lowPassHz > 0, read a window of
// frames at a time. Built from a take in memory they stay in memory; streamed from its file they
// are spooled to an unnamed temporary file, so memory does not grow with the take's length.
// Either way a frame's samples are the same.
class MarkerTrack {
  public:
    MarkerTrack(const C3dTake& take, const std::vector<std::size_t>& points, double lowPassHz);
    MarkerTrack(const C3dFrameReader& reader, const std::vector<std::size_t>& points,
                double lowPassHz);
    ~MarkerTrack();
    MarkerTrack(const MarkerTrack&) = delete;
    MarkerTrack& operator=(const MarkerTrack&) = delete;

    std::size_t frames() const { return frames_; }
    // The frame nearest `frame` (the earlier on a tie) where some marker is seen; −1 for none.
    int nearestSeen(int frame) const;
    std::size_t markers() const { return markers_; }
    const std::string& file() const { return file_; }
    double rate() const { return rate_; }
    double unitToMm() const { return unitToMm_; }
    const Eigen::Vector3d& vertical() const { return vertical_; }  // C3dTake::vertical

    // Frames [first, first + count) of the markers, low-passed if asked (residuals are not
    // kept). Safe to call from several threads. Throws Error when the spool cannot be read.
    C3dSamples read(std::size_t first, std::size_t count) const;
    // One frame of the markers as the file records them, before any low-pass filter: what a
    // frame's marker residual is measured against.
    C3dSamples recorded(std::size_t frame) const;
    bool filtered() const { return layer_ == 1; }  // recorded() differs from read()

  private:
    // Throws Error when lowPassHz asks to filter a take without a frame rate.
    void describe(const C3dTake& take, std::size_t frames, std::size_t markers, double lowPassHz);
    // A marker's frames [first, first + xyz.size() / 3) to and from the spool.
    void spoolColumn(std::size_t marker, std::size_t first, std::vector<double>& xyz);
    void unspoolColumn(std::size_t marker, std::size_t first, std::vector<double>& xyz) const;
    void moveColumn(bool write, std::size_t marker, std::size_t first, double* xyz,
                    std::size_t count) const;
    C3dSamples readLayer(std::size_t layer, std::size_t first, std::size_t count) const;

    std::string file_;
    double rate_ = 0, unitToMm_ = 1;
    Eigen::Vector3d vertical_ = Eigen::Vector3d::UnitZ();
    std::size_t frames_ = 0, markers_ = 0;
    std::vector<int> seen_;  // the frames where some marker is seen, ascending
    // Built from a take in memory: layer 0 is the take's own samples (a copy sharing their
    // block, so a long take is not held twice), column k being point columns_[k]; layer 1, when
    // filtered, the low-passed trajectories in double, one column per marker.
    C3dSamples recorded_;
    std::vector<std::size_t> columns_;
    C3dSamples memory_;
    // When streamed: marker-major, xyz doubles, NaN where missing; the recorded samples, then,
    // when filtered, the low-passed ones (layer 1).
    std::FILE* spool_ = nullptr;
    std::size_t layer_ = 0;  // the layer read() reads
};

}  // namespace boneless
