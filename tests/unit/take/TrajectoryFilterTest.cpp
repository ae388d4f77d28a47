#include <gtest/gtest.h>

#include <cmath>

#include "ProcessLocale.h"
#include "TrajectoryFilter.h"
#include "boneless/C3dTake.h"
#include "boneless/Error.h"

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

// A marker lost for a few frames is put back on its path: a straight path exactly, a curved one
// close to it; a gap longer than allowed, or at the take's ends, stays a gap.
TEST(GapFill, ShortGapsFollowTheTrajectoryAndLongOnesStay) {
    const int frames = 40;
    C3dSamples samples(frames, 2);
    for (int f = 0; f < frames; ++f) {
        samples.set(f, 0, 2.0 * f, -f, 5.0);                           // a straight line
        samples.set(f, 1, std::cos(0.2 * f), std::sin(0.2 * f), 0.0);  // a circle
    }
    for (int f = 10; f < 14; ++f) samples.setMissing(f, 0), samples.setMissing(f, 1);
    for (int f = 20; f < 30; ++f) samples.setMissing(f, 0);  // ten frames
    samples.setMissing(0, 1);                                // the take's first frame
    for (int f = 10; f < 14; ++f) {
        const auto line = gapFilled(samples, f, 0, 5);
        ASSERT_TRUE(line.has_value()) << f;
        EXPECT_LT((*line - Eigen::Vector3d(2.0 * f, -f, 5.0)).norm(), 1e-12) << f;
        const auto arc = gapFilled(samples, f, 1, 5);
        ASSERT_TRUE(arc.has_value()) << f;
        const Eigen::Vector3d truth(std::cos(0.2 * f), std::sin(0.2 * f), 0);
        // The chord between the gap's ends, a radian of arc apart, sags 0.12 at the middle.
        const double t = (f - 9) / 5.0;
        const Eigen::Vector3d chord =
            (1 - t) * *samples.position(9, 1) + t * *samples.position(14, 1);
        EXPECT_LT((*arc - truth).norm(), 0.2 * (chord - truth).norm()) << f;
    }
    EXPECT_FALSE(gapFilled(samples, 25, 0, 5).has_value());  // longer than five frames
    EXPECT_TRUE(gapFilled(samples, 25, 0, 10).has_value());
    EXPECT_FALSE(gapFilled(samples, 0, 1, 5).has_value());   // nothing before it
    EXPECT_FALSE(gapFilled(samples, 5, 0, 5).has_value());   // not missing
    EXPECT_FALSE(gapFilled(samples, 11, 0, 0).has_value());  // filling off
}

// The application runs with the user's locale (QApplication calls setlocale): in German printf
// wrote "low-pass cutoff 12,5 Hz", which the project file the user types it back into refuses.
TEST(TrajectoryFilter, ACutoffTooHighIsSaidWithADecimalPointInAGermanLocale) {
    PROCESS_LOCALE_OR_SKIP(german, "de_DE.UTF-8");
    std::vector<double> v(10, 1.0);
    try {
        lowPassFilter(v, 30, 12.5);
        FAIL() << "a cutoff of 12.5 Hz at 30 Hz was taken";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("low-pass cutoff 12.5 Hz must be below 12.03 Hz"),
                  std::string::npos)
            << e.what();
    }
}
