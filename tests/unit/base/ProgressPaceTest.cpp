#include <gtest/gtest.h>

#include "boneless/ProgressPace.h"

using boneless::ProgressPace;

TEST(ProgressPace, ALongTakesLogHearsOfItAtLeastEveryTenSeconds) {
    ProgressPace pace(2305);  // a tenth is 230 frames, which took 16 to 24 s on MakeHuman
    EXPECT_FALSE(pace.due(1, 2.0));
    EXPECT_TRUE(pace.due(5, 10.5));
    EXPECT_FALSE(pace.due(6, 11.0));
    EXPECT_FALSE(pace.due(9, 20.4));
    EXPECT_TRUE(pace.due(10, 20.6));
}

TEST(ProgressPace, AQuickTakesLogHearsOfEachTenthMoreAndOfTheLastFrame) {
    ProgressPace pace(95);
    EXPECT_FALSE(pace.due(8, 0.8));
    EXPECT_TRUE(pace.due(9, 0.9));
    EXPECT_FALSE(pace.due(17, 1.7));
    EXPECT_TRUE(pace.due(18, 1.8));
    EXPECT_FALSE(pace.due(26, 2.6));
    EXPECT_TRUE(pace.due(27, 2.7));
    EXPECT_TRUE(pace.due(95, 9.5));
}
