#pragma once

// Helpers shared by the C3D tests: locating the real sample files, building synthetic takes.

#include <gtest/gtest.h>

#include <cstdint>
#include <filesystem>
#include <random>
#include <string>
#include <vector>

#include "boneless/C3dReader.h"
#include "boneless/C3dTake.h"
#include "boneless/C3dWriter.h"

namespace c3dtest {

inline std::filesystem::path sharedC3d() {
    return std::filesystem::path(BONELESS_SHARED_DATA) / "c3d";
}

// Skips the calling test when the shared data folder (beside the repository) is absent.
#define C3D_SHARED_OR_SKIP(var, rel)                                 \
    const std::string var = (c3dtest::sharedC3d() / (rel)).string(); \
    if (!std::filesystem::exists(var)) GTEST_SKIP() << "no shared data: " << var

inline std::filesystem::path workDir() {
    std::filesystem::path d = std::filesystem::path(BONELESS_TEST_WORK_DIR) / "c3d";
    std::filesystem::create_directories(d);
    return d;
}

// frames x labels.size() take with coordinates that are exact floats, every seventh sample
// missing, and a residual that is a multiple of the scale.
inline boneless::C3dTake syntheticTake(std::size_t frames, const std::vector<std::string>& labels,
                                       unsigned seed = 1) {
    boneless::C3dTake t;
    t.rate = 120.0;
    t.units = "mm";
    t.pointScale = -0.1;
    t.firstFrame = 1;
    for (const auto& l : labels) {
        boneless::C3dPoint p;
        p.label = l;
        boneless::splitC3dLabel(l, p.subject, p.name);
        t.points.push_back(p);
    }
    t.samples = boneless::C3dSamples(frames, labels.size());
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> u(-2000.0f, 2000.0f);
    for (std::size_t f = 0; f < frames; ++f)
        for (std::size_t k = 0; k < labels.size(); ++k) {
            if ((f * labels.size() + k) % 7 == 3) continue;  // missing
            t.samples.set(f, k, u(rng), u(rng), u(rng), float(int(rng() % 200)) * 0.1f);
        }
    return t;
}

inline std::vector<std::string> numberedLabels(std::size_t n, const std::string& prefix = "M") {
    std::vector<std::string> out;
    for (std::size_t i = 0; i < n; ++i) out.push_back(prefix + std::to_string(i));
    return out;
}

// "Müller" and "Kniewinkel ä" as this source file spells them (UTF-8), for the Latin-1 tests.
inline const std::string kLatin1Subject = "M\xC3\xBCller";
inline const std::string kLatin1Description = "Kniewinkel \xC3\xA4";

// A take whose labels and descriptions are written in Latin-1, as older Vicon files are.
inline boneless::C3dTake latin1Take() {
    boneless::C3dTake t =
        syntheticTake(4, {kLatin1Subject + ":LFHD", kLatin1Subject + ":LKneeAngles", "RFHD"});
    t.points[1].kind = boneless::C3dPointKind::Angle;
    t.points[1].description = kLatin1Description;
    t.textEncoding = boneless::C3dTextEncoding::Latin1;
    return t;
}

inline boneless::C3dTake roundTrip(const boneless::C3dTake& t,
                                   const boneless::C3dWriteOptions& w = {},
                                   const boneless::C3dReadOptions& r = {}) {
    const std::vector<std::uint8_t> bytes = boneless::encodeC3d(t, w);
    return boneless::readC3dMemory(bytes.data(), bytes.size(), "roundtrip.c3d", r);
}

}  // namespace c3dtest
