// Where the frames lie in the file and how their words are stored.

#include <algorithm>
#include <cmath>

#include "C3dTakeLayout.h"
#include "boneless/Text.h"

namespace boneless::c3d_detail {

namespace {
std::size_t dataBytes(const Source& src, const PointLayout& L) {
    return L.dataStart < src.size ? src.size - L.dataStart : 0;
}
}  // namespace

void chooseStorage(const Source& src, const HeaderWords& h, double scale, PointLayout& L,
                   C3dTake& take) {
    if (!std::isfinite(scale) || scale == 0.0) {
        if (L.points > 0 || L.analogWords > 0)
            src.fail(12, "the point scale is " + shortNumber(scale) +
                             " in both the header and POINT:SCALE, so the storage (int16 or "
                             "float) is unknown");
        scale = -1.0;
    }
    L.storage = scale < 0 ? C3dStorage::Float : C3dStorage::Int16;
    L.scale = scale;
    take.storage = L.storage;
    take.pointScale = scale;
}

std::size_t chooseDataStart(const Source& src, const C3dParameters& ps, const HeaderWords& h,
                            std::size_t headerDataStart, const PointLayout& L,
                            std::vector<std::string>& warn) {
    // POINT:DATA_START when it lies in the file, else the header.
    std::size_t dataStart = headerDataStart;
    if (auto ds = paramNumber(ps, "POINT", "DATA_START")) {
        const std::size_t block = static_cast<std::size_t>(std::max(0.0, std::min(*ds, 65535.0)));
        if (block != h.dataStartBlock) {
            if (block >= 1 && (block - 1) * kBlock < src.size) {
                warn.push_back("header data start block " + std::to_string(h.dataStartBlock) +
                               " differs from POINT:DATA_START " + std::to_string(block) +
                               "; using POINT:DATA_START");
                dataStart = (block - 1) * kBlock;
            } else {
                warn.push_back("POINT:DATA_START " + std::to_string(block) +
                               " lies outside the file; using the header's block " +
                               std::to_string(h.dataStartBlock));
            }
        }
    }
    if (dataStart == 0 && (L.points > 0 || L.analogWords > 0))
        src.fail(16, "the 3D data start block is 0");
    return dataStart;
}

void reconcileStorage(const Source& src, const HeaderWords& h, std::size_t declaredFrames,
                      PointLayout& L, C3dTake& take) {
    // The header's scale and POINT:SCALE may disagree on the storage (the sign); POINT:SCALE wins
    // unless only the header's storage fits the file's size: read as floats, an int16 file gave
    // half its frames, and those garbage.
    if (h.scale == 0.0f || !std::isfinite(h.scale) || (h.scale < 0) == (L.scale < 0)) return;
    PointLayout alt = L;
    alt.storage = h.scale < 0 ? C3dStorage::Float : C3dStorage::Int16;
    alt.scale = h.scale;
    const auto fits = [&](const PointLayout& l) {
        return l.frameBytes() == 0 || declaredFrames <= dataBytes(src, l) / l.frameBytes();
    };
    // The data section is the declared frames and at most a block's padding: a float file read
    // as int16 fits too, in half its bytes, and gave coordinates like -133720.
    const auto fills = [&](const PointLayout& l) {
        return fits(l) && dataBytes(src, l) - declaredFrames * l.frameBytes() < kBlock;
    };
    const auto name = [](const PointLayout& l) {
        return l.storage == C3dStorage::Int16 ? std::string("int16") : std::string("float");
    };
    const std::string both = "the header's point scale (" + shortNumber(h.scale) + ", " +
                             name(alt) + ") and POINT:SCALE (" + shortNumber(L.scale) + ", " +
                             name(L) + ") disagree on the storage; ";
    const bool onlyHeaderFits = !fits(L) && fits(alt);
    if (onlyHeaderFits || (!fills(L) && fills(alt))) {
        take.warnings.push_back(both + (onlyHeaderFits
                                            ? "only the header's fits the file's size, using it"
                                            : "the 3D data section is the size of " +
                                                  std::to_string(declaredFrames) + " " + name(alt) +
                                                  " frames, using the header's"));
        L.storage = alt.storage;
        L.scale = alt.scale;
        take.storage = L.storage;
        take.pointScale = L.scale;
    } else {
        take.warnings.push_back(both + "using POINT:SCALE");
    }
}

void reconcileAnalogWords(const Source& src, const HeaderWords& h, const AnalogFrame& analog,
                          std::size_t declaredFrames, PointLayout& L,
                          std::vector<std::string>& warn) {
    // Header and parameters may disagree on the analog words per frame; the one the file's size
    // can hold wins.
    if (L.analogWords == h.analogPerFrame || (analog.channels == 0 && h.analogPerFrame == 0))
        return;
    PointLayout alt = L;
    alt.analogWords = h.analogPerFrame;
    const auto fits = [&](const PointLayout& l) {
        return l.frameBytes() == 0 || declaredFrames <= dataBytes(src, l) / l.frameBytes();
    };
    if (!fits(L) && fits(alt)) {
        warn.push_back("parameters give " + std::to_string(L.analogWords) +
                       " analog values per frame, the header " + std::to_string(h.analogPerFrame) +
                       "; only the header's fits the file, using it");
        L.analogWords = alt.analogWords;
    } else {
        warn.push_back("parameters give " + std::to_string(L.analogWords) +
                       " analog values per frame, the header " + std::to_string(h.analogPerFrame) +
                       "; using the parameters");
    }
}

void keepCompleteFrames(const Source& src, std::size_t declaredFrames, PointLayout& L,
                        std::vector<std::string>& warn) {
    // Truncated files: keep the complete frames, say how many are lost.
    L.frames = declaredFrames;
    const std::size_t bytes = dataBytes(src, L);
    if (L.frameBytes() > 0 && declaredFrames > bytes / L.frameBytes()) {
        const std::size_t complete = bytes / L.frameBytes();
        if (complete == 0)
            src.fail(
                std::min(L.dataStart, src.size),
                "the 3D data section holds no complete frame: " + std::to_string(declaredFrames) +
                    " frames of " + std::to_string(L.frameBytes()) +
                    " bytes declared, the file ends at byte " + std::to_string(src.size));
        warn.push_back("file is truncated: " + std::to_string(declaredFrames) +
                       " frames declared, " + std::to_string(complete) +
                       " complete frames present; reading those");
        L.frames = complete;
    }
}

}  // namespace boneless::c3d_detail
