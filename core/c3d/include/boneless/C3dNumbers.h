#pragma once

// Reading 16-bit and 32-bit values the way each C3D processor type stored them. The processor
// type is byte 4 of the parameter section: 84 Intel (little-endian IEEE), 85 DEC (little-endian
// integers, VAX F floats), 86 MIPS/SGI (big-endian IEEE).

#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>

namespace boneless {

enum class C3dProcessor : std::uint8_t { Intel = 84, Dec = 85, Mips = 86 };

namespace c3d {

inline std::uint16_t u16(const std::uint8_t* p, C3dProcessor proc) {
    if (proc == C3dProcessor::Mips) return static_cast<std::uint16_t>((p[0] << 8) | p[1]);
    return static_cast<std::uint16_t>(p[0] | (p[1] << 8));
}

inline std::int16_t i16(const std::uint8_t* p, C3dProcessor proc) {
    return static_cast<std::int16_t>(u16(p, proc));
}

inline float ieeeFromBits(std::uint32_t bits) {
    float f;
    std::memcpy(&f, &bits, sizeof f);
    return f;
}

// VAX F_floating: two little-endian 16-bit words; the first holds the sign (bit 15), an 8-bit
// exponent biased by 128 (bits 14..7) and the top 7 fraction bits, the second the low 16 fraction
// bits. The hidden bit sits left of the binary point (0.1f x 2^(e-128)), so the value is
// 1.f x 2^(e-129): IEEE's layout with the exponent off by two. Exponent 0 is zero, or with the
// sign set a "reserved operand" that traps on a VAX; we return NaN so it can only become a
// missing sample.
inline float decodeVaxF(const std::uint8_t* p) {
    const std::uint32_t hi = static_cast<std::uint32_t>(p[0] | (p[1] << 8));
    const std::uint32_t lo = static_cast<std::uint32_t>(p[2] | (p[3] << 8));
    const int exponent = static_cast<int>((hi >> 7) & 0xFFu);
    const bool negative = (hi & 0x8000u) != 0;
    if (exponent == 0) return negative ? std::numeric_limits<float>::quiet_NaN() : 0.0f;
    const std::uint32_t fraction = ((hi & 0x7Fu) << 16) | lo;
    if (exponent > 2) {
        // Normal in IEEE too: shift the exponent by two, no rounding involved.
        const std::uint32_t bits = (negative ? 0x80000000u : 0u) |
                                   (static_cast<std::uint32_t>(exponent - 2) << 23) | fraction;
        return ieeeFromBits(bits);
    }
    const double mantissa = 1.0 + static_cast<double>(fraction) / 8388608.0;
    const double v = std::ldexp(mantissa, exponent - 129);
    return static_cast<float>(negative ? -v : v);
}

// Inverse of decodeVaxF for finite floats (used by tests and fuzz seeds); values below VAX's range
// become zero and values beyond it saturate to the largest VAX magnitude.
inline void encodeVaxF(float value, std::uint8_t* p) {
    std::uint32_t bits;
    std::memcpy(&bits, &value, sizeof bits);
    const std::uint32_t sign = bits & 0x80000000u;
    int exponent = static_cast<int>((bits >> 23) & 0xFFu);
    std::uint32_t fraction = bits & 0x7FFFFFu;
    int vaxExp;
    if (exponent == 0) {
        vaxExp = 0;  // zero or IEEE subnormal: below VAX's smallest normal
        fraction = 0;
    } else if (exponent >= 254) {
        vaxExp = 255;
        fraction = 0x7FFFFFu;
    } else {
        vaxExp = exponent + 2;
    }
    const std::uint32_t hi = (vaxExp == 0)
                                 ? 0u
                                 : ((sign ? 0x8000u : 0u) |
                                    (static_cast<std::uint32_t>(vaxExp) << 7) | (fraction >> 16));
    const std::uint32_t lo = (vaxExp == 0) ? 0u : (fraction & 0xFFFFu);
    p[0] = static_cast<std::uint8_t>(hi & 0xFF);
    p[1] = static_cast<std::uint8_t>(hi >> 8);
    p[2] = static_cast<std::uint8_t>(lo & 0xFF);
    p[3] = static_cast<std::uint8_t>(lo >> 8);
}

inline float f32(const std::uint8_t* p, C3dProcessor proc) {
    switch (proc) {
        case C3dProcessor::Dec:
            return decodeVaxF(p);
        case C3dProcessor::Mips:
            return ieeeFromBits((std::uint32_t(p[0]) << 24) | (std::uint32_t(p[1]) << 16) |
                                (std::uint32_t(p[2]) << 8) | std::uint32_t(p[3]));
        case C3dProcessor::Intel:
        default:
            return ieeeFromBits(std::uint32_t(p[0]) | (std::uint32_t(p[1]) << 8) |
                                (std::uint32_t(p[2]) << 16) | (std::uint32_t(p[3]) << 24));
    }
}

inline void putU16(std::uint8_t* p, std::uint16_t v) {
    p[0] = static_cast<std::uint8_t>(v & 0xFF);
    p[1] = static_cast<std::uint8_t>(v >> 8);
}

inline void putF32(std::uint8_t* p, float v) {
    std::uint32_t bits;
    std::memcpy(&bits, &v, sizeof bits);
    for (int i = 0; i < 4; ++i) p[i] = static_cast<std::uint8_t>(bits >> (8 * i));
}

}  // namespace c3d
}  // namespace boneless
