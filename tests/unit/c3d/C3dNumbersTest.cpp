// Processor formats: DEC VAX F floats and MIPS big-endian values.

#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "boneless/C3dNumbers.h"

using namespace boneless;

TEST(C3dNumbers, VaxFloatKnownValues) {
    const std::uint8_t one[] = {0x80, 0x40, 0x00, 0x00};  // 0.5 x 2^1: exponent 129
    EXPECT_EQ(c3d::f32(one, C3dProcessor::Dec), 1.0f);
    const std::uint8_t minus2_5[] = {0x20, 0xC1, 0x00, 0x00};  // sign, exponent 130, .101b
    EXPECT_EQ(c3d::f32(minus2_5, C3dProcessor::Dec), -2.5f);
    const std::uint8_t zero[] = {0x00, 0x00, 0x12, 0x34};  // exponent 0 is zero whatever follows
    EXPECT_EQ(c3d::f32(zero, C3dProcessor::Dec), 0.0f);
    const std::uint8_t reserved[] = {0x00, 0x80, 0x00, 0x00};  // sign with exponent 0 traps on VAX
    EXPECT_TRUE(std::isnan(c3d::f32(reserved, C3dProcessor::Dec)));
    // Exponents 1 and 2 fall below IEEE's normal range and must still decode, not vanish.
    const std::uint8_t tiny[] = {0x80, 0x00, 0x00, 0x00};  // exponent 1: 2^-128
    EXPECT_EQ(c3d::f32(tiny, C3dProcessor::Dec), std::ldexp(1.0f, -128));
}

TEST(C3dNumbers, VaxFloatRoundTripsEveryNormalMagnitude) {
    std::mt19937 rng(7);
    std::uniform_int_distribution<int> exp(-120, 120);
    std::uniform_real_distribution<float> mant(1.0f, 2.0f);
    for (int i = 0; i < 100000; ++i) {
        const float v = std::ldexp(mant(rng), exp(rng)) * ((i & 1) ? -1.0f : 1.0f);
        std::uint8_t b[4];
        c3d::encodeVaxF(v, b);
        ASSERT_EQ(c3d::decodeVaxF(b), v) << v;
    }
}

TEST(C3dNumbers, EndiannessPerProcessor) {
    const std::uint8_t w[] = {0xFF, 0xFE};
    EXPECT_EQ(c3d::i16(w, C3dProcessor::Intel), std::int16_t(0xFEFF));
    EXPECT_EQ(c3d::i16(w, C3dProcessor::Dec), std::int16_t(0xFEFF));
    EXPECT_EQ(c3d::i16(w, C3dProcessor::Mips), -2);
    EXPECT_EQ(c3d::u16(w, C3dProcessor::Mips), 0xFFFE);
    const std::uint8_t be[] = {0x3F, 0x80, 0x00, 0x00};
    EXPECT_EQ(c3d::f32(be, C3dProcessor::Mips), 1.0f);
    const std::uint8_t le[] = {0x00, 0x00, 0x80, 0x3F};
    EXPECT_EQ(c3d::f32(le, C3dProcessor::Intel), 1.0f);
    std::uint8_t out[4];
    c3d::putF32(out, -0.0833f);
    EXPECT_EQ(c3d::f32(out, C3dProcessor::Intel), -0.0833f);
}
