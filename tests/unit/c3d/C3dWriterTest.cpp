// Synthetic takes through the writer and back: what the real files cannot cover on demand.

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>

#include "C3dTestSupport.h"
#include "boneless/C3dNumbers.h"

using namespace boneless;
using c3dtest::numberedLabels;
using c3dtest::roundTrip;
using c3dtest::syntheticTake;

namespace {

void expectExactSamples(const C3dTake& a, const C3dTake& b) {
    ASSERT_EQ(a.frameCount(), b.frameCount());
    ASSERT_EQ(a.points.size(), b.points.size());
    for (std::size_t f = 0; f < a.frameCount(); ++f)
        for (std::size_t k = 0; k < a.points.size(); ++k) {
            ASSERT_EQ(a.samples.valid(f, k), b.samples.valid(f, k)) << f << "," << k;
            const auto pa = a.samples.position(f, k), pb = b.samples.position(f, k);
            if (!pa) continue;
            ASSERT_EQ(*pa, *pb) << f << "," << k;
            ASSERT_EQ(a.samples.residual(f, k), b.samples.residual(f, k)) << f << "," << k;
        }
}

// Where a parameter's first value lies in an encoded (Intel) file, found by walking the records.
std::size_t valueOffset(const std::vector<std::uint8_t>& file, const std::string& group,
                        const std::string& name) {
    std::size_t pos = (file[0] - 1) * 512 + 4;
    int groupId = 0;
    while (pos + 2 < file.size() && file[pos] != 0) {
        const int n = std::abs(static_cast<std::int8_t>(file[pos]));
        const int id = static_cast<std::int8_t>(file[pos + 1]);
        const std::string recName(reinterpret_cast<const char*>(&file[pos + 2]), n);
        const std::size_t offsetAt = pos + 2 + n;
        const int offset = c3d::i16(&file[offsetAt], C3dProcessor::Intel);
        if (id < 0 && recName == group) groupId = -id;
        if (id > 0 && id == groupId && recName == name)
            return offsetAt + 2 + 2 + file[offsetAt + 3];  // type, ndims, dims
        if (offset == 0) break;
        pos = offsetAt + offset;
    }
    ADD_FAILURE() << group << ":" << name << " not found";
    return 0;
}

// Re-encodes a float file written by encodeC3d as int16 with the given (positive) scale.
std::vector<std::uint8_t> toInt16(const std::vector<std::uint8_t>& f, float scale,
                                  std::size_t frames) {
    std::vector<std::uint8_t> out(f);
    const std::size_t points = c3d::u16(&f[2], C3dProcessor::Intel);
    const std::size_t dataStart = (c3d::u16(&f[16], C3dProcessor::Intel) - 1) * 512;
    c3d::putF32(&out[12], scale);
    c3d::putF32(&out[valueOffset(out, "POINT", "SCALE")], scale);
    out.resize(dataStart + frames * points * 8);
    for (std::size_t i = 0; i < frames * points; ++i) {
        const std::uint8_t* src = &f[dataStart + 16 * i];
        std::uint8_t* dst = &out[dataStart + 8 * i];
        for (int c = 0; c < 3; ++c) {
            const float v = c3d::f32(src + 4 * c, C3dProcessor::Intel);
            c3d::putU16(dst + 2 * c, static_cast<std::uint16_t>(std::lround(v / scale)));
        }
        const float r = c3d::f32(src + 12, C3dProcessor::Intel);
        c3d::putU16(dst + 6, static_cast<std::uint16_t>(static_cast<std::int16_t>(r)));
    }
    return out;
}

bool hasWarning(const C3dTake& t, const std::string& needle) {
    for (const auto& w : t.warnings)
        if (w.find(needle) != std::string::npos) return true;
    return false;
}

}  // namespace

TEST(C3dWriter, RoundTripIsExact) {
    C3dTake t = syntheticTake(40, {"male:LFHD", "male:RFHD", "male:LHipAngles", "male:LKneeForce",
                                   "male:LKneeMoment", "male:LKneePower", "Speed", "CLAV"});
    t.points[2].kind = C3dPointKind::Angle;
    t.points[3].kind = C3dPointKind::Force;
    t.points[4].kind = C3dPointKind::Moment;
    t.points[5].kind = C3dPointKind::Power;
    t.points[6].kind = C3dPointKind::Scalar;
    t.points[0].description = "left front head";
    t.units = "cm";  // 4000 units across: 40 m, a span a take may have (in metres, warned of)
    t.rate = 250.0;
    t.firstFrame = 17;
    t.parameters.addGroup("MYGROUP", "kept as is").locked = true;
    C3dParameter custom = C3dParameter::int16s("GRID", {1, -2, 3, -4, 5, -6}, {3, 2});
    custom.description = "a 3x2 grid";
    custom.locked = true;
    t.parameters.set("MYGROUP", custom);

    const C3dTake r = roundTrip(t);
    EXPECT_EQ(r.processor, C3dProcessor::Intel);
    EXPECT_EQ(r.storage, C3dStorage::Float);
    EXPECT_DOUBLE_EQ(r.rate, 250.0);
    EXPECT_EQ(r.units, "cm");
    EXPECT_DOUBLE_EQ(r.unitToMm, 10.0);
    EXPECT_EQ(r.firstFrame, 17);
    EXPECT_EQ(r.firstFrameWord, 17);
    EXPECT_EQ(r.lastFrameWord, 56);
    EXPECT_EQ(r.analogChannels, 0);
    EXPECT_TRUE(r.warnings.empty()) << r.warnings.front();
    ASSERT_EQ(r.points.size(), t.points.size());
    for (std::size_t k = 0; k < t.points.size(); ++k) {
        EXPECT_EQ(r.points[k].label, t.points[k].label);
        EXPECT_EQ(r.points[k].subject, t.points[k].subject);
        EXPECT_EQ(r.points[k].name, t.points[k].name);
        EXPECT_EQ(r.points[k].description, t.points[k].description);
        EXPECT_EQ(r.points[k].kind, t.points[k].kind) << t.points[k].label;
    }
    expectExactSamples(t, r);
    EXPECT_GT(r.samples.missingCount(), 0u);

    const C3dGroup* g = r.parameters.group("MYGROUP");
    ASSERT_NE(g, nullptr);
    EXPECT_TRUE(g->locked);
    EXPECT_EQ(g->description, "kept as is");
    const C3dParameter* grid = g->find("grid");  // names are case-insensitive
    ASSERT_NE(grid, nullptr);
    EXPECT_EQ(grid->dims(), (std::vector<int>{3, 2}));
    EXPECT_EQ(grid->numbers(), (std::vector<double>{1, -2, 3, -4, 5, -6}));
    EXPECT_TRUE(grid->locked);
    EXPECT_EQ(grid->description, "a 3x2 grid");

    // Re-encoding what was read gives the same bytes: nothing drifts on a second trip.
    EXPECT_EQ(encodeC3d(r), encodeC3d(roundTrip(r)));
}

TEST(C3dWriter, MissingSamplesHaveNegativeResidual) {
    C3dTake t = syntheticTake(2, {"A", "B"});
    t.samples.setMissing(1, 1);
    const auto bytes = encodeC3d(t);
    const std::size_t dataStart = (c3d::u16(&bytes[16], C3dProcessor::Intel) - 1) * 512;
    const std::uint8_t* s = &bytes[dataStart + 16 * 3];  // frame 1, point 1
    EXPECT_EQ(c3d::f32(s + 12, C3dProcessor::Intel), -1.0f);
    const C3dTake r = roundTrip(t);
    EXPECT_FALSE(r.samples.position(1, 1).has_value());
    EXPECT_EQ(r.samples.residual(1, 1), -1.0f);
    EXPECT_FALSE(r.samples.valid(1, 1));
}

TEST(C3dWriter, MoreThan255LabelsContinueInLabels2) {
    const auto labels = numberedLabels(600, "subj:M");
    const C3dTake r = roundTrip(syntheticTake(3, labels));
    ASSERT_EQ(r.points.size(), 600u);
    for (std::size_t k = 0; k < 600; ++k) EXPECT_EQ(r.points[k].label, labels[k]);
    ASSERT_NE(r.parameters.find("POINT", "LABELS2"), nullptr);
    ASSERT_NE(r.parameters.find("POINT", "LABELS3"), nullptr);
    EXPECT_EQ(r.parameters.find("POINT", "LABELS")->strings().size(), 255u);
    EXPECT_EQ(r.parameters.find("POINT", "LABELS3")->strings().size(), 90u);
    EXPECT_EQ(r.points[599].subject, "subj");
}

TEST(C3dWriter, MoreThan65535FramesEveryVendorConvention) {
    struct Case {
        bool trial, longFrames;
        const char* framesFrom;
    } cases[] = {{true, true, "TRIAL and LONG_FRAMES"},
                 {true, false, "TRIAL"},
                 {false, true, "LONG_FRAMES"},
                 {false, false, "float POINT:FRAMES"}};
    const C3dTake t = syntheticTake(70001, {"A"});
    for (const auto& c : cases) {
        SCOPED_TRACE(c.framesFrom);
        C3dWriteOptions w;
        w.trialFrameRange = c.trial;
        w.longFrames = c.longFrames;
        const C3dTake r = roundTrip(t, w);
        EXPECT_EQ(r.frameCount(), 70001u);
        EXPECT_EQ(r.lastFrameWord, 65535);
        EXPECT_EQ(r.parameters.find("TRIAL", "ACTUAL_END_FIELD") != nullptr, c.trial);
        EXPECT_EQ(r.parameters.find("POINT", "LONG_FRAMES") != nullptr, c.longFrames);
        expectExactSamples(t, r);
    }
}

// Found by the fuzzer: a take with no frames whose first frame number needs TRIAL was written
// with a one-frame TRIAL range, and the file did not read back.
TEST(C3dWriter, EmptyTakeWithLargeFirstFrameReadsBack) {
    for (std::size_t frames : {0u, 1u, 65535u}) {
        SCOPED_TRACE(frames);
        C3dTake t = syntheticTake(frames, {"A", "B"});
        t.firstFrame = 70000;
        const C3dTake r = roundTrip(t);
        EXPECT_EQ(r.frameCount(), frames);
        EXPECT_EQ(r.firstFrame, 70000);
        EXPECT_TRUE(r.warnings.empty()) << r.warnings.front();
    }
}

TEST(C3dWriter, Int16StorageIsScaled) {
    const C3dTake t = syntheticTake(20, {"A", "B", "C"});
    const float scale = 0.125f;
    const auto bytes = toInt16(encodeC3d(t), scale, 20);
    const C3dTake r = readC3dMemory(bytes.data(), bytes.size(), "int16.c3d");
    EXPECT_EQ(r.storage, C3dStorage::Int16);
    EXPECT_DOUBLE_EQ(r.pointScale, 0.125);
    ASSERT_EQ(r.frameCount(), 20u);
    for (std::size_t f = 0; f < 20; ++f)
        for (std::size_t k = 0; k < 3; ++k) {
            ASSERT_EQ(r.samples.valid(f, k), t.samples.valid(f, k));
            if (!t.samples.valid(f, k)) continue;
            const Eigen::Vector3d d = *r.samples.position(f, k) - *t.samples.position(f, k);
            EXPECT_LE(d.cwiseAbs().maxCoeff(), scale / 2 + 1e-9);
            // Int16 values times the scale: every coordinate is a multiple of it.
            const double x = (*r.samples.position(f, k))[0] / scale;
            EXPECT_EQ(x, std::round(x));
        }
}

TEST(C3dWriter, APointScaleWhoseStorageTheFileCannotHoldGivesWayToTheHeaders) {
    const C3dTake t = syntheticTake(20, {"A", "B", "C"});
    auto bytes = toInt16(encodeC3d(t), 0.125f, 20);
    c3d::putF32(&bytes[valueOffset(bytes, "POINT", "SCALE")], -0.125f);  // float, by its sign
    const C3dTake r = readC3dMemory(bytes.data(), bytes.size(), "signs.c3d");
    EXPECT_EQ(r.storage, C3dStorage::Int16);
    EXPECT_DOUBLE_EQ(r.pointScale, 0.125);
    EXPECT_TRUE(hasWarning(r, "only the header's fits the file's size"))
        << ::testing::PrintToString(r.warnings);
    EXPECT_FALSE(hasWarning(r, "; using POINT:SCALE")) << ::testing::PrintToString(r.warnings);
    ASSERT_EQ(r.frameCount(), 20u);
    for (std::size_t f = 0; f < 20; ++f)
        for (std::size_t k = 0; k < 3; ++k) {
            ASSERT_EQ(r.samples.valid(f, k), t.samples.valid(f, k));
            if (t.samples.valid(f, k))
                EXPECT_LE((*r.samples.position(f, k) - *t.samples.position(f, k)).norm(), 0.2);
        }
    // A float file holds int16's frames too: there POINT:SCALE keeps its word, with a warning.
    auto floats = encodeC3d(t);
    c3d::putF32(&floats[12], 0.125f);
    const C3dTake f = readC3dMemory(floats.data(), floats.size(), "header.c3d");
    EXPECT_EQ(f.storage, C3dStorage::Float);
    EXPECT_TRUE(hasWarning(f, "using POINT:SCALE")) << ::testing::PrintToString(f.warnings);
}

// From a user's probe of other writers' files (2 December 2026): POINT:SCALE stored as an int16
// -1 was read as 65535, so a short float take was read as int16 with a 3786 km span.
TEST(C3dWriter, APointScaleStoredAsInt16IsSigned) {
    const C3dTake t = syntheticTake(6, {"A", "B", "C"});
    auto bytes = encodeC3d(t);
    const std::size_t value = valueOffset(bytes, "POINT", "SCALE");
    ASSERT_EQ(bytes[value - 2], 4);  // float, no dimensions
    bytes[value - 2] = 2;            // int16: the record's offset still skips its 4 bytes
    c3d::putU16(&bytes[value], 0xFFFF);
    const C3dTake r = readC3dMemory(bytes.data(), bytes.size(), "int16scale.c3d");
    EXPECT_EQ(r.storage, C3dStorage::Float);
    EXPECT_DOUBLE_EQ(r.pointScale, -1.0);
    EXPECT_FALSE(hasWarning(r, "65535")) << ::testing::PrintToString(r.warnings);
    ASSERT_EQ(r.frameCount(), 6u);
    for (std::size_t f = 0; f < 6; ++f)  // the residuals scale with |POINT:SCALE|, now 1
        for (std::size_t k = 0; k < 3; ++k) {
            ASSERT_EQ(r.samples.valid(f, k), t.samples.valid(f, k));
            if (t.samples.valid(f, k))
                EXPECT_EQ(*r.samples.position(f, k), *t.samples.position(f, k));
        }
}

// The standard says POINT:LONG_FRAMES overrides POINT:FRAMES; a writer that wrapped FRAMES to
// 16 bits (70001 as 4465) lost 65,536 frames, with a warning only that the header disagreed.
TEST(C3dWriter, LongFramesOverridesAWrappedPointFrames) {
    const C3dTake t = syntheticTake(70001, {"A"});
    C3dWriteOptions w;
    w.trialFrameRange = false;
    auto bytes = encodeC3d(t, w);
    c3d::putU16(&bytes[valueOffset(bytes, "POINT", "FRAMES")], 70001 % 65536);
    const C3dTake r = readC3dMemory(bytes.data(), bytes.size(), "wrapped.c3d");
    EXPECT_EQ(r.frameCount(), 70001u);
    expectExactSamples(t, r);
    // A FRAMES that is neither saturated nor the wrap (a tool trimmed the take and left
    // LONG_FRAMES) is the count, with a warning.
    c3d::putU16(&bytes[valueOffset(bytes, "POINT", "FRAMES")], 100);
    const C3dTake trimmed = readC3dMemory(bytes.data(), bytes.size(), "trimmed.c3d");
    EXPECT_EQ(trimmed.frameCount(), 100u);
    EXPECT_TRUE(hasWarning(trimmed, "POINT:LONG_FRAMES 70001 disagrees with POINT:FRAMES 100"))
        << ::testing::PrintToString(trimmed.warnings);
}

// A label written as a C string in its fixed-width field kept the buffer's leftover after the NUL
// ("LFHD\0ab"), and a map naming LFHD did not find it.
TEST(C3dWriter, ALabelEndsAtItsFirstNul) {
    const C3dTake t = syntheticTake(3, {std::string("LFHD\0ab", 7), "RFHD"});
    const C3dTake r = roundTrip(t);
    ASSERT_EQ(r.points.size(), 2u);
    EXPECT_EQ(r.points[0].label, "LFHD");
    EXPECT_EQ(r.points[1].label, "RFHD");
}

// CMU 85_02 with POINT:SCALE made +10 (int16) and the header's -0.05 (float) left: int16 frames
// fit in the first half of its data, and were read so, coordinates like -133720.
TEST(C3dWriter, AFloatFileWhosePointScaleSaysInt16IsReadAsFloatsByItsDataSize) {
    const C3dTake t = syntheticTake(100, {"A", "B", "C"});
    auto bytes = encodeC3d(t);
    c3d::putF32(&bytes[valueOffset(bytes, "POINT", "SCALE")], 10.0f);
    const C3dTake r = readC3dMemory(bytes.data(), bytes.size(), "scale.c3d");
    EXPECT_EQ(r.storage, C3dStorage::Float);
    EXPECT_TRUE(hasWarning(r,
                           "the 3D data section is the size of 100 float frames, using the "
                           "header's"))
        << ::testing::PrintToString(r.warnings);
    ASSERT_EQ(r.frameCount(), 100u);
    for (std::size_t f = 0; f < 100; ++f)
        for (std::size_t k = 0; k < 3; ++k) {
            ASSERT_EQ(r.samples.valid(f, k), t.samples.valid(f, k));
            if (t.samples.valid(f, k))
                EXPECT_LE((*r.samples.position(f, k) - *t.samples.position(f, k)).norm(), 1e-3);
        }
}

TEST(C3dWriter, ZeroSamplesAreMissingUnlessKept) {
    C3dTake t = syntheticTake(3, {"A", "B"});
    t.samples.set(1, 0, 0.0, 0.0, 0.0, 0.5f);
    const C3dTake dropped = roundTrip(t);
    EXPECT_FALSE(dropped.samples.valid(1, 0));
    EXPECT_TRUE(hasWarning(dropped, "(0, 0, 0)"));
    C3dReadOptions keep;
    keep.keepZeroSamples = true;
    const C3dTake kept = roundTrip(t, {}, keep);
    ASSERT_TRUE(kept.samples.valid(1, 0));
    EXPECT_EQ(*kept.samples.position(1, 0), Eigen::Vector3d::Zero());
}

TEST(C3dWriter, HeaderDisagreementTrustsParametersAndWarns) {
    auto bytes = encodeC3d(syntheticTake(5, {"A", "B", "C"}));
    c3d::putU16(&bytes[2], 2);       // header: 2 points
    c3d::putU16(&bytes[8], 4);       // header: last frame 4
    c3d::putF32(&bytes[20], 60.0f);  // header: 60 Hz
    const C3dTake r = readC3dMemory(bytes.data(), bytes.size(), "disagree.c3d");
    EXPECT_EQ(r.points.size(), 3u);
    EXPECT_EQ(r.frameCount(), 5u);
    EXPECT_DOUBLE_EQ(r.rate, 120.0);
    EXPECT_TRUE(hasWarning(r, "POINT:USED"));
    EXPECT_TRUE(hasWarning(r, "POINT:RATE"));
    EXPECT_TRUE(hasWarning(r, "header frames"));
}

TEST(C3dWriter, UnusableParameterFallsBackToTheHeader) {
    auto bytes = encodeC3d(syntheticTake(5, {"A", "B"}));
    c3d::putF32(&bytes[valueOffset(bytes, "POINT", "RATE")], std::nanf(""));
    const C3dTake r = readC3dMemory(bytes.data(), bytes.size(), "nan-rate.c3d");
    EXPECT_DOUBLE_EQ(r.rate, 120.0);  // from the header
    EXPECT_TRUE(hasWarning(r, "POINT:RATE is nan"));
    EXPECT_EQ(r.frameCount(), 5u);
}

TEST(C3dWriter, WithoutParametersTheHeaderIsUsed) {
    auto bytes = encodeC3d(syntheticTake(5, {"A", "B", "C"}));
    bytes[0] = 0;  // no parameter section
    const C3dTake r = readC3dMemory(bytes.data(), bytes.size(), "noparams.c3d");
    EXPECT_EQ(r.points.size(), 3u);
    EXPECT_EQ(r.frameCount(), 5u);
    EXPECT_DOUBLE_EQ(r.rate, 120.0);
    EXPECT_EQ(r.points[2].label, "P3");
    EXPECT_TRUE(hasWarning(r, "no parameter section"));
}

TEST(C3dWriter, ParameterSectionLongerThanDeclaredIsReadToItsEnd) {
    auto bytes = encodeC3d(syntheticTake(2, numberedLabels(300)));
    ASSERT_GE(bytes[512 + 2], 2);  // the labels need more than one block
    bytes[512 + 2] = 1;
    const C3dTake r = readC3dMemory(bytes.data(), bytes.size(), "short-declared.c3d");
    EXPECT_EQ(r.points.size(), 300u);
    EXPECT_EQ(r.points[299].label, "M299");
    EXPECT_TRUE(hasWarning(r, "declares 1 blocks"));
}

TEST(C3dWriter, TruncatedDataKeepsCompleteFrames) {
    const auto full = encodeC3d(syntheticTake(10, {"A", "B"}));
    std::vector<std::uint8_t> cut(full.begin(), full.end() - 40);  // 1.25 frames short
    const C3dTake r = readC3dMemory(cut.data(), cut.size(), "cut.c3d");
    EXPECT_EQ(r.frameCount(), 8u);
    EXPECT_TRUE(hasWarning(r, "truncated"));
    const std::size_t dataStart = (c3d::u16(&full[16], C3dProcessor::Intel) - 1) * 512;
    std::vector<std::uint8_t> none(full.begin(), full.begin() + dataStart + 20);
    EXPECT_THROW(readC3dMemory(none.data(), none.size(), "none.c3d"), C3dError);
}

TEST(C3dWriter, UnitsAreScaledToMillimetres) {
    EXPECT_EQ(c3dUnitToMm("mm"), 1.0);
    EXPECT_EQ(c3dUnitToMm("cm"), 10.0);
    EXPECT_EQ(c3dUnitToMm("m"), 1000.0);
    EXPECT_EQ(c3dUnitToMm("mete"), 1000.0);  // truncated "meters"
    EXPECT_EQ(c3dUnitToMm("Metres"), 1000.0);
    EXPECT_EQ(c3dUnitToMm("millim"), 1.0);
    EXPECT_EQ(c3dUnitToMm("cent"), 10.0);
    EXPECT_EQ(c3dUnitToMm(" mm "), 1.0);
    EXPECT_EQ(c3dUnitToMm("in"), 25.4);
    EXPECT_FALSE(c3dUnitToMm("me").has_value());  // too short to tell
    EXPECT_FALSE(c3dUnitToMm("parsec").has_value());
    C3dTake t = syntheticTake(1, {"A"});
    t.units = "mete";
    EXPECT_EQ(roundTrip(t).unitToMm, 1000.0);
}

TEST(C3dTake, FindPointIgnoresSubjectPrefix) {
    C3dTake t = syntheticTake(1, {"male:LFHD", "female:LFHD", "RFHD"});
    EXPECT_EQ(t.findPoint("male:LFHD"), 0u);
    EXPECT_EQ(t.findPoint("female:LFHD"), 1u);
    EXPECT_EQ(t.findPoint("other:RFHD"), 2u);
    EXPECT_EQ(t.findPoint("rfhd "), 2u);
    EXPECT_FALSE(t.findPoint("LBHD").has_value());
}

// "other:T10" found walker:T10: a prefix the take has no subject for now finds only a point
// without a prefix.
TEST(C3dTake, APrefixNamingNoSubjectOfTheTakeFindsNoOtherSubjectsPoint) {
    C3dTake t = syntheticTake(1, {"walker:T10", "Walker:C7", "RFHD"});
    EXPECT_FALSE(t.findPoint("other:T10").has_value());
    EXPECT_TRUE(t.pointsNamed("other:T10").empty());
    EXPECT_EQ(t.findPoint("walker:T10"), 0u);
    EXPECT_EQ(t.findPoint("WALKER:c7"), 1u);
    EXPECT_EQ(t.findPoint("T10"), 0u);
    EXPECT_EQ(t.findPoint("other:RFHD"), 2u);
}

TEST(C3dTake, ABareNameTwoSubjectsWearFindsNeitherAndShortLabelsKeepTheirSubject) {
    C3dTake t = syntheticTake(1, {"male:LFHD", "female:LFHD", "male:RFHD"});
    EXPECT_FALSE(t.findPoint("LFHD").has_value());
    EXPECT_EQ(t.pointsNamed("lfhd "), (std::vector<std::size_t>{0, 1}));
    EXPECT_EQ(t.shortLabel(0), "male:LFHD");
    EXPECT_EQ(t.shortLabel(1), "female:LFHD");
    EXPECT_EQ(t.shortLabel(2), "RFHD");
}

TEST(C3dTake, MissingSampleIsNeverAPosition) {
    C3dSamples s(2, 2);
    EXPECT_FALSE(s.position(0, 0).has_value());
    s.set(0, 0, 1.0, 2.0, 3.0);
    EXPECT_EQ(*s.position(0, 0), Eigen::Vector3d(1, 2, 3));
    s.set(0, 1, std::nan(""), 0.0, 0.0);  // not a position either
    EXPECT_FALSE(s.valid(0, 1));
    s.setMissing(0, 0);
    EXPECT_FALSE(s.position(0, 0).has_value());
    EXPECT_FALSE(s.valid(0, 0));
    EXPECT_EQ(s.missingFrames(0), 2u);
    EXPECT_THROW(s.position(2, 0), std::out_of_range);
    EXPECT_THROW(s.valid(0, 2), std::out_of_range);
}
