#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "ProcessLocale.h"
#include "boneless/Text.h"

using namespace boneless;

// The mesh reader, the take options and the C3D reader each formatted numbers for messages
// their own way; they share shortNumber now, printf's %g: six significant digits.
TEST(ShortNumber, GivesAnIntegerWithoutADecimalPointUpToSixDigits) {
    EXPECT_EQ(shortNumber(0), "0");
    EXPECT_EQ(shortNumber(3), "3");
    EXPECT_EQ(shortNumber(-12), "-12");
    EXPECT_EQ(shortNumber(65535), "65535");
    EXPECT_EQ(shortNumber(999999), "999999");
    EXPECT_EQ(shortNumber(1e6), "1e+06");
    EXPECT_EQ(shortNumber(1234567), "1.23457e+06");
}

TEST(ShortNumber, GivesFractionsInSixSignificantDigitsAndTinyOrHugeOnesWithAnExponent) {
    EXPECT_EQ(shortNumber(0.1), "0.1");
    EXPECT_EQ(shortNumber(-2.5), "-2.5");
    EXPECT_EQ(shortNumber(1.0 / 3), "0.333333");
    EXPECT_EQ(shortNumber(0.0001), "0.0001");
    EXPECT_EQ(shortNumber(1e-7), "1e-07");
    EXPECT_EQ(shortNumber(-0.01), "-0.01");
    EXPECT_EQ(shortNumber(1e20), "1e+20");
    EXPECT_EQ(shortNumber(3.4028234663852886e38), "3.40282e+38");  // a float's largest
}

// A C3D parameter may hold a NaN or an infinity, which the C3D reader's warnings name.
TEST(ShortNumber, NamesNotANumberAndTheInfinities) {
    EXPECT_EQ(shortNumber(std::nan("")), "nan");
    EXPECT_EQ(shortNumber(std::numeric_limits<double>::infinity()), "inf");
    EXPECT_EQ(shortNumber(-std::numeric_limits<double>::infinity()), "-inf");
}

// Core writes and reads numbers as JSON and the CLI do in any locale: once a program calls
// setlocale (the application does), printf and strtod use a German decimal comma.
TEST(NumbersInAGermanLocale, AreWrittenAndReadWithADecimalPoint) {
    PROCESS_LOCALE_OR_SKIP(german, "de_DE.UTF-8");
    EXPECT_EQ(shortNumber(12.5), "12.5");
    EXPECT_EQ(shortNumber(0.4 * 30, 3), "12");
    EXPECT_EQ(fixedNumber(2.5, 1), "2.5");
    EXPECT_EQ(lengthText(1540), "1.54 m");
    double x = 0;
    EXPECT_EQ(readDecimal("12.5", x), Decimal::Number);
    EXPECT_EQ(x, 12.5);
    EXPECT_EQ(readDecimal("12,5", x), Decimal::NotANumber);
}

TEST(LengthText, ALengthOfKilometresIsWrittenInKilometresWithoutAnExponent) {
    // A take in millimetres read as metres spans 1540 m: it said "1.54e+03 m".
    EXPECT_EQ(lengthText(1540e3), "1.54 km");
    EXPECT_EQ(lengthText(999e3), "999 m");
    EXPECT_EQ(lengthText(2.5e12), "2500000 km");
    EXPECT_EQ(lengthText(15.4), "15.4 mm");
}
