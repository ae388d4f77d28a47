#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <functional>
#include <random>

#include "TestMeshes.h"
#include "boneless/Alignment.h"
#include "boneless/C3dReader.h"
#include "boneless/C3dTake.h"
#include "boneless/Error.h"
#include "boneless/MeshReader.h"

using namespace boneless;
using namespace boneless::testing;

TEST(Alignment, RecoversAKnownSimilarity) {
    std::mt19937 rng(2);
    std::uniform_real_distribution<double> u(-1, 1);
    Positions mesh(8, 3);
    for (int i = 0; i < 8; ++i) mesh.row(i) << u(rng), u(rng), u(rng);
    // The take: millimetres, another orientation, another origin.
    const Mat3 R = randomRotation(rng);
    Positions take(8, 3);
    const Vec3 origin(500, -200, 30);
    for (int i = 0; i < 8; ++i)
        take.row(i) = (1000.0 * R * mesh.row(i).transpose() + origin).transpose();
    take.row(3).setConstant(std::nan(""));  // a missing marker is skipped, not used
    const Similarity s = fitSimilarity(take, mesh);
    EXPECT_NEAR(s.scale, 1e-3, 1e-12);
    EXPECT_LT((s.R - R.transpose()).norm(), 1e-9);
    EXPECT_LT((s.apply(origin) - Vec3::Zero()).norm(), 1e-9);
    EXPECT_LT(alignmentResidual(s, take, mesh), 1e-9);
}

// A pose unlike the rest's tilts the free fit; the level one puts the take's +Z on the mesh's
// up exactly, keeps the scale, and still finds the turn about the vertical.
TEST(Alignment, LevelledPutsTheTakesVerticalOnTheMeshsUpAndFindsTheTurn) {
    std::mt19937 rng(3);
    std::uniform_real_distribution<double> u(-1, 1);
    Positions mesh(12, 3);  // Y up, taller than wide
    for (int i = 0; i < 12; ++i) mesh.row(i) << 0.3 * u(rng), 1 + u(rng), 0.2 * u(rng);
    // The take: Z up, millimetres, turned 40° about its vertical; upper markers lean forward.
    const Mat3 zUpToYUp = Eigen::AngleAxisd(-M_PI / 2, Vec3::UnitX()).toRotationMatrix();
    const Mat3 turn = Eigen::AngleAxisd(0.7, Vec3::UnitZ()).toRotationMatrix();
    Positions take(12, 3);
    for (int i = 0; i < 12; ++i) {
        Vec3 p = zUpToYUp.transpose() * mesh.row(i).transpose();
        p.x() += 0.15 * p.z();  // a lean: a shear, which no rotation undoes
        take.row(i) = (1000.0 * (turn * p) + Vec3(300, 100, 0)).transpose();
    }
    const Similarity free = fitSimilarity(take, mesh);
    const Similarity s = levelled(free, take, mesh, Vec3::UnitZ());
    EXPECT_GT((free.R * Vec3::UnitZ() - Vec3::UnitY()).norm(), 0.02) << "the free fit leans";
    EXPECT_LT((s.R * Vec3::UnitZ() - Vec3::UnitY()).norm(), 1e-12);
    EXPECT_EQ(s.scale, free.scale);
    // The turn: the take's forward (its +X turned by 40°) lands within a few degrees of the
    // mesh's, which the lean biases a little.
    const Vec3 forward = s.R * (turn * Vec3::UnitX());
    EXPECT_GT(forward.dot(Vec3::UnitX()), std::cos(5.0 * M_PI / 180)) << forward.transpose();
    // Without the lean, level and free agree: nothing to take out.
    for (int i = 0; i < 12; ++i)
        take.row(i) =
            (1000.0 * (turn * (zUpToYUp.transpose() * mesh.row(i).transpose())) + Vec3(3, 1, 0))
                .transpose();
    const Similarity exact = fitSimilarity(take, mesh);
    const Similarity same = levelled(exact, take, mesh, Vec3::UnitZ());
    EXPECT_LT((same.R - exact.R).norm(), 1e-9);
    EXPECT_LT((same.t - exact.t).norm(), 1e-9);
    EXPECT_LT(alignmentResidual(same, take, mesh), 1e-9);
}

TEST(Alignment, RefusesTooFewOrCollinearMarkers) {
    Positions a(3, 3), b(3, 3);
    a << 0, 0, 0, 1, 0, 0, 2, 0, 0;
    b = a;
    EXPECT_THROW(fitSimilarity(a, b), Error);
    EXPECT_THROW(fitSimilarity(a.topRows(2), b.topRows(2)), Error);
}

TEST(Alignment, CalibrationPicksTheFrameClosestToTheRestPose) {
    const TriMesh mesh = icosphere(1);
    const std::vector<int> ids{0, 5, 9, 11, 20, 33};
    const Positions rest = rows(mesh.V, ids);
    C3dTake take;
    take.file = "synthetic.c3d";
    take.points.resize(ids.size());
    take.samples = C3dSamples(5, ids.size());
    std::mt19937 rng(4);
    for (int f = 0; f < 5; ++f)
        for (size_t k = 0; k < ids.size(); ++k) {
            // Frame 3 is a scaled, moved copy of the rest pose; the others are squashed.
            const double squash = (f == 3) ? 1.0 : 0.7;
            const Vec3 p = rest.row(k).transpose();
            take.samples.set(f, k, 10 * p.x() + 1, 10 * p.y() * squash, 10 * p.z() + f);
        }
    take.samples.setMissing(1, 2);
    std::vector<std::size_t> points(ids.size());
    for (size_t k = 0; k < points.size(); ++k) points[k] = k;
    const Calibration c = calibrate(take, points, rest);
    EXPECT_EQ(c.frame, 3);
    // The take holds its samples as float, as a C3D file does: exact to about 1e-7 of their size.
    EXPECT_NEAR(c.takeToMesh.scale, 0.1, 1e-7);
    EXPECT_LT(c.residual, 1e-6);
    EXPECT_EQ(c.visibleMarkers, 6);
}

namespace {

struct Marker {
    const char* name;
    Vec3 at;  // front, left, height
};

// `markers` on an actor in millimetres, Z up, facing +X (left is +Y), standing away from the
// origin, which is on the floor; frame 1 lacks the fourth marker, so frame 0 shows the most.
C3dTake actorWith(const std::vector<Marker>& markers) {
    C3dTake take;
    take.file = "standing.c3d";
    for (const Marker& m : markers) take.points.push_back({m.name, "", m.name, "", {}});
    take.samples = C3dSamples(2, markers.size());
    const Vec3 origin(3000, 2000, 0);
    for (std::size_t f = 0; f < 2; ++f)
        for (std::size_t k = 0; k < markers.size(); ++k) {
            const Vec3 x = origin + markers[k].at;
            take.samples.set(f, k, x.x(), x.y(), x.z());
        }
    take.samples.setMissing(1, 3);
    return take;
}

// An actor 1.6 m tall.
C3dTake standingActor() {
    return actorWith({{"LFHD", {80, 70, 1650}},
                      {"RFHD", {80, -70, 1650}},
                      {"LBHD", {-80, 70, 1630}},
                      {"STRN", {100, 0, 1300}},
                      {"LANK", {0, 100, 80}},
                      {"RANK", {0, -100, 60}}});
}

// An icosphere stretched to a body's box: `extent` along x, y, z.
TriMesh bodyBox(const Vec3& extent) {
    TriMesh mesh = icosphere(2);
    for (int v = 0; v < mesh.vertexCount(); ++v)
        mesh.V.row(v) = mesh.V.row(v).cwiseProduct(0.5 * extent.transpose());
    return mesh;
}

Vec3 placed(const C3dTake& take, const Calibration& c, const char* name) {
    return c.takeToMesh.apply(*take.samples.position(c.frame, *take.findPoint(name)));
}

std::vector<std::size_t> allPoints(const C3dTake& take) {
    std::vector<std::size_t> points(take.points.size());
    for (std::size_t k = 0; k < points.size(); ++k) points[k] = k;
    return points;
}

}  // namespace

TEST(RoughAlignment, StandsTheActorUpOnAYUpMeshWithItsLeftOnTheMeshsLeft) {
    const C3dTake take = standingActor();
    const TriMesh mesh = bodyBox({17, 16, 3});  // a T-pose: wider than tall, still Y up
    const Calibration c = roughAlignment(take, allPoints(take), mesh);
    EXPECT_EQ(c.frame, 0);
    EXPECT_EQ(c.visibleMarkers, 6);
    EXPECT_NEAR(c.takeToMesh.scale, 16.0 / 1590, 1e-12);  // median height over the frames
    const Vec3 lfhd = placed(take, c, "LFHD"), rfhd = placed(take, c, "RFHD");
    const Vec3 rank = placed(take, c, "RANK"), strn = placed(take, c, "STRN");
    EXPECT_GT(lfhd.y(), 7.5);           // the head at the top of the mesh, which spans -8 to 8
    EXPECT_NEAR(rank.y(), -8.0, 1e-9);  // the lowest marker on the mesh's lowest point
    EXPECT_GT(lfhd.x(), 0.5);           // left on +X
    EXPECT_LT(rfhd.x(), -0.5);
    EXPECT_GT(strn.z(), 0.5);  // the front on +Z
    EXPECT_GT(lfhd.z(), placed(take, c, "LBHD").z());
    EXPECT_NEAR(c.takeToMesh.R.determinant(), 1.0, 1e-12);
}

TEST(RoughAlignment, FacesAZUpMeshTowardsMinusY) {
    const C3dTake take = standingActor();
    const TriMesh mesh = bodyBox({18, 3, 17});  // T-posed, Z up (Blender's way)
    const Calibration c = roughAlignment(take, allPoints(take), mesh);
    const Vec3 lfhd = placed(take, c, "LFHD");
    EXPECT_GT(lfhd.z(), 8.0);
    EXPECT_GT(lfhd.x(), 0.5);
    EXPECT_LT(placed(take, c, "STRN").y(), -0.5);
}

TEST(RoughAlignment, FacesAMeshTheWayItsToesPointWhenItIsWiderAcrossThanDeep) {
    const C3dTake take = standingActor();
    // Y up, wide along Z, the soles reaching towards +X: a scan facing +X, whose left is -Z.
    TriMesh mesh = bodyBox({3, 17, 5});
    for (int v = 0; v < mesh.vertexCount(); ++v)
        if (mesh.V(v, 1) < -7.9) mesh.V(v, 0) += 1.0;
    const Calibration c = roughAlignment(take, allPoints(take), mesh);
    EXPECT_LT(placed(take, c, "LFHD").z(), -0.5);
    EXPECT_GT(placed(take, c, "RFHD").z(), 0.5);
    EXPECT_GT(placed(take, c, "STRN").x(), 0.5);
    EXPECT_NEAR(c.takeToMesh.R.determinant(), 1.0, 1e-12);
    // The toes turned round: the scan faces -X, its left is +Z.
    for (int v = 0; v < mesh.vertexCount(); ++v)
        if (mesh.V(v, 1) < -7.9) mesh.V(v, 0) -= 2.0;
    const Calibration back = roughAlignment(take, allPoints(take), mesh);
    EXPECT_GT(placed(take, back, "LFHD").z(), 0.5);
    EXPECT_LT(placed(take, back, "STRN").x(), -0.5);
    // Longer than tall, as a horse is along its spine: the convention, left on +X.
    TriMesh horse = bodyBox({3, 13, 20});
    for (int v = 0; v < horse.vertexCount(); ++v)
        if (horse.V(v, 1) < -6.0) horse.V(v, 0) += 1.0;
    const Calibration onHorse = roughAlignment(take, allPoints(take), horse);
    EXPECT_GT(placed(take, onHorse, "LFHD").x(), placed(take, onHorse, "RFHD").x() + 0.5);
}

TEST(RoughAlignment, WithoutSidedNamesTheActorStillStandsUp) {
    C3dTake take = standingActor();
    for (std::size_t k = 0; k < take.points.size(); ++k)
        take.points[k].name = take.points[k].label = "M" + std::to_string(k);
    const TriMesh mesh = bodyBox({5, 17, 3});
    const Calibration c = roughAlignment(take, allPoints(take), mesh);
    EXPECT_GT(c.takeToMesh.apply(*take.samples.position(0, 0)).y(), 8.0);
    EXPECT_NEAR(c.takeToMesh.apply(*take.samples.position(0, 5)).y(), -8.5, 1e-9);
    // Nothing seen: no frame, no placement.
    const Calibration none = roughAlignment(take, {}, mesh);
    EXPECT_EQ(none.frame, -1);
    EXPECT_EQ(none.takeToMesh.scale, 1.0);
}

TEST(RoughAlignment, ATakeWithNoHeightStillGetsAFiniteScale) {
    C3dTake take = standingActor();
    for (std::size_t k = 0; k < take.points.size(); ++k)
        for (std::size_t f = 0; f < 2; ++f)
            if (const auto x = take.samples.position(f, k))
                take.samples.set(f, k, x->x(), x->y(), 0.0);  // every marker on the floor
    const TriMesh mesh = bodyBox({5, 17, 3});
    const Calibration flat = roughAlignment(take, allPoints(take), mesh);
    EXPECT_TRUE(std::isfinite(flat.takeToMesh.scale));
    EXPECT_GT(flat.takeToMesh.scale, 0.001);  // the markers' span onto the mesh's, not 1
    EXPECT_LT(flat.takeToMesh.scale, 0.1);
    const Calibration one = roughAlignment(take, {0}, mesh);  // one marker: nothing to measure
    EXPECT_EQ(one.takeToMesh.scale, 1.0);
    EXPECT_TRUE(one.takeToMesh.apply(*take.samples.position(0, 0)).allFinite());
}

// A take without foot markers (its lowest a knee) had that knee put on the mesh's floor and its
// head-to-knee extent scaled to the mesh's height: the body sank into the floor up to the knees.
// Its lowest markers far above the lab's floor (the origin) say the feet are not marked.
TEST(RoughAlignment, ATakeWithoutFootMarkersStandsOnTheLabsFloorNotOnItsKnees) {
    const C3dTake take = actorWith({{"LFHD", {80, 70, 1650}},
                                    {"RFHD", {80, -70, 1650}},
                                    {"STRN", {100, 0, 1300}},
                                    {"LKNE", {40, 100, 500}},
                                    {"RKNE", {40, -100, 480}}});
    const TriMesh mesh = bodyBox({5, 17, 3});  // feet at y = -8.5
    const Calibration c = roughAlignment(take, allPoints(take), mesh);
    EXPECT_NEAR(c.takeToMesh.scale, 17.0 / 1650, 1e-12);  // the head's height above the floor
    EXPECT_NEAR(placed(take, c, "RKNE").y(), -8.5 + 480 * 17.0 / 1650, 1e-9);
    EXPECT_NEAR(placed(take, c, "LFHD").y(), 8.5, 1e-9);
}

// The same with the CMU take, its foot and shin markers left out, on MakeHuman: the knees land
// where the take with its feet puts them.
TEST(RoughAlignment, TheCmuTakeWithoutItsFootMarkersStandsWhereItStandsWithThem) {
    static const char* const kLowerLeg[] = {"ANK", "HEE", "MT5", "TOE", "SHN"};
    namespace fs = std::filesystem;
    const fs::path data = BONELESS_SHARED_DATA;
    const fs::path meshFile = data / "meshes" / "makehuman" / "makehuman_base.obj";
    const fs::path takeFile = data / "c3d" / "cmu" / "85_02.c3d";
    if (!fs::exists(meshFile) || !fs::exists(takeFile)) GTEST_SKIP() << "no " << data;
    MeshReadOptions options;
    options.group = "body";
    const TriMesh mesh = readMesh(meshFile.string(), options).mesh;
    const C3dTake take = readC3d(takeFile.string());
    std::vector<std::size_t> legless;
    for (std::size_t k = 0; k < take.points.size(); ++k) {
        const std::string& label = take.points[k].label;  // "LANK", or with its subject's prefix
        if (std::none_of(std::begin(kLowerLeg), std::end(kLowerLeg),
                         [&](const char* part) { return label.find(part) != std::string::npos; }))
            legless.push_back(k);
    }
    ASSERT_EQ(legless.size(), 31u);
    const Calibration with = roughAlignment(take, allPoints(take), mesh);
    const Calibration without = roughAlignment(take, legless, mesh);
    const double height = mesh.V.col(1).maxCoeff() - mesh.V.col(1).minCoeff();
    EXPECT_NEAR(without.takeToMesh.scale / with.takeToMesh.scale, 1.0, 0.05);
    for (const char* knee : {"LKNE", "RKNE"})
        EXPECT_NEAR(placed(take, without, knee).y(), placed(take, with, knee).y(), 0.03 * height)
            << knee;
}

// The same actor recorded Y up (POINT:Y_SCREEN +Y, as many systems but Vicon's write) lands where
// the Z-up one does: before, its +Z, then horizontal, went to the mesh's up and laid it down.
TEST(RoughAlignment, ATakeWhoseYScreenSaysPlusYStandsWhereItsZUpTwinStands) {
    const C3dTake zUp = standingActor();
    C3dTake yUp = zUp;
    for (std::size_t f = 0; f < 2; ++f)
        for (std::size_t k = 0; k < yUp.points.size(); ++k)
            if (const auto x = zUp.samples.position(f, k))
                yUp.samples.set(f, k, x->x(), x->z(), -x->y());
    yUp.vertical = Vec3::UnitY();  // what the reader makes of Y_SCREEN +Y (C3dVerticalTest)
    for (const Vec3& extent : {Vec3(17, 16, 3), Vec3(18, 3, 17)}) {
        const TriMesh mesh = bodyBox(extent);
        const Calibration a = roughAlignment(zUp, allPoints(zUp), mesh);
        const Calibration b = roughAlignment(yUp, allPoints(yUp), mesh);
        for (const char* name : {"LFHD", "RFHD", "STRN", "RANK"})
            EXPECT_LT((placed(zUp, a, name) - placed(yUp, b, name)).norm(), 1e-9) << name;
    }
}

// The levelling turns the take's own vertical onto the mesh's up, whichever axis that is.
TEST(Alignment, LevelledTurnsTheTakesOwnVerticalOntoTheMeshsUp) {
    std::mt19937 rng(4);
    std::uniform_real_distribution<double> u(-1, 1);
    Positions mesh(10, 3);  // Z up
    for (int i = 0; i < 10; ++i) mesh.row(i) << 0.3 * u(rng), 0.2 * u(rng), 1 + u(rng);
    // The take: Y up, a slight lean.
    const Mat3 zUpToYUp = Eigen::AngleAxisd(-M_PI / 2, Vec3::UnitX()).toRotationMatrix();
    Positions take(10, 3);
    for (int i = 0; i < 10; ++i) {
        Vec3 p = mesh.row(i).transpose();
        p.x() += 0.1 * p.z();
        take.row(i) = (1000.0 * (zUpToYUp * p)).transpose();
    }
    const Similarity free = fitSimilarity(take, mesh);
    const Similarity s = levelled(free, take, mesh, Vec3::UnitY());
    EXPECT_LT((s.R * Vec3::UnitY() - Vec3::UnitZ()).norm(), 1e-12);
    const Similarity told = levelled(free, take, mesh, Vec3::UnitY(), -Vec3::UnitZ());
    EXPECT_LT((told.R * Vec3::UnitY() + Vec3::UnitZ()).norm(), 1e-12);
}

namespace {

// calibrate as it was specified and first written: every frame's visibility, then a fit of every
// frame that shows the most; the smallest residual, the earliest of equal ones.
Calibration calibrationFoundFrameByFrame(int frames, const std::function<Positions(int)>& frameAt,
                                         const Positions& rest) {
    std::vector<int> visible(frames);
    int most = 0;
    for (int f = 0; f < frames; ++f) most = std::max(most, visible[f] = visibleRows(frameAt(f)));
    Calibration best;
    best.residual = INFINITY;
    for (int f = 0; f < frames && most >= 3; ++f) {
        if (visible[f] != most) continue;
        const Positions P = frameAt(f);
        Similarity s;
        try {
            s = fitSimilarity(P, rest);
        } catch (const Error&) {
            continue;
        }
        const double r = alignmentResidual(s, P, rest);
        if (r < best.residual) {
            best.frame = f;
            best.takeToMesh = s;
            best.residual = r;
            best.visibleMarkers = most;
        }
    }
    return best;
}

// A take of `frames` frames of 10 markers: the rest's rows bent by a pose that differs frame by
// frame, turned, scaled to millimetres and moved, with noise; two markers missing for stretches,
// frames where all but two are missing, a collinear frame, and the best pose twice.
struct GappyTake {
    Positions rest;                 // the mesh's rows, 10 by 3
    std::vector<Positions> frames;  // the take's, NaN rows where missing
    Positions at(int f) const { return frames[f]; }
};

GappyTake gappyTake(int frames) {
    GappyTake t;
    std::mt19937 rng(11);
    std::uniform_real_distribution<double> u(-1, 1);
    std::normal_distribution<double> noise(0, 0.5);
    t.rest.resize(10, 3);
    for (int k = 0; k < 10; ++k) t.rest.row(k) << 0.3 * u(rng), 0.2 * u(rng), 0.9 + 0.9 * u(rng);
    for (int f = 0; f < frames; ++f) {
        const Mat3 R = randomRotation(rng);
        const Vec3 origin(1000 * u(rng), 1000 * u(rng), 0);
        const double bend = 0.05 + 0.25 * (0.5 + 0.5 * std::sin(0.05 * f));
        Positions P(10, 3);
        for (int k = 0; k < 10; ++k) {
            Vec3 p = t.rest.row(k).transpose();
            p.x() += bend * p.z() * p.z();
            P.row(k) =
                (1000.0 * (R * p) + origin + Vec3(noise(rng), noise(rng), noise(rng))).transpose();
        }
        if (f % 7 < 3) P.row(2).setConstant(NAN);
        if (f % 11 == 0) P.row(5).setConstant(NAN);
        if (f % 13 == 0)
            for (int k = 2; k < 10; ++k) P.row(k).setConstant(NAN);
        t.frames.push_back(P);
    }
    // The best pose twice, the earlier one chosen: frames 40 and 90 are one and the same.
    for (int k = 0; k < 10; ++k)
        t.frames[40].row(k) = 1000.0 * t.rest.row(k) + Vec3(5, 5, 5).transpose();
    t.frames[90] = t.frames[40];
    // Collinear markers fit no rotation: never a candidate.
    for (int k = 0; k < 10; ++k) t.frames[60].row(k) << 10.0 * k, 0, 0;
    return t;
}

// The rest's rows `offset` off along fixed directions: as TakeSolver places the markers off the
// skin once the mesh's scale is known.
Positions offsetRest(const Positions& rest, double offset) {
    Positions R = rest;
    for (int k = 0; k < R.rows(); ++k)
        R.row(k) += offset * Vec3(std::sin(k), std::cos(k), 0.3).normalized().transpose();
    return R;
}

}  // namespace

// TakeSolver aligns three times (markers on the skin, then off it at the scale found): each search
// must find the frame, fit and residual that a search of every frame finds.
TEST(CalibrationSearch, EachSearchFindsWhatASearchOfEveryFrameFinds) {
    const GappyTake take = gappyTake(400);
    const auto frameAt = [&](int f) { return take.at(f); };
    CalibrationSearch search(400, frameAt, "gappy.c3d");
    for (const double offset : {0.0, 0.01, 0.0101, 0.2, 0.0}) {
        const Positions R = offsetRest(take.rest, offset);
        const Calibration expected = calibrationFoundFrameByFrame(400, frameAt, R);
        const Calibration found = search.find(R);
        ASSERT_GE(expected.frame, 0);
        EXPECT_EQ(found.frame, expected.frame) << "offset " << offset;
        EXPECT_EQ(found.residual, expected.residual) << "offset " << offset;
        EXPECT_EQ(found.takeToMesh.scale, expected.takeToMesh.scale);
        EXPECT_EQ(found.visibleMarkers, expected.visibleMarkers);
        EXPECT_EQ(calibrate(400, frameAt, "gappy.c3d", R).frame, expected.frame);
    }
    // The twin frames of the best pose: the earlier.
    EXPECT_EQ(calibrationFoundFrameByFrame(400, frameAt, take.rest).frame, 40);
}

// The take was read whole twice per search, three searches per solve (a 25-minute take: 20 s
// before the first frame of any range): the first search reads each frame once, and a search
// for a rest near an earlier one reads few.
TEST(CalibrationSearch, ATakeIsReadOnceAndLaterSearchesReadOnlyFramesStillInTheRunning) {
    const GappyTake take = gappyTake(400);
    int reads = 0;
    CalibrationSearch search(
        400,
        [&](int f) {
            ++reads;
            return take.at(f);
        },
        "gappy.c3d");
    search.find(offsetRest(take.rest, 0.0));
    EXPECT_EQ(reads, 400);
    EXPECT_EQ(search.framesRead(), 400);
    search.find(offsetRest(take.rest, 0.01));
    search.find(offsetRest(take.rest, 0.0101));
    EXPECT_EQ(search.framesRead(), reads);
    EXPECT_LT(reads, 400 + 400 / 4) << "the later searches read most of the take again";
}

TEST(CalibrationSearch, ATakeWithoutThreeMarkersSeenAtOnceIsRefusedNamingIt) {
    std::vector<Positions> frames(5, Positions::Constant(4, 3, NAN));
    frames[2].topRows(2).setZero();
    CalibrationSearch search(
        5, [&](int f) { return frames[f]; }, "two.c3d");
    try {
        search.find(Positions::Zero(4, 3));
        FAIL() << "no error";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("two.c3d: no frame shows three"), std::string::npos)
            << e.what();
    }
}
