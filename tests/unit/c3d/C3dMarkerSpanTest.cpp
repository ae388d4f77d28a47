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
