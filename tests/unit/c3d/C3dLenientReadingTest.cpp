// Files other readers (BTK, Mokka) open with a warning open here too. Each case is made by the
// project's own writer, so no outside file is needed.

#include <gtest/gtest.h>

#include <algorithm>

#include "C3dTestSupport.h"

using namespace boneless;

namespace {

bool anyWarningHas(const C3dTake& t, const std::string& text) {
    return std::any_of(t.warnings.begin(), t.warnings.end(),
                       [&](const std::string& w) { return w.find(text) != std::string::npos; });
}

bool contains(const std::vector<std::uint8_t>& bytes, const std::string& needle) {
    const auto same = [](std::uint8_t b, char c) { return b == static_cast<unsigned char>(c); };
    return std::search(bytes.begin(), bytes.end(), needle.begin(), needle.end(), same) !=
           bytes.end();
}

const std::string& kSubject = c3dtest::kLatin1Subject;
const std::string& kDescription = c3dtest::kLatin1Description;
using c3dtest::latin1Take;

}  // namespace

TEST(C3dLenientReading, ParameterAndGroupNamesWithSpacesAreRead) {
    C3dTake t = c3dtest::syntheticTake(3, {"A", "B"});
    t.parameters.addGroup("SUBJECT INFO", "as Qualisys writes it")
        .set(C3dParameter::int16s("MARKER COUNT", {2}));
    const std::vector<std::uint8_t> bytes = encodeC3d(t);
    ASSERT_TRUE(contains(bytes, "SUBJECT INFO"));
    const C3dTake back = readC3dMemory(bytes.data(), bytes.size(), "spaces.c3d");
    const C3dParameter* p = back.parameters.find("SUBJECT INFO", "MARKER COUNT");
    ASSERT_NE(p, nullptr);
    EXPECT_EQ(p->number(), 2.0);
    EXPECT_EQ(back.frameCount(), 3u);
    // Written back, the names keep their spaces.
    const std::vector<std::uint8_t> again = encodeC3d(back);
    EXPECT_TRUE(contains(again, "MARKER COUNT"));
}

TEST(C3dLenientReading, NameWithAControlCharacterIsStillCorrupt) {
    C3dTake t = c3dtest::syntheticTake(2, {"A"});
    t.parameters.addGroup("USER").set(C3dParameter::int16s("ODD_NAME", {1}));
    std::vector<std::uint8_t> bytes = encodeC3d(t);
    const std::string name = "ODD_NAME";
    auto at = std::search(bytes.begin(), bytes.end(), name.begin(), name.end());
    ASSERT_NE(at, bytes.end());
    at[3] = 0x07;
    EXPECT_THROW(readC3dMemory(bytes.data(), bytes.size(), "bell.c3d"), C3dError);
}

TEST(C3dLenientReading, HeaderDataStartZeroDefersToPointDataStartWithAWarning) {
    const C3dTake t = c3dtest::syntheticTake(5, {"A", "B", "C"});
    std::vector<std::uint8_t> bytes = encodeC3d(t);
    bytes[16] = bytes[17] = 0;  // header word 9
    const C3dTake back = readC3dMemory(bytes.data(), bytes.size(), "start0.c3d");
    EXPECT_TRUE(anyWarningHas(back, "POINT:DATA_START")) << ::testing::PrintToString(back.warnings);
    ASSERT_EQ(back.frameCount(), 5u);
    for (std::size_t f = 0; f < 5; ++f)
        for (std::size_t k = 0; k < 3; ++k) {
            ASSERT_EQ(back.samples.valid(f, k), t.samples.valid(f, k));
            if (t.samples.valid(f, k))
                EXPECT_EQ(*back.samples.position(f, k), *t.samples.position(f, k));
        }
}

TEST(C3dLenientReading, HeaderDataStartZeroWithoutTheParameterIsRejected) {
    C3dTake t = c3dtest::syntheticTake(5, {"A"});
    std::vector<std::uint8_t> bytes = encodeC3d(t);
    bytes[16] = bytes[17] = 0;
    const std::string name = "DATA_START";
    auto at = std::search(bytes.begin(), bytes.end(), name.begin(), name.end());
    ASSERT_NE(at, bytes.end());
    at[0] = 'X';  // the parameter is now XATA_START, unknown
    EXPECT_THROW(readC3dMemory(bytes.data(), bytes.size(), "nostart.c3d"), C3dError);
}

TEST(C3dLenientReading, Latin1LabelsAreWrittenAsLatin1Bytes) {
    const std::vector<std::uint8_t> bytes = encodeC3d(latin1Take());
    EXPECT_TRUE(contains(bytes, "M\xFCller:LFHD"));
    EXPECT_TRUE(contains(bytes, "Kniewinkel \xE4"));
    EXPECT_FALSE(contains(bytes, kSubject));
}

TEST(C3dLenientReading, Latin1LabelsReadAsUtf8AndWriteBackAsLatin1) {
    const std::vector<std::uint8_t> bytes = encodeC3d(latin1Take());
    const C3dTake back = readC3dMemory(bytes.data(), bytes.size(), "latin1.c3d");
    EXPECT_EQ(back.textEncoding, C3dTextEncoding::Latin1);
    EXPECT_TRUE(anyWarningHas(back, "Latin-1"));
    ASSERT_EQ(back.points.size(), 3u);
    EXPECT_EQ(back.points[0].label, kSubject + ":LFHD");
    EXPECT_EQ(back.points[0].subject, kSubject);
    EXPECT_EQ(back.points[1].description, kDescription);
    EXPECT_EQ(back.points[1].kind, C3dPointKind::Angle);  // the ANGLES list is Latin-1 too
    EXPECT_TRUE(back.findPoint("LFHD").has_value());
    // Written back (the parameter order may change), the text keeps its Latin-1 bytes.
    const std::vector<std::uint8_t> again = encodeC3d(back);
    EXPECT_TRUE(contains(again, "M\xFCller:LFHD"));
    EXPECT_TRUE(contains(again, "Kniewinkel \xE4"));
    EXPECT_FALSE(contains(again, kSubject));
}

TEST(C3dLenientReading, Utf8LabelsStayUtf8) {
    C3dTake t = latin1Take();
    t.textEncoding = C3dTextEncoding::Utf8;
    const C3dTake back = c3dtest::roundTrip(t);
    EXPECT_EQ(back.textEncoding, C3dTextEncoding::Utf8);
    EXPECT_EQ(back.points[0].label, kSubject + ":LFHD");
    EXPECT_FALSE(anyWarningHas(back, "Latin-1"));
}
