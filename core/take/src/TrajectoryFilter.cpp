#include "TrajectoryFilter.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

#include "boneless/C3dTake.h"
#include "boneless/Error.h"
#include "boneless/Text.h"

namespace boneless {

namespace {

constexpr double kPi = 3.14159265358979323846;
// Running a 2nd-order Butterworth twice puts the -3 dB point at 0.802 of its own cutoff.
constexpr double kTwoPassCorrection = 0.802;
constexpr int kMinimumRun = 4;

struct Biquad {
    double b0, b1, b2, a1, a2;
};

Biquad butterworth(double rate, double cutoffHz) {
    const double corrected = cutoffHz / kTwoPassCorrection;
    if (!(cutoffHz > 0) || !(corrected < 0.5 * rate)) {
        throw Error("low-pass cutoff " + shortNumber(cutoffHz) + " Hz must be below " +
                    shortNumber(0.5 * rate * kTwoPassCorrection, 4) +
                    " Hz (0.401 times the take's frame rate, " + shortNumber(rate) +
                    " Hz), or 0 for no filter");
    }
    const double K = std::tan(kPi * corrected / rate);
    const double norm = 1.0 / (1.0 + std::sqrt(2.0) * K + K * K);
    Biquad f;
    f.b0 = K * K * norm;
    f.b1 = 2 * f.b0;
    f.b2 = f.b0;
    f.a1 = 2 * (K * K - 1) * norm;
    f.a2 = (1 - std::sqrt(2.0) * K + K * K) * norm;
    return f;
}

// One causal pass, started in the steady state of its first value so the start does not ring.
void pass(const Biquad& f, std::vector<double>& x) {
    double x1 = x.front(), x2 = x.front(), y1 = x.front(), y2 = x.front();
    for (double& v : x) {
        const double y = f.b0 * v + f.b1 * x1 + f.b2 * x2 - f.a1 * y1 - f.a2 * y2;
        x2 = x1;
        x1 = v;
        y2 = y1;
        y1 = y;
        v = y;
    }
}

void filterRun(const Biquad& f, std::vector<double>& values) {
    const int n = static_cast<int>(values.size());
    if (n < kMinimumRun) return;
    // Odd reflection at both ends keeps the ends' value and slope through the filter's transient.
    const int pad = std::min(n - 1, 12);
    std::vector<double> x;
    x.reserve(n + 2 * pad);
    for (int i = pad; i >= 1; --i) x.push_back(2 * values.front() - values[i]);
    x.insert(x.end(), values.begin(), values.end());
    for (int i = 1; i <= pad; ++i) x.push_back(2 * values.back() - values[n - 1 - i]);
    pass(f, x);
    std::reverse(x.begin(), x.end());
    pass(f, x);
    std::reverse(x.begin(), x.end());
    std::copy(x.begin() + pad, x.begin() + pad + n, values.begin());
}

}  // namespace

void lowPassFilter(std::vector<double>& values, double rate, double cutoffHz) {
    filterRun(butterworth(rate, cutoffHz), values);
}

void lowPassFilter(C3dSamples& samples, double rate, double cutoffHz) {
    const Biquad f = butterworth(rate, cutoffHz);
    const std::size_t frames = samples.frames();
    std::vector<double> axis[3];
    for (std::size_t p = 0; p < samples.points(); ++p) {
        std::size_t start = 0;
        while (start < frames) {
            while (start < frames && !samples.valid(start, p)) ++start;
            std::size_t end = start;
            while (end < frames && samples.valid(end, p)) ++end;
            if (end - start >= static_cast<std::size_t>(kMinimumRun)) {
                for (auto& a : axis) a.clear();
                for (std::size_t t = start; t < end; ++t) {
                    const Eigen::Vector3d x = *samples.position(t, p);
                    for (int c = 0; c < 3; ++c) axis[c].push_back(x[c]);
                }
                for (auto& a : axis) filterRun(f, a);
                for (std::size_t t = start; t < end; ++t)
                    samples.set(t, p, axis[0][t - start], axis[1][t - start], axis[2][t - start],
                                samples.residual(t, p));
            }
            start = end;
        }
    }
}

std::optional<Eigen::Vector3d> gapFilled(const C3dSamples& samples, std::size_t frame,
                                         std::size_t point, int maxFrames) {
    if (maxFrames <= 0 || samples.valid(frame, point)) return std::nullopt;
    const long f = static_cast<long>(frame), frames = static_cast<long>(samples.frames());
    long a = f - 1, b = f + 1;
    while (a >= 0 && f - a <= maxFrames && !samples.valid(a, point)) --a;
    if (a < 0 || f - a > maxFrames) return std::nullopt;
    while (b < frames && b - a - 1 <= maxFrames && !samples.valid(b, point)) ++b;
    if (b >= frames || b - a - 1 > maxFrames) return std::nullopt;
    const Eigen::Vector3d pa = *samples.position(a, point), pb = *samples.position(b, point);
    const double span = static_cast<double>(b - a), t = (f - a) / span;
    // Tangents per unit of t: a sample's velocity beyond each end, times the gap's span.
    const Eigen::Vector3d chord = pb - pa;
    const Eigen::Vector3d ta = a > 0 && samples.valid(a - 1, point)
                                   ? Eigen::Vector3d(span * (pa - *samples.position(a - 1, point)))
                                   : chord;
    const Eigen::Vector3d tb = b + 1 < frames && samples.valid(b + 1, point)
                                   ? Eigen::Vector3d(span * (*samples.position(b + 1, point) - pb))
                                   : chord;
    const double t2 = t * t, t3 = t2 * t;
    return (2 * t3 - 3 * t2 + 1) * pa + (t3 - 2 * t2 + t) * ta + (-2 * t3 + 3 * t2) * pb +
           (t3 - t2) * tb;
}

}  // namespace boneless
