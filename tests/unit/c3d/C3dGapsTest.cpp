// A take's gaps (inspect's table, the app's timeline) and the comparison of two takes' samples
// (the app's check that a take read again is the one its solve was prepared for).

#include <gtest/gtest.h>

#include "C3dTestSupport.h"

using namespace boneless;

namespace boneless {

// Found by the vectors' comparison through the argument's namespace.
bool operator==(const C3dGap& a, const C3dGap& b) {
    return a.first == b.first && a.frames == b.frames;
}

}  // namespace boneless

TEST(C3dGaps, EachPointsRunsOfMissingFramesAreFoundInFrameOrder) {
    C3dSamples s(10, 3);
    for (std::size_t f = 0; f < 10; ++f) {
        s.set(f, 1, 1.0, 2.0, 3.0);  // point 1 is never missing
        if (f >= 2) s.set(f, 0, 1.0, 2.0, 3.0);
    }
    s.setMissing(5, 0);  // point 0: frames 0-1, 5-6 and 8-9
    s.setMissing(6, 0);
    s.setMissing(8, 0);
    s.setMissing(9, 0);
    const auto gaps = s.gaps();
    ASSERT_EQ(gaps.size(), 3u);
    EXPECT_EQ(gaps[0], (std::vector<C3dGap>{{0, 2}, {5, 2}, {8, 2}}));
    EXPECT_TRUE(gaps[1].empty());
    EXPECT_EQ(gaps[2], (std::vector<C3dGap>{{0, 10}}));  // point 2 is never seen
    EXPECT_EQ(s.missingFrames(0), 6u);
}

TEST(C3dGaps, ATakeWithoutFramesHasNoGaps) {
    const C3dSamples s(0, 4);
    const auto gaps = s.gaps();
    ASSERT_EQ(gaps.size(), 4u);
    for (const auto& g : gaps) EXPECT_TRUE(g.empty());
}

TEST(C3dSamePositions, ACopyAndATakeReadAgainHoldTheSamePositions) {
    const C3dTake t = c3dtest::syntheticTake(20, c3dtest::numberedLabels(5));
    const C3dSamples copy = t.samples;
    EXPECT_TRUE(copy.sharesData(t.samples));
    EXPECT_TRUE(copy.samePositions(t.samples));
    const C3dTake again = c3dtest::roundTrip(t);
    EXPECT_FALSE(again.samples.sharesData(t.samples));
    EXPECT_TRUE(again.samples.samePositions(t.samples));
}

TEST(C3dSamePositions, AMovedOrMissingSampleOrAnotherShapeDiffers) {
    const C3dTake t = c3dtest::syntheticTake(20, c3dtest::numberedLabels(5));
    std::size_t f = 0;
    while (!t.samples.valid(f, 2)) ++f;
    C3dSamples moved = t.samples;
    const Eigen::Vector3d p = *moved.position(f, 2);
    moved.set(f, 2, p.x() + 1.0, p.y(), p.z());
    EXPECT_FALSE(moved.samePositions(t.samples));
    C3dSamples missing = t.samples;
    missing.setMissing(f, 2);
    EXPECT_FALSE(missing.samePositions(t.samples));
    EXPECT_FALSE(t.samples.samePositions(missing));
    EXPECT_FALSE(C3dSamples(20, 4).samePositions(C3dSamples(20, 5)));
    EXPECT_FALSE(C3dSamples(19, 5).samePositions(C3dSamples(20, 5)));
}

TEST(C3dSamePositions, FloatAndDoubleSamplesOfOnePositionAreTheSame) {
    C3dSamples narrow(2, 1), wide(2, 1, C3dSamples::Precision::Double);
    narrow.set(0, 0, 1.5, -2.25, 3.0);
    wide.set(0, 0, 1.5, -2.25, 3.0);
    EXPECT_TRUE(narrow.samePositions(wide));
    wide.set(1, 0, 1.0, 1.0, 1.0);
    EXPECT_FALSE(narrow.samePositions(wide));
}
