// A take whose markers span no body in the units it states (CMU 85_02 in metres under "mm").
#include <gtest/gtest.h>

#include <fstream>

#include "C3dTestSupport.h"
#include "boneless/C3dFrameReader.h"
#include "boneless/C3dWriter.h"

using namespace boneless;

namespace {

// A synthetic take (markers spread over 4 m) with every coordinate times `factor`, its units
// left as written.
C3dTake scaledTake(double factor, const std::string& units = "mm") {
    C3dTake t = c3dtest::syntheticTake(200, c3dtest::numberedLabels(8));
    t.units = units;
    for (std::size_t f = 0; f < t.samples.frames(); ++f)
        for (std::size_t k = 0; k < t.samples.points(); ++k)
            if (const auto p = t.samples.position(f, k)) {
                const Eigen::Vector3d q = *p * factor;
                t.samples.set(f, k, q.x(), q.y(), q.z(), t.samples.residual(f, k));
            }
    return t;
}

bool hasWarning(const C3dTake& t, const std::string& needle) {
    for (const std::string& w : t.warnings)
        if (w.find(needle) != std::string::npos) return true;
    return false;
}

std::string written(const std::string& name, const C3dTake& t) {
    const std::string path = (c3dtest::workDir() / name).string();
    writeC3d(t, path);
    return path;
}

}  // namespace

TEST(C3dMarkerSpan, MetresUnderMillimetresAreDoubtedNamingTheSpanAndTheLikelyUnits) {
    const std::string path = written("metres.c3d", scaledTake(0.001));
    const C3dTake whole = readC3d(path);
    const C3dFrameReader streamed(path);
    for (const MarkerSpan& s : {whole.markerSpan, streamed.take().markerSpan}) {
        EXPECT_EQ(s.likelyUnits, "m");
        EXPECT_NE(s.doubt.find("its markers span"), std::string::npos) << s.doubt;
        EXPECT_NE(s.doubt.find("although POINT:UNITS says mm: are they in metres"),
                  std::string::npos)
            << s.doubt;
        EXPECT_GT(s.mm, 1.0);
        EXPECT_LT(s.mm, 10.0);
    }
    for (const C3dTake* t : {&whole, &streamed.take()})
        EXPECT_TRUE(hasWarning(*t, "its markers span")) << ::testing::PrintToString(t->warnings);
}

TEST(C3dMarkerSpan, MillimetresUnderMetresAreDoubtedToo) {
    const MarkerSpan s = readC3d(written("millimetres.c3d", scaledTake(1.0, "m"))).markerSpan;
    EXPECT_EQ(s.likelyUnits, "mm");
    EXPECT_NE(s.doubt.find("although POINT:UNITS says m: are they in millimetres"),
              std::string::npos)
        << s.doubt;
}

TEST(C3dMarkerSpan, ABodySizedTakeIsNotDoubted) {
    for (const auto& [factor, units] : {std::pair{1.0, "mm"}, {0.1, "cm"}, {0.001, "m"}}) {
        const C3dTake t = readC3d(written("body.c3d", scaledTake(factor, units)));
        const MarkerSpan& s = t.markerSpan;
        EXPECT_TRUE(s.doubt.empty()) << units << ": " << s.doubt;
        EXPECT_TRUE(s.likelyUnits.empty());
        EXPECT_NEAR(s.mm, 4000.0, 600.0) << units;
        EXPECT_FALSE(hasWarning(t, "its markers span")) << units;
    }
}

TEST(C3dMarkerSpan, TakeUnitsJudgeTheSpanAgainWithoutTheFramesAndTheDoubtNamesWhoSetThem) {
    const std::string path = written("metres-set.c3d", scaledTake(0.001));
    C3dTake whole = readC3d(path);
    C3dFrameReader streamed(path);
    setTakeUnits(whole, "m", "--take-units");
    streamed.setUnits("m", "--take-units");
    for (const C3dTake* t : {static_cast<const C3dTake*>(&whole), &streamed.take()}) {
        EXPECT_EQ(t->units, "m");
        EXPECT_EQ(t->unitToMm, 1000.0);
        EXPECT_EQ(t->unitsFrom, "--take-units");
        EXPECT_TRUE(t->markerSpan.doubt.empty()) << t->markerSpan.doubt;
        EXPECT_NEAR(t->markerSpan.mm, 4000.0, 600.0);
        EXPECT_FALSE(hasWarning(*t, "its markers span")) << ::testing::PrintToString(t->warnings);
    }
    // Units that make it no body's are doubted, naming what said them, not POINT:UNITS.
    setTakeUnits(whole, "cm", "\"take_units\"");
    EXPECT_NE(whole.markerSpan.doubt.find("although \"take_units\" says cm: are they in metres"),
              std::string::npos)
        << whole.markerSpan.doubt;
    EXPECT_EQ(whole.markerSpan.likelyUnits, "m");
    EXPECT_TRUE(hasWarning(whole, "although \"take_units\" says cm"));
    // The file's units again: the doubt as the reader gave it, once.
    setTakeUnits(whole, "file", "");
    const C3dTake read = readC3d(path);
    EXPECT_EQ(whole.units, "mm");
    EXPECT_EQ(whole.unitToMm, 1.0);
    EXPECT_TRUE(whole.unitsFrom.empty());
    EXPECT_EQ(whole.markerSpan.doubt, read.markerSpan.doubt);
    EXPECT_EQ(whole.warnings, read.warnings);
}

TEST(C3dMarkerSpan, TakeUnitsReplaceTheAssumedMillimetresOfATakeWithoutPointUnits) {
    C3dTake t = scaledTake(0.001);
    t.warnings = {"no POINT:UNITS; assuming millimetres"};
    setTakeUnits(t, "m", "--take-units");
    EXPECT_TRUE(t.warnings.empty()) << ::testing::PrintToString(t.warnings);
    setTakeUnits(t, "file", "");
    EXPECT_EQ(t.units, "mm");
    EXPECT_EQ(t.warnings, std::vector<std::string>{"no POINT:UNITS; assuming millimetres"});
}

TEST(C3dMarkerSpan, UnitsSetTakeUnitsDoesNotKnowAreRefusedNamingTheFile) {
    C3dTake t = scaledTake(1.0);
    t.file = "take.c3d";
    try {
        setTakeUnits(t, "yards", "--take-units");
        FAIL() << "yards were taken";
    } catch (const C3dError& e) {
        EXPECT_NE(std::string(e.what()).find("take.c3d"), std::string::npos) << e.what();
        EXPECT_NE(std::string(e.what()).find("\"yards\""), std::string::npos) << e.what();
    }
    // A spelled-out name the reader accepts from a file is no symbol of the option's.
    EXPECT_THROW(setTakeUnits(t, "metres", "--take-units"), C3dError);
    EXPECT_EQ(t.units, "mm");
}
