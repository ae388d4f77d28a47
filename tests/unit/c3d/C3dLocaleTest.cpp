// The C3D reader under the user's locale, which the application sets: in Turkish, C's
// tolower('I') is 'I' (its lower case is a dotless i), and "IN" read as no unit at all.

#include <gtest/gtest.h>

#include "C3dTestSupport.h"
#include "ProcessLocale.h"
#include "boneless/C3dReader.h"

using namespace boneless;

TEST(C3dUnderTurkishLocale, ATakeInInchesIsReadInInches) {
    PROCESS_LOCALE_OR_SKIP(turkish, "tr_TR.UTF-8");
    C3dTake take = c3dtest::syntheticTake(3, {"A", "B"});
    take.units = "IN";
    const C3dTake read = c3dtest::roundTrip(take);
    EXPECT_EQ(read.unitToMm, 25.4);
    for (const std::string& warning : read.warnings)
        EXPECT_EQ(warning.find("POINT:UNITS"), std::string::npos) << warning;
}

TEST(C3dUnderTurkishLocale, UnitsInCapitalsWithAnIAreKnown) {
    PROCESS_LOCALE_OR_SKIP(turkish, "tr_TR.UTF-8");
    EXPECT_EQ(c3dUnitToMm("INCHES"), 25.4);
    EXPECT_EQ(c3dUnitToMm("CENTIMETRES"), 10.0);
    EXPECT_EQ(c3dUnitToMm("MILLIMETERS"), 1.0);
}
