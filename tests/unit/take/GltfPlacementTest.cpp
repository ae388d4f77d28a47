#include <gtest/gtest.h>

#include "boneless/TakeExport.h"

using namespace boneless;

namespace {

// A take in millimetres standing on a mesh whose up is `up`, in units of `mmPerUnit`.
Similarity takeOnto(const Vec3& up, double mmPerUnit) {
    Similarity s;
    s.R = Eigen::Quaterniond::FromTwoVectors(Vec3::UnitZ(), up).toRotationMatrix();
    s.scale = 1.0 / mmPerUnit;
    return s;
}

}  // namespace

TEST(GltfPlacement, AZUpMeshInMetresIsTurnedUpright) {
    const GltfPlacement p = gltfPlacement(takeOnto(Vec3::UnitZ(), 1000.0), 1.0, Vec3::UnitZ());
    EXPECT_LT((p.turn * Vec3::UnitZ() - Vec3::UnitY()).norm(), 1e-12);
    EXPECT_NEAR(p.turn.determinant(), 1.0, 1e-12);
    EXPECT_DOUBLE_EQ(p.metresPerUnit, 1.0);
}

TEST(GltfPlacement, AYUpMeshInDecimetresKeepsItsAxesAndIsScaledToMetres) {
    // MakeHuman's: an actor of 1.7 m fits a body 16.5 units tall, not quite 1 dm a unit.
    const GltfPlacement p = gltfPlacement(takeOnto(Vec3::UnitY(), 103.0), 1.0, Vec3::UnitZ());
    EXPECT_LT((p.turn - Mat3::Identity()).norm(), 1e-12);
    EXPECT_DOUBLE_EQ(p.metresPerUnit, 0.1);
}

TEST(GltfPlacement, AMeshUpsideDownAlongYIsTurnedOver) {
    const GltfPlacement p = gltfPlacement(takeOnto(-Vec3::UnitY(), 10.0), 1.0, Vec3::UnitZ());
    EXPECT_LT((p.turn * -Vec3::UnitY() - Vec3::UnitY()).norm(), 1e-12);
    EXPECT_NEAR(p.metresPerUnit, 0.01, 1e-15);
}

TEST(GltfPlacement, ATakeInMetresIsReadInMillimetres) {
    // A take stored in metres (unitToMm 1000) on a mesh in centimetres: 100 units a metre.
    Similarity s = takeOnto(Vec3::UnitY(), 10.0);
    s.scale *= 1000.0;  // take units (m) to mesh units (cm)
    EXPECT_NEAR(gltfPlacement(s, 1000.0, Vec3::UnitZ()).metresPerUnit, 0.01, 1e-15);
}

// 3ds Max's default unit: a body modelled in inches was read as centimetres, and its glb came out
// 2.54 times too small (a 1.86 m walker 0.73 m tall).
TEST(GltfPlacement, AMeshInInchesOrFeetIsScaledToMetresByItsOwnUnit) {
    EXPECT_NEAR(
        gltfPlacement(takeOnto(Vec3::UnitY(), 25.4 * 1.04), 1.0, Vec3::UnitZ()).metresPerUnit,
        0.0254, 1e-15);
    EXPECT_STREQ(guessMeshUnits(1.0 / 25.4), "in");
    EXPECT_NEAR(
        gltfPlacement(takeOnto(Vec3::UnitY(), 304.8 * 0.95), 1.0, Vec3::UnitZ()).metresPerUnit,
        0.3048, 1e-15);
    EXPECT_STREQ(guessMeshUnits(1.0 / 304.8), "ft");
    EXPECT_STREQ(guessMeshUnits(0.1 * 1.2), "cm");  // an actor a fifth smaller than the mesh
    // A child's body modelled in cm, driven by an adult 1.64 times its size, is not in inches.
    EXPECT_STREQ(guessMeshUnits(0.1 / 1.64), "cm");
    EXPECT_STREQ(guessMeshUnits(0.01 / 1.75), "dm");
}

// The MakeHuman body scaled by 0.01 (17 cm tall) was "mesh units look like m" and came out of a
// glb 100 times too small with nothing said; a body that no unit makes a body's size is named.
TEST(GltfPlacement, AMeshThatNoUnitMakesTheActorsSizeIsSaidToBeWronglyScaled) {
    TriMesh body;  // 17.4 units tall along y, as a MakeHuman body in decimetres
    body.V.resize(3, 3);
    body.V << 0, 0, 0, 1, 17.4, 0, 0, 17.4, 1;
    body.F.resize(1, 3);
    body.F << 0, 1, 2;
    const double actorMm = 1740;
    EXPECT_EQ(meshScaleWarning(body, takeOnto(Vec3::UnitY(), actorMm / 17.4), 1.0, Vec3::UnitZ()),
              "");  // decimetres
    TriMesh small = body;
    small.V *= 0.01;
    EXPECT_EQ(meshScaleWarning(small, takeOnto(Vec3::UnitY(), actorMm / 0.174), 1.0, Vec3::UnitZ()),
              "mesh units look like m, but the body would be 17 cm tall: check the mesh's scale (a "
              ".glb "
              "export places it by that unit)");
    TriMesh tiny = body;
    tiny.V *= 0.001;
    EXPECT_NE(meshScaleWarning(tiny, takeOnto(Vec3::UnitY(), actorMm / 0.0174), 1.0, Vec3::UnitZ())
                  .find("but the body would be 1.7 cm tall"),
              std::string::npos);
    TriMesh huge = body;
    huge.V *= 1000;
    EXPECT_NE(meshScaleWarning(huge, takeOnto(Vec3::UnitY(), actorMm / 17400), 1.0, Vec3::UnitZ())
                  .find("mesh units look like mm, but the body would be 17 m tall"),
              std::string::npos);
    // A body's size in its unit (metres), and the take read ten times the actor's size (in mm,
    // given as cm): the take's units are what to check, not the mesh's scale.
    TriMesh metres = body;
    metres.V *= 0.1;
    EXPECT_EQ(meshScaleWarning(metres, takeOnto(Vec3::UnitY(), 1000.0), 10.0, Vec3::UnitZ()),
              "the take's markers make the body 17 m tall, where the mesh is 1.7 m tall in m: "
              "check the take's units");
    // Every unit between mm and m, and a child's body driven by an adult, says nothing.
    for (double unitMm : {1.0, 10.0, 100.0, 1000.0, 25.4, 304.8})
        for (double actorOverMesh : {0.6, 1.0, 1.7}) {
            TriMesh m = body;
            m.V *= 100.0 / unitMm / actorOverMesh;  // a body 1.74 m / actorOverMesh tall
            const double meshUnitsPerMm = m.V(1, 1) / actorMm;
            EXPECT_EQ(meshScaleWarning(m, takeOnto(Vec3::UnitY(), 1 / meshUnitsPerMm), 1.0,
                                       Vec3::UnitZ()),
                      "")
                << unitMm << " mm units, actor " << actorOverMesh;
        }
}
