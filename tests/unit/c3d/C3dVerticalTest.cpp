// The take's vertical: the axis POINT:Y_SCREEN names, else +Z, reversed when the markers lie
// below the origin along it; the same whether the take is read whole or streamed.
#include <gtest/gtest.h>

#include <cmath>
#include <optional>

#include "C3dTestSupport.h"
#include "boneless/C3dFrameReader.h"

using namespace boneless;

namespace {

// A 600-frame take whose markers stand on the side `side` (+1 above, -1 below, 0 either) of
// the origin along coordinate `axis`, saying `yScreen` when given.
std::string writeTake(const std::string& name, int axis, int side,
                      const std::optional<std::string>& yScreen) {
    C3dTake t = c3dtest::syntheticTake(600, c3dtest::numberedLabels(12));
    for (std::size_t f = 0; f < t.frameCount(); ++f)
        for (std::size_t k = 0; k < t.points.size(); ++k)
            if (auto p = t.samples.position(f, k)) {
                if (side != 0) (*p)[axis] = side * (1.0 + std::abs((*p)[axis]));
                t.samples.set(f, k, p->x(), p->y(), p->z(), t.samples.residual(f, k));
            }
    if (yScreen) t.parameters.set("POINT", C3dParameter::chars("Y_SCREEN", {*yScreen}));
    const std::string path = (c3dtest::workDir() / name).string();
    writeC3d(t, path);
    return path;
}

bool saysUp(const C3dTake& take) {
    for (const std::string& w : take.warnings)
        if (w.find("for the take's up") != std::string::npos) return true;
    return false;
}

// The vertical of the take at `path`, read whole and streamed, which must agree.
Eigen::Vector3d verticalOf(const std::string& path, bool warned) {
    const C3dTake whole = readC3d(path);
    const C3dFrameReader streamed(path);
    EXPECT_EQ(whole.vertical, streamed.take().vertical) << path;
    EXPECT_EQ(saysUp(whole), warned) << path;
    EXPECT_EQ(streamed.take().warnings, whole.warnings) << path;
    return whole.vertical;
}

}  // namespace

TEST(C3dVertical, TheAxisYScreenNamesIsTheTakesUpWhenTheMarkersStandOnItsSide) {
    EXPECT_EQ(verticalOf(writeTake("y_up.c3d", 1, +1, "+Y"), false), Eigen::Vector3d::UnitY());
    EXPECT_EQ(verticalOf(writeTake("x_down.c3d", 0, -1, " -x "), false), -Eigen::Vector3d::UnitX());
}

// numediart's 03_rolling says Y_SCREEN -Z, with its floor at z = 0 and the actor above it.
TEST(C3dVertical, AYScreenThatPointsUnderTheFloorIsReversedWithAWarning) {
    const std::string path = writeTake("minus_z.c3d", 2, +1, "-Z");
    EXPECT_EQ(verticalOf(path, true), Eigen::Vector3d::UnitZ());
    const C3dTake take = readC3d(path);
    bool named = false;
    for (const std::string& w : take.warnings)
        named |= w.find("POINT:Y_SCREEN says -Z points up, but 100% of the markers lie below") !=
                     std::string::npos &&
                 w.find("taking +Z for the take's up") != std::string::npos;
    EXPECT_TRUE(named) << take.warnings.size();
}

TEST(C3dVertical, WithoutYScreenTheUpIsPlusZUnlessTheMarkersHangBelowIt) {
    EXPECT_EQ(verticalOf(writeTake("z_up.c3d", 2, +1, std::nullopt), false),
              Eigen::Vector3d::UnitZ());
    EXPECT_EQ(verticalOf(writeTake("z_down.c3d", 2, -1, std::nullopt), true),
              -Eigen::Vector3d::UnitZ());
}

// A lab whose origin is at hip height has markers on both sides: the file's word stands.
TEST(C3dVertical, MarkersOnBothSidesOfTheOriginLeaveTheFilesWord) {
    EXPECT_EQ(verticalOf(writeTake("both.c3d", 2, 0, "-Z"), false), -Eigen::Vector3d::UnitZ());
}
