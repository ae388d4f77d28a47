#pragma once

#include <Eigen/Core>
#include <cstddef>
#include <optional>
#include <vector>

namespace boneless {

class C3dSamples;

// Zero-phase low-pass filtering of marker trajectories, the biomechanics habit against jitter
// (docs/algorithm.md §5): a 2nd-order Butterworth run forwards and backwards, its cutoff corrected
// so that the two passes together are 3 dB down at `cutoffHz`. Each unbroken run of visible
// samples is filtered on its own, so a gap stays a gap and nothing is smeared across it; runs
// shorter than four samples are left as they are. Throws Error when the cutoff is not below the
// Nyquist frequency.
void lowPassFilter(C3dSamples& samples, double rate, double cutoffHz);

// The same for one run of values (in place), for tests and other signals.
void lowPassFilter(std::vector<double>& values, double rate, double cutoffHz);

// Where `point` is missing at `frame`, inside a gap of at most maxFrames frames with a sample
// on each side: its position across the gap, a cubic Hermite curve through the two ends with
// tangents from the samples beyond them (where an end has none, the chord's). Nothing
// otherwise: at the take's ends and across longer gaps a marker stays missing.
std::optional<Eigen::Vector3d> gapFilled(const C3dSamples& samples, std::size_t frame,
                                         std::size_t point, int maxFrames);

}  // namespace boneless
