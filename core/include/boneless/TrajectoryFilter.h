#pragma once

#include <vector>

namespace boneless {

class C3dSamples;

// Zero-phase low-pass filtering of marker trajectories, the biomechanics habit against jitter
// (algorithm.md §4.4): a 2nd-order Butterworth run forwards and backwards, its cutoff corrected
// so that the two passes together are 3 dB down at `cutoffHz`. Each unbroken run of visible
// samples is filtered on its own, so a gap stays a gap and nothing is smeared across it; runs
// shorter than four samples are left as they are. Throws Error when the cutoff is not below the
// Nyquist frequency.
void lowPassFilter(C3dSamples& samples, double rate, double cutoffHz);

// The same for one run of values (in place), for tests and other signals.
void lowPassFilter(std::vector<double>& values, double rate, double cutoffHz);

}  // namespace boneless
