// The 3D data section: frames of X, Y, Z, residual words per point, then analog values.

#include <cmath>

#include "C3dDetail.h"

namespace boneless::c3d_detail {

namespace {

// One instantiation per processor and storage keeps the per-sample loop free of branches on
// the format, which is what lets a 100 MB take decode well under a second.
template <C3dProcessor P, C3dStorage S>
DecodeStats decode(const Source& src, const PointLayout& L, C3dSamples& samples,
                   std::size_t first) {
    DecodeStats stats;
    const std::size_t frameBytes = L.frameBytes();
    const double scale = L.scale;
    const float residualScale = static_cast<float>(std::fabs(L.scale));
    for (std::size_t f = 0; f < L.frames; ++f) {
        const std::uint8_t* p = src.data + L.dataStart + f * frameBytes;
        for (std::size_t k = 0; k < L.points; ++k) {
            double x, y, z;
            int word;  // residual word: high byte camera mask, low byte residual; < 0 = missing
            if constexpr (S == C3dStorage::Int16) {
                x = c3d::i16(p, P) * scale;
                y = c3d::i16(p + 2, P) * scale;
                z = c3d::i16(p + 4, P) * scale;
                word = c3d::i16(p + 6, P);
                p += 8;
            } else {
                x = c3d::f32(p, P);
                y = c3d::f32(p + 4, P);
                z = c3d::f32(p + 8, P);
                const float r = c3d::f32(p + 12, P);
                // Float files store the 16-bit word as a float value; NaN and out-of-range
                // values cannot be a residual word and count as missing.
                word = (r >= 0.0f && r < 65536.0f) ? static_cast<int>(r) : -1;
                p += 16;
            }
            if (word < 0) {
                samples.setMissing(first + f, k);
                continue;
            }
            if (x == 0.0 && y == 0.0 && z == 0.0) {
                ++stats.zeroSamples;
                if (!L.keepZeroSamples) {
                    samples.setMissing(first + f, k);
                    continue;
                }
            }
            if (!(std::isfinite(x) && std::isfinite(y) && std::isfinite(z))) ++stats.nonFinite;
            samples.set(first + f, k, x, y, z, static_cast<float>(word & 0xFF) * residualScale);
        }
    }
    return stats;
}

template <C3dProcessor P>
DecodeStats decodeFor(const Source& src, const PointLayout& L, C3dSamples& samples,
                      std::size_t first) {
    if (L.storage == C3dStorage::Int16) return decode<P, C3dStorage::Int16>(src, L, samples, first);
    return decode<P, C3dStorage::Float>(src, L, samples, first);
}

}  // namespace

DecodeStats decodePoints(const Source& src, const PointLayout& layout, C3dSamples& samples,
                         std::size_t firstFrame) {
    // A file may declare two billion frames of nothing; do not walk them.
    if (layout.points == 0) return {};
    switch (layout.processor) {
        case C3dProcessor::Dec:
            return decodeFor<C3dProcessor::Dec>(src, layout, samples, firstFrame);
        case C3dProcessor::Mips:
            return decodeFor<C3dProcessor::Mips>(src, layout, samples, firstFrame);
        case C3dProcessor::Intel:
        default:
            return decodeFor<C3dProcessor::Intel>(src, layout, samples, firstFrame);
    }
}

}  // namespace boneless::c3d_detail
