// The take's vertical: the axis POINT:Y_SCREEN names, else +Z, reversed only when the markers
// lie below the origin along it and their floor is at its top; the same whether the take is
// read whole or streamed.
#include <gtest/gtest.h>

#include <cmath>
#include <optional>

#include "C3dTestSupport.h"
#include "boneless/C3dFrameReader.h"

using namespace boneless;

namespace {

// A 600-frame take of 12 markers over a floor: marker 0 on it, the others up to 1.7 m above it,
// crouching and standing by turns. `up` is the take's true up (a signed axis), `origin` how far
// the lab's origin is above the floor along it in frame f, and `yScreen` what the file says.
std::string writeTake(const std::string& name, const Eigen::Vector3d& up,
                      const std::function<double(std::size_t f)>& origin,
                      const std::optional<std::string>& yScreen) {
    C3dTake t = c3dtest::syntheticTake(600, c3dtest::numberedLabels(12));
    int axis = 0;
    up.cwiseAbs().maxCoeff(&axis);
    for (std::size_t f = 0; f < t.frameCount(); ++f) {
        const double crouch = 0.7 + 0.3 * std::sin(0.05 * double(f));
        for (std::size_t k = 0; k < t.points.size(); ++k)
            if (auto p = t.samples.position(f, k)) {
                const double height = k == 0 ? 10.0 : 10.0 + crouch * 1700.0 * double(k) / 11.0;
                (*p)[axis] = up[axis] * (height - origin(f));
                t.samples.set(f, k, p->x(), p->y(), p->z(), t.samples.residual(f, k));
            }
    }
    if (yScreen) t.parameters.set("POINT", C3dParameter::chars("Y_SCREEN", {*yScreen}));
    const std::string path = (c3dtest::workDir() / name).string();
    writeC3d(t, path);
    return path;
}

double onTheFloor(std::size_t) {
    return 0.0;
}

std::string upWarning(const C3dTake& take) {
    for (const std::string& w : take.warnings)
        if (w.find("for the take's up") != std::string::npos) return w;
    return "";
}

// The vertical of the take at `path`, read whole and streamed, which must agree, with the
// warning about it (empty for none).
Eigen::Vector3d verticalOf(const std::string& path, std::string* warning = nullptr) {
    const C3dTake whole = readC3d(path);
    const C3dFrameReader streamed(path);
    EXPECT_EQ(whole.vertical, streamed.take().vertical) << path;
    EXPECT_EQ(streamed.take().warnings, whole.warnings) << path;
    if (warning)
        *warning = upWarning(whole);
    else
        EXPECT_EQ(upWarning(whole), "") << path;
    return whole.vertical;
}

const Eigen::Vector3d X = Eigen::Vector3d::UnitX(), Y = Eigen::Vector3d::UnitY(),
                      Z = Eigen::Vector3d::UnitZ();

}  // namespace

TEST(C3dVertical, TheAxisYScreenNamesIsTheTakesUp) {
    EXPECT_EQ(verticalOf(writeTake("y_up.c3d", Y, onTheFloor, "+Y")), Y);
    EXPECT_EQ(verticalOf(writeTake("x_down.c3d", -X, onTheFloor, " -x ")), -X);
    EXPECT_EQ(verticalOf(writeTake("z_up.c3d", Z, onTheFloor, std::nullopt)), Z);
}

// numediart's 03_rolling says Y_SCREEN -Z, with its floor at z = 0 and the actor above it.
TEST(C3dVertical, AYScreenThatPointsUnderTheFloorIsReversedWithAWarning) {
    std::string warning;
    EXPECT_EQ(verticalOf(writeTake("minus_z.c3d", Z, onTheFloor, "-Z"), &warning), Z);
    EXPECT_NE(warning.find("POINT:Y_SCREEN says -z points up, but 100% of the markers lie below"),
              std::string::npos)
        << warning;
    EXPECT_NE(warning.find("taking +z for the take's up"), std::string::npos) << warning;
    EXPECT_EQ(verticalOf(writeTake("z_down.c3d", -Z, onTheFloor, std::nullopt), &warning), -Z);
    EXPECT_NE(warning.find("does not say which axis points up"), std::string::npos) << warning;
}

// A lab whose origin is above the actor, or at hip height, says nothing about the file's sign:
// the floor is still at the bottom, or the markers on both sides.
TEST(C3dVertical, AnOriginAboveTheActorOrAtHipHeightLeavesTheFilesWord) {
    const auto high = [](std::size_t) { return 3000.0; };
    EXPECT_EQ(verticalOf(writeTake("high_origin.c3d", Z, high, "+Z")), Z);
    EXPECT_EQ(verticalOf(writeTake("high_no_screen.c3d", Z, high, std::nullopt)), Z);
    const auto hips = [](std::size_t) { return 900.0; };
    EXPECT_EQ(verticalOf(writeTake("hips.c3d", -Z, hips, "-Z")), -Z);
}

// Judged on the first 256 frames, this take would be reversed (its origin is above the floor
// there); over frames spread across the take, half its markers lie above. Both readers must
// judge the spread frames.
TEST(C3dVertical, BothReadersJudgeFramesSpreadOverTheTake) {
    const auto late = [](std::size_t f) { return f < 300 ? 0.0 : 3000.0; };
    EXPECT_EQ(verticalOf(writeTake("half.c3d", Z, late, "-Z")), -Z);
}

TEST(C3dVertical, AYScreenNamingNoAxisIsSaidAndPlusZTaken) {
    std::string warning;
    EXPECT_EQ(verticalOf(writeTake("unsigned.c3d", Z, onTheFloor, "Y"), &warning), Z);
    EXPECT_NE(warning.find("POINT:Y_SCREEN is \"Y\", which names no axis"), std::string::npos)
        << warning;
}
