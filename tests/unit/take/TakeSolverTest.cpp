// TakeSolver: a take's frames, each from its own markers.
#include <gtest/gtest.h>

#include <map>

#include "boneless/C3dReader.h"
#include "boneless/Correspondence.h"
#include "boneless/DemoFiles.h"
#include "boneless/Error.h"
#include "boneless/MeshReader.h"
#include "boneless/Metrics.h"
#include "boneless/RigidFit.h"
#include "boneless/TakeSolver.h"

using namespace boneless;

namespace {

struct Take {
    TriMesh mesh;
    C3dTake take;
    Correspondence map;
};

// The demo creature at `detail` (2: 5,666 vertices, enough for a coarse level of its own), 30
// frames: a stride every 30 frames, so a frame is far from the one before.
Take demoTake(const std::string& name, int detail) {
    const DemoFiles files = writeDemoFiles(freshTestDir(name), 30, 10.0, false, detail);
    return {readMesh(files.mesh).mesh, readC3d(files.take), Correspondence::read(files.map)};
}

double maxDistance(const Positions& a, const Positions& b) {
    return (a - b).rowwise().norm().maxCoeff();
}

}  // namespace

// The user's scrub (20, then 5, then 12) and the export's order (0, 1, 2, ...) give each frame
// the same answer, bit for bit: what the app shows is what the file holds.
TEST(TakeSolver, AFrameIsTheSameWhateverFramesWereSolvedBefore) {
    for (int detail : {1, 2}) {
        const Take t = demoTake("take-order", detail);
        TakeSolver player(t.mesh, t.take, t.map), scrubber(t.mesh, t.take, t.map);
        std::vector<Positions> played;
        for (int f = 0; f <= 20; ++f) {
            FrameReport r;
            played.push_back(player.solve(f, r));
        }
        for (int f : {20, 5, 12, 0, 19}) {
            FrameReport r;
            EXPECT_EQ(maxDistance(scrubber.solve(f, r), played[f]), 0.0)
                << "detail " << detail << ", frame " << f;
        }
    }
}

// An actor who leans in every frame, the calibration frame too, is solved leaning: the take's
// vertical stays the mesh's, so an exported floor stays level (a free alignment took the lean
// out, and tilted the walk it was fitted at instead). The shape is the same as upright.
TEST(TakeSolver, AnActorLeaningAtTheCalibrationFrameIsSolvedLeaningNotTilted) {
    const Take t = demoTake("take-lean", 1);
    Take leaning = t;
    const double lean = 8.0 * M_PI / 180;
    const Mat3 tilt = Eigen::AngleAxisd(lean, Vec3::UnitX()).toRotationMatrix();
    for (std::size_t f = 0; f < t.take.frameCount(); ++f)
        for (std::size_t k = 0; k < t.take.points.size(); ++k)
            if (const auto x = t.take.samples.position(f, k)) {
                const Vec3 y = tilt * *x;
                leaning.take.samples.set(f, k, y.x(), y.y(), y.z());
            }
    TakeSolver upright(t.mesh, t.take, t.map), leant(leaning.mesh, leaning.take, leaning.map);
    const Vec3 up = upright.calibration().takeToMesh.R * Vec3::UnitZ();
    EXPECT_LT((leant.calibration().takeToMesh.R * Vec3::UnitZ() - up).norm(), 1e-12);
    for (int f : {0, 17}) {
        FrameReport r;
        const Positions a = upright.solve(f, r), b = leant.solve(f, r);
        const RigidMotion m = fitRigidMotion(a, b);
        const Eigen::AngleAxisd turn(m.R);
        EXPECT_NEAR(turn.angle(), lean, 0.2 * M_PI / 180) << "frame " << f;
        EXPECT_LT(std::abs(turn.axis().dot(up)), 0.01) << "frame " << f;  // a lean, not a turn
        const Positions moved = (a * m.R.transpose()).rowwise() + m.t.transpose();
        EXPECT_LT(maxDistance(moved, b) / boundingBoxDiagonal(t.mesh.V), 1e-4) << "frame " << f;
    }
}

// An actor who lies in every frame (a floor routine) tips the guess over: the take's vertical
// goes wherever the standing mesh's front is. The user's `meshUp` stands the mesh's up on it, and
// the frames' shapes are the same, turned.
TEST(TakeSolver, AnActorLyingInEveryFrameStandsOnTheMeshUpTheUserGives) {
    const Take t = demoTake("take-lying", 1);
    Take lying = t;
    const Mat3 down = Eigen::AngleAxisd(M_PI / 2, Vec3::UnitX()).toRotationMatrix();
    for (std::size_t f = 0; f < t.take.frameCount(); ++f)
        for (std::size_t k = 0; k < t.take.points.size(); ++k)
            if (const auto x = t.take.samples.position(f, k)) {
                const Vec3 y = down * *x;
                lying.take.samples.set(f, k, y.x(), y.y(), y.z());
            }
    const Vec3 meshUp =
        TakeSolver(t.mesh, t.take, t.map).calibration().takeToMesh.R * Vec3::UnitZ();
    const TakeSolver guessed(lying.mesh, lying.take, lying.map);
    EXPECT_LT(std::abs((guessed.calibration().takeToMesh.R * Vec3::UnitZ()).dot(meshUp)), 1e-9);
    TakeSolveOptions options;
    options.meshUp = parseAxis(axisName(meshUp));
    ASSERT_TRUE(options.meshUp);
    TakeSolver told(lying.mesh, lying.take, lying.map, options);
    EXPECT_LT((told.calibration().takeToMesh.R * Vec3::UnitZ() - meshUp).norm(), 1e-12);
    FrameReport r;
    const Positions a = TakeSolver(t.mesh, t.take, t.map).solve(9, r), b = told.solve(9, r);
    const RigidMotion m = fitRigidMotion(a, b);
    EXPECT_NEAR(Eigen::AngleAxisd(m.R).angle(), M_PI / 2, 0.5 * M_PI / 180);
    const Positions moved = (a * m.R.transpose()).rowwise() + m.t.transpose();
    EXPECT_LT(maxDistance(moved, b) / boundingBoxDiagonal(t.mesh.V), 1e-3);
}

// A calibration frame the user picked where the actor left the volume said only "alignment needs at
// least 3 markers visible at once, got 0", naming neither the frame nor the take.
TEST(TakeSolver, ACalibrationFrameThatShowsTooFewMarkersIsNamedWithWhatItShows) {
    Take t = demoTake("take-empty-calibration", 1);
    for (std::size_t k = 0; k < t.take.points.size(); ++k) t.take.samples.set(5, k, NAN, NAN, NAN);
    TakeSolveOptions options;
    options.calibrationFrame = 5;
    try {
        TakeSolver solver(t.mesh, t.take, t.map, options);
        FAIL() << "solved from a frame without markers";
    } catch (const Error& e) {
        EXPECT_NE(
            std::string(e.what()).find(t.take.file + ": calibration frame 5 shows 0 of the " +
                                       std::to_string(t.map.markers.size()) + " mapped markers"),
            std::string::npos)
            << e.what();
    }
}

// Marker 4 is missing from frames 20–27. Leaving it in the map and taking it out pose one
// problem: the local/global factor takes it out by a low-rank correction, the same algebra as a
// factor without it. Only the coarse level can differ (a map's markers are kept in it); here it
// does not (measured: 3e-14 of the diagonal), and a marker pulled to (0,0,0) would move the mesh
// by a tenth of it.
TEST(TakeSolver, AMarkerMissingFromTheFrameShapesNothing) {
    const Take t = demoTake("take-gap", 2);
    ASSERT_FALSE(t.take.samples.valid(24, 3));
    ASSERT_FALSE(t.take.samples.valid(25, 3));
    Take reduced = t;
    reduced.map.markers.erase(reduced.map.markers.begin() + 3);
    TakeSolveOptions options;
    options.alignment = TakeSolver(t.mesh, t.take, t.map).calibration().takeToMesh;
    options.fillGapSeconds = 0;  // the gap itself, not the marker put back on its path
    // The marker is seen at the calibration frame, so it rightly shapes a calibrated rest: what
    // is checked here is the frame's solve alone.
    options.calibrate = CalibrateMode::None;
    TakeSolver a(t.mesh, t.take, t.map, options),
        b(reduced.mesh, reduced.take, reduced.map, options);
    for (int f : {24, 25}) {
        FrameReport ra, rb;
        const Positions Va = a.solve(f, ra), Vb = b.solve(f, rb);
        EXPECT_EQ(ra.visibleMarkers, rb.visibleMarkers);
        const double off = maxDistance(Va, Vb) / boundingBoxDiagonal(t.mesh.V);
        std::printf("frame %d: %.2e of the diagonal from the map without the marker\n", f, off);
        EXPECT_LT(off, 1e-3) << "frame " << f;
    }
}

// The app's Align hands the solver an alignment; the sidecar's residual is then the one that
// alignment leaves at its frame, measured as a found one is, not 0 whatever it fits.
TEST(TakeSolver, AGivenAlignmentReportsTheResidualItLeavesAtItsFrame) {
    const Take t = demoTake("take-given-alignment", 1);
    const TakeSolver automatic(t.mesh, t.take, t.map);
    TakeSolveOptions options;
    options.alignment = automatic.calibration().takeToMesh;
    options.calibrationFrame = automatic.calibration().frame;
    const TakeSolver given(t.mesh, t.take, t.map, options);
    const double diagonal = boundingBoxDiagonal(t.mesh.V);
    EXPECT_NEAR(given.calibration().residual, automatic.calibration().residual, 1e-9 * diagonal);

    options.alignment->t += Vec3(0.05 * diagonal, 0, 0);  // Align done 5 % of the body off
    const TakeSolver shifted(t.mesh, t.take, t.map, options);
    EXPECT_NEAR(shifted.calibration().residual, 0.05 * diagonal, 0.01 * diagonal);
}

// A frame where every marker is missing has nothing to follow: the (calibrated) rest pose, finite,
// and the frames around it are what they would be without it.
// Frames 11 to 13 show no marker (the actor left the volume): each holds the pose of the nearest
// frame that shows one, the earlier on a tie, whichever frames were solved before it. Solved from
// nothing, they were the rest mesh where the mesh file stands.
TEST(TakeSolver, AFrameWithoutMarkersHoldsTheNearestSeenFramesPoseAndChangesNoOtherFrame) {
    Take t = demoTake("take-blank", 2);
    const Take untouched = t;
    for (int f : {11, 12, 13})
        for (int k = 0; k < static_cast<int>(t.take.points.size()); ++k)
            t.take.samples.setMissing(f, k);
    TakeSolveOptions options;
    options.alignment =
        TakeSolver(untouched.mesh, untouched.take, untouched.map).calibration().takeToMesh;
    options.fillGapSeconds = 0;  // frames with no marker at all, not ones put back
    TakeSolver solver(t.mesh, t.take, t.map, options), fresh(t.mesh, t.take, t.map, options),
        reference(untouched.mesh, untouched.take, untouched.map, options);
    FrameReport r;
    std::map<int, Positions> blank;
    for (int f : {13, 11, 12}) {
        blank[f] = solver.solve(f, r);
        EXPECT_EQ(r.visibleMarkers, 0);
        EXPECT_EQ(r.heldFrom, f == 13 ? 14 : 10) << "frame " << f;
    }
    const Positions V10 = fresh.solve(10, r), V14 = fresh.solve(14, r);
    EXPECT_EQ(r.heldFrom, -1);
    EXPECT_EQ(maxDistance(blank[11], V10), 0.0);
    EXPECT_EQ(maxDistance(blank[12], V10), 0.0);
    EXPECT_EQ(maxDistance(blank[13], V14), 0.0);
    EXPECT_GT(maxDistance(blank[11], solver.rest().V), 0.0);
    EXPECT_EQ(maxDistance(V14, reference.solve(14, r)), 0.0);
}

// A gap short enough is filled from the marker's own path: the frame then lands closer to where
// the take shows the marker just before and after than with the gap left empty, and what the
// report counts as seen is still what was seen.
TEST(TakeSolver, AShortGapIsFilledFromTheMarkersPath) {
    Take t = demoTake("take-fill", 2);
    const int frame = 12, point = 0;
    for (int f = frame - 1; f <= frame + 1; ++f) t.take.samples.setMissing(f, point);
    TakeSolveOptions filled, empty;
    filled.alignment = empty.alignment = TakeSolver(t.mesh, t.take, t.map).calibration().takeToMesh;
    empty.fillGapSeconds = 0;
    TakeSolver a(t.mesh, t.take, t.map, filled), b(t.mesh, t.take, t.map, empty);
    const Positions seen = a.targets(frame), pulled = a.targets(frame, true);
    EXPECT_FALSE(seen.row(point).allFinite());
    ASSERT_TRUE(pulled.row(point).allFinite());
    FrameReport ra, rb;
    const Positions Va = a.solve(frame, ra), Vb = b.solve(frame, rb);
    EXPECT_EQ(ra.visibleMarkers, rb.visibleMarkers);
    // The marker's predicted place sits near its filled target with the fill, farther without.
    const double withFill = (a.predictedMarkers(Va).row(point) - pulled.row(point)).norm();
    const double without = (b.predictedMarkers(Vb).row(point) - pulled.row(point)).norm();
    EXPECT_LT(withFill, without);
}
