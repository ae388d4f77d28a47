// The analog channels each frame carries and the number of frames the file declares.

#include <cmath>

#include "C3dTakeLayout.h"
#include "boneless/Text.h"

namespace boneless::c3d_detail {

namespace {

// TRIAL:ACTUAL_START_FIELD / ACTUAL_END_FIELD: a 32-bit frame number as two 16-bit words, least
// significant first.
std::optional<std::int64_t> trialField(const C3dParameters& ps, const char* name) {
    const C3dParameter* p = ps.find("TRIAL", name);
    if (!p) return std::nullopt;
    const auto lo = p->number(0, true), hi = p->number(1, true);
    if (!lo) return std::nullopt;
    if (p->type() == C3dParamType::Float) {
        if (!(*lo >= 0.0 && *lo <= 4294967295.0)) return std::nullopt;
        return std::int64_t(*lo);
    }
    return std::int64_t(*lo) + (hi ? std::int64_t(*hi) * 65536 : 0);
}

}  // namespace

AnalogFrame readAnalog(const C3dParameters& ps, const HeaderWords& h, double rate, C3dTake& take) {
    auto& warn = take.warnings;
    std::size_t channels = h.analogSamplesPerFrame ? h.analogPerFrame / h.analogSamplesPerFrame : 0;
    double analogRate = double(h.analogSamplesPerFrame) * rate;
    std::size_t perFrame = h.analogSamplesPerFrame;
    if (auto u = paramNumber(ps, "ANALOG", "USED"))
        channels = countOr(warn, *u, 65535, "ANALOG:USED", channels);
    if (auto r = paramNumber(ps, "ANALOG", "RATE")) analogRate = *r;
    if (channels > 0 && ps.find("ANALOG", "RATE") && rate > 0.0) {
        const double ratio = analogRate / rate;
        if (std::isfinite(ratio) && ratio >= 0.5 && ratio <= 65535.0) {
            perFrame = static_cast<std::size_t>(std::lround(ratio));
            if (std::fabs(ratio - double(perFrame)) > 1e-3)
                warn.push_back("analog rate " + shortNumber(analogRate) +
                               " Hz is not a multiple of " + shortNumber(rate) + " Hz; assuming " +
                               std::to_string(perFrame) + " samples per frame");
        } else {
            warn.push_back("ANALOG:RATE " + shortNumber(analogRate) +
                           " Hz is unusable; using the header's " + std::to_string(perFrame) +
                           " samples per frame");
        }
    }
    if (!std::isfinite(analogRate) || analogRate < 0.0) analogRate = 0.0;
    take.analogChannels = static_cast<int>(channels);
    take.analogRate = channels > 0 ? analogRate : 0.0;
    take.analogSamplesPerFrame = channels > 0 ? static_cast<int>(perFrame) : 0;
    return {channels, perFrame};
}

std::size_t declaredFrameCount(const C3dParameters& ps, const HeaderWords& h, C3dTake& take) {
    // POINT:LONG_FRAMES, which the standard says overrides POINT:FRAMES (a writer wraps that
    // 16-bit count: 70000 frames read as 4464), then POINT:FRAMES, then the vendors' other ways
    // past 65535, then the header. A LONG_FRAMES that is no count (0: unused) or that a FRAMES
    // neither saturated nor its wrap contradicts (a take trimmed by a tool that left it) is not.
    const std::size_t headerFrames =
        h.lastFrame >= h.firstFrame && h.lastFrame > 0 ? h.lastFrame - h.firstFrame + 1 : 0;
    const auto framesParam = paramNumber(ps, "POINT", "FRAMES");
    const auto trialStart = trialField(ps, "ACTUAL_START_FIELD");
    const auto trialEnd = trialField(ps, "ACTUAL_END_FIELD");
    const bool trialOk = trialStart && trialEnd && *trialEnd >= *trialStart;
    const auto longFrames = paramNumber(ps, "POINT", "LONG_FRAMES");
    double frames = double(headerFrames);
    const char* framesFrom = "the header";
    const bool longCount = longFrames && std::isfinite(*longFrames) && *longFrames > 0 &&
                           *longFrames <= 2147483647.0 && *longFrames == std::floor(*longFrames);
    const bool longAgrees =
        longCount && (!framesParam || *framesParam == 65535.0 || *framesParam == *longFrames ||
                      std::fmod(*longFrames, 65536.0) == *framesParam);
    if (longCount && !longAgrees)
        take.warnings.push_back("POINT:LONG_FRAMES " + shortNumber(*longFrames) +
                                " disagrees with POINT:FRAMES " + shortNumber(*framesParam) +
                                "; using POINT:FRAMES");
    if (longAgrees) {
        frames = *longFrames;
        framesFrom = "POINT:LONG_FRAMES";
    } else if (framesParam && *framesParam != 65535.0) {
        frames = *framesParam;
        framesFrom = "POINT:FRAMES";
    } else if (trialOk) {
        frames = double(*trialEnd - *trialStart + 1);
        framesFrom = "TRIAL:ACTUAL_START_FIELD..ACTUAL_END_FIELD";
    } else if (framesParam) {
        frames = 65535.0;
    }
    const std::size_t declaredFrames =
        countOr(take.warnings, frames, 2147483647.0,
                std::string("the frame count from ") + framesFrom, headerFrames);
    if (framesParam && declaredFrames <= 65535 && declaredFrames != headerFrames)
        take.warnings.push_back("header frames " + std::to_string(h.firstFrame) + ".." +
                                std::to_string(h.lastFrame) + " (" + std::to_string(headerFrames) +
                                ") disagree with the parameters (" +
                                std::to_string(declaredFrames) + "); using the parameters");
    take.firstFrame = trialStart ? *trialStart : std::int64_t(h.firstFrame);
    return declaredFrames;
}

}  // namespace boneless::c3d_detail
