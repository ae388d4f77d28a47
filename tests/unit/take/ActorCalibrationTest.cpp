// Actor calibration: the rest mesh fitted to the actor at the calibration frame, so that an actor
// built otherwise than the mesh is followed without stretching every frame.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "CliRunner.h"
#include "DemoCreature.h"
#include "DemoTake.h"
#include "boneless/ActorCalibration.h"
#include "boneless/C3dWriter.h"
#include "boneless/Error.h"
#include "boneless/MeshReader.h"
#include "boneless/Metrics.h"
#include "boneless/ObjWriter.h"
#include "boneless/TakeSolver.h"

using namespace boneless;
using namespace boneless::testing;
namespace fs = std::filesystem;

namespace {

// The demo creature's actor is 15 % longer than the mesh (along its body, x) and moves rigidly:
// every frame's shape is the stretched rest, so any stretch left in a solved frame is the
// calibration's fault.
struct LongActor {
    DemoCreature demo;
    Positions actorRest;
    DemoTake take;
};

LongActor longActor(int frames = 12) {
    LongActor a;
    a.demo = makeDemoCreature(frames);
    const Vec3 centre = a.demo.rest.V.colwise().mean().transpose();
    a.actorRest = a.demo.rest.V;
    for (int v = 0; v < a.actorRest.rows(); ++v)
        a.actorRest(v, 0) = centre.x() + 1.15 * (a.actorRest(v, 0) - centre.x());
    for (int t = 0; t < frames; ++t) {
        const Mat3 R = Eigen::AngleAxisd(0.15 * t, Vec3(0.2, 1, 0.4).normalized()).matrix();
        const Vec3 shift(0.1 * t, -0.05 * t, 0.02 * t);
        a.demo.frames[t] =
            ((a.actorRest.rowwise() - centre.transpose()) * R.transpose()).rowwise() +
            (centre + shift).transpose();
    }
    a.take = makeDemoTake(a.demo);
    return a;
}

}  // namespace

// Without calibration every frame stretches the mesh by the actor's extra length; with it, the
// calibrated rest is the actor's shape and the frames meet their markers with no stretch left.
TEST(ActorCalibration, AnActorWithLongerLimbsIsFittedBackWithNoStretchLeft) {
    const LongActor a = longActor();
    TakeSolveOptions none;
    none.calibrate = CalibrateMode::None;
    TakeSolver calibrated(a.demo.rest, a.take.take, a.take.map),
        raw(a.demo.rest, a.take.take, a.take.map, none);
    const TriMesh& rest = calibrated.rest();
    // The calibrated rest is the actor's body, up to the similarity the alignment found.
    const Similarity toRest = fitSimilarity(a.actorRest, rest.V);
    Positions actor = a.actorRest;
    for (int v = 0; v < actor.rows(); ++v)
        actor.row(v) = toRest.apply(a.actorRest.row(v).transpose()).transpose();
    const double diagonal = (rest.V.colwise().maxCoeff() - rest.V.colwise().minCoeff()).norm();
    const double off = rmsVertexError(rest.V, actor) / diagonal;
    const Similarity toInput = fitSimilarity(a.actorRest, a.demo.rest.V);
    for (int v = 0; v < actor.rows(); ++v)
        actor.row(v) = toInput.apply(a.actorRest.row(v).transpose()).transpose();
    const double inputOff = rmsVertexError(a.demo.rest.V, actor) / diagonal;
    // Measured: 2.6e-3 (30 markers on 1,394 vertices), the input rest 9.1e-3.
    std::printf("calibrated rest: %.2e of the diagonal from the actor's body (input rest %.2e)\n",
                off, inputOff);
    EXPECT_LT(off, 5e-3);
    EXPECT_LT(3 * off, inputOff);
    for (int f : {0, 5, 11}) {
        FrameReport rc, rr;
        const Positions Vc = calibrated.solve(f, rc), Vr = raw.solve(f, rr);
        const double stretchCalibrated = edgeLengthDistortion(rest.F, Vc, rest.V);
        const double stretchRaw = edgeLengthDistortion(rest.F, Vr, a.demo.rest.V);
        std::printf("frame %d: residual %.2f mm, distortion %.4f (uncalibrated %.2f mm, %.4f)\n", f,
                    rc.residualRmsMm, stretchCalibrated, rr.residualRmsMm, stretchRaw);
        EXPECT_LT(rc.residualRmsMm, 2.0) << "frame " << f;
        EXPECT_LT(stretchCalibrated, 0.01) << "frame " << f;
        EXPECT_GT(stretchRaw, 5 * stretchCalibrated) << "frame " << f;
    }
}

// A marker half a metre from the body (a map entry on the wrong actor, a prop) is named, rather
// than followed by a spike of stretched mesh.
TEST(ActorCalibration, AMarkerTheMeshCannotReachIsNamed) {
    LongActor a = longActor(4);
    C3dSamples& samples = a.take.take.samples;
    const int marker = 7;
    for (int t = 0; t < 4; ++t) {
        const auto x = samples.position(t, marker);
        ASSERT_TRUE(x);
        samples.set(t, marker, x->x(), x->y(), x->z() + 500.0);
    }
    try {
        TakeSolver solver(a.demo.rest, a.take.take, a.take.map);
        FAIL() << "a marker 500 mm off the body was followed";
    } catch (const Error& e) {
        const std::string message = e.what();
        EXPECT_NE(message.find("cannot reach"), std::string::npos) << message;
        // The map first: solved without calibrating, a map of another vertex order hid itself.
        EXPECT_LT(message.find("check the map first"), message.find("calibrate none")) << message;
        EXPECT_NE(message.find(a.take.map.markers[marker].label), std::string::npos) << message;
        EXPECT_EQ(message.find(a.take.map.markers[marker + 1].label), std::string::npos) << message;
    }
    TakeSolveOptions none;  // the user's way out: solve against the rest as given
    none.calibrate = CalibrateMode::None;
    EXPECT_NO_THROW(TakeSolver(a.demo.rest, a.take.take, a.take.map, none));
    // Two of them: the farther is named first, where a user starts checking the map.
    const int farther = 20;
    for (int t = 0; t < 4; ++t) {
        const auto x = samples.position(t, farther);
        ASSERT_TRUE(x);
        samples.set(t, farther, x->x(), x->y() + 900.0, x->z());
    }
    try {
        TakeSolver solver(a.demo.rest, a.take.take, a.take.map);
        FAIL() << "markers 500 and 900 mm off the body were followed";
    } catch (const Error& e) {
        const std::string message = e.what();
        const auto first = message.find(a.take.map.markers[farther].label + " (");
        const auto second = message.find(a.take.map.markers[marker].label + " (");
        ASSERT_NE(first, std::string::npos) << message;
        ASSERT_NE(second, std::string::npos) << message;
        EXPECT_LT(first, second) << message;
    }
}

// `solve --write-calibrated-rest` writes the fitted rest in the input's vertex order and faces,
// the sidecar names it and gives each frame's 95th percentile edge strain; --calibrate none is
// recorded and writes no rest.
TEST(ActorCalibration, SolveWritesTheCalibratedRestAndNamesItInTheSidecar) {
    const LongActor a = longActor(6);
    const fs::path dir = freshTestDir("calibrated-rest");
    writeObj((dir / "creature.obj").string(), a.demo.rest.V, a.demo.rest.F, "rest");
    writeC3d(a.take.take, (dir / "creature.c3d").string());
    a.take.map.write((dir / "creature.json").string());
    const std::string common = "solve --quiet --mesh " + (dir / "creature.obj").string() +
                               " --c3d " + (dir / "creature.c3d").string() + " --map " +
                               (dir / "creature.json").string() + " --format pc2";
    const CliResult r =
        runCli(common + " --out " + (dir / "on").string() + " --write-calibrated-rest");
    ASSERT_EQ(r.exitCode, 0) << r.out;
    const auto sidecar = nlohmann::json::parse(std::ifstream(dir / "on" / "creature.json"));
    EXPECT_EQ(sidecar["calibration"]["calibrate"], "shape");
    ASSERT_EQ(sidecar["calibration"]["calibrated_rest"], "creature_calibrated_rest.obj");
    const TriMesh written = readMesh((dir / "on" / "creature_calibrated_rest.obj").string()).mesh;
    EXPECT_EQ(written.F, a.demo.rest.F);
    ASSERT_EQ(written.vertexCount(), a.demo.rest.vertexCount());
    EXPECT_GT(edgeLengthDistortion(written.F, written.V, a.demo.rest.V), 0.02);  // it was fitted
    for (const auto& f : sidecar["per_frame"]) EXPECT_LT(f["edge_strain_p95"].get<double>(), 0.02);

    const CliResult off = runCli(common + " --out " + (dir / "off").string() + " --calibrate none");
    ASSERT_EQ(off.exitCode, 0) << off.out;
    const auto plain = nlohmann::json::parse(std::ifstream(dir / "off" / "creature.json"));
    EXPECT_EQ(plain["calibration"]["calibrate"], "none");
    EXPECT_GT(plain["summary"]["edge_strain_p95_worst_frame"].get<double>(), 0.05);
    EXPECT_FALSE(fs::exists(dir / "off" / "creature_calibrated_rest.obj"));
}
