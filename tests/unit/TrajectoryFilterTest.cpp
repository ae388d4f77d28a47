#include <gtest/gtest.h>

#include <cmath>

#include "boneless/C3dTake.h"
#include "boneless/Error.h"
#include "boneless/TrajectoryFilter.h"

using namespace boneless;

namespace {

std::vector<double> sine(double hz, double rate, int n) {
    std::vector<double> v(n);
    for (int i = 0; i < n; ++i) v[i] = std::sin(2 * M_PI * hz * i / rate);
    return v;
}

double amplitude(const std::vector<double>& v, int from, int to) {
    double a = 0;
    for (int i = from; i < to; ++i) a = std::max(a, std::abs(v[i]));
    return a;
}

}  // namespace

TEST(TrajectoryFilter, PassesSlowMotionAndRemovesJitter) {
    const double rate = 120;
    auto slow = sine(1.0, rate, 600);
    const auto original = slow;
    lowPassFilter(slow, rate, 6.0);
    double worst = 0;
    for (size_t i = 0; i < slow.size(); ++i)
        worst = std::max(worst, std::abs(slow[i] - original[i]));
    EXPECT_LT(worst, 0.01);  // 1 Hz under a 6 Hz cutoff, no phase shift, ends included

    auto cutoff = sine(6.0, rate, 600);
    lowPassFilter(cutoff, rate, 6.0);
    EXPECT_NEAR(amplitude(cutoff, 100, 500), std::sqrt(0.5), 0.03);  // -3 dB at the cutoff

    auto jitter = sine(30.0, rate, 600);
    lowPassFilter(jitter, rate, 6.0);
    EXPECT_LT(amplitude(jitter, 100, 500), 0.01);
}

TEST(TrajectoryFilter, GapsStayGapsAndRunsAreFilteredApart) {
    C3dSamples samples(40, 1);
    for (int t = 0; t < 40; ++t)
        if (t < 15 || t >= 20) samples.set(t, 0, t < 15 ? 0.0 : 100.0, 1.0, 2.0);
    lowPassFilter(samples, 100, 5);
    for (int t = 15; t < 20; ++t) EXPECT_FALSE(samples.valid(t, 0));
    // A step across the gap must not leak into either side.
    for (int t = 0; t < 15; ++t) EXPECT_NEAR(samples.position(t, 0)->x(), 0.0, 1e-9);
    for (int t = 20; t < 40; ++t) EXPECT_NEAR(samples.position(t, 0)->x(), 100.0, 1e-9);
}

TEST(TrajectoryFilter, RejectsACutoffAboveNyquist) {
    std::vector<double> v(10, 1.0);
    EXPECT_THROW(lowPassFilter(v, 100, 60), Error);
    EXPECT_THROW(lowPassFilter(v, 100, 0), Error);
}
