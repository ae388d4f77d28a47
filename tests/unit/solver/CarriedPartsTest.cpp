#include <gtest/gtest.h>

#include <atomic>
#include <random>

#include "DemoWalker.h"
#include "TestMeshes.h"
#include "boneless/Reconstruction.h"

using namespace boneless;
using namespace boneless::testing;

namespace {

// The demo walker with a small ball (no marker on it) 6 cm above its crown, its vertices first
// so that the walker's are renumbered, as an eye or a tooth of a character file would be.
struct WalkerWithBall {
    DemoWalker walker = makeDemoWalker(8);
    TriMesh mesh;
    int ball = 0;                  // the ball's vertex count: the walker's vertex v is ball + v
    std::vector<int> markers;      // in mesh ids
    std::vector<int> bodyMarkers;  // in the walker's own ids
    Vec3 crown = Vec3::Zero();

    WalkerWithBall() {
        const TriMesh sphere = icosphere(1);
        ball = sphere.vertexCount();
        const TriMesh& body = walker.rest;
        int top = 0;
        for (int v = 0; v < body.vertexCount(); ++v)
            if (body.V(v, 2) > body.V(top, 2)) top = v;
        crown = body.V.row(top).transpose();
        mesh.V.resize(ball + body.vertexCount(), 3);
        for (int v = 0; v < ball; ++v)
            mesh.V.row(v) =
                (crown + Vec3(0, 0, 0.06) + 0.03 * sphere.V.row(v).transpose()).transpose();
        mesh.V.bottomRows(body.vertexCount()) = body.V;
        mesh.F.resize(sphere.faceCount() + body.faceCount(), 3);
        mesh.F.topRows(sphere.faceCount()) = sphere.F;
        mesh.F.bottomRows(body.faceCount()) = body.F.array() + ball;
        for (const auto& [label, v] : walker.markerVertices) {
            bodyMarkers.push_back(v);
            markers.push_back(ball + v);
        }
    }
    // A pose of the walker alone, with the ball where `ballRows` put it.
    Positions withBall(const Positions& body, const Positions& ballRows) const {
        Positions V(mesh.vertexCount(), 3);
        V.topRows(ball) = ballRows;
        V.bottomRows(body.rows()) = body;
        return V;
    }
};

SolverOptions takeOptions() {
    SolverOptions o;
    o.constraints = SolverOptions::Constraints::Soft;
    return o;
}

const WalkerWithBall& subject() {
    static const WalkerWithBall s;
    return s;
}

}  // namespace

TEST(ComponentsWithoutMarkers, AreCountedOnlyWhenSomeComponentHoldsAMarker) {
    const WalkerWithBall& s = subject();
    EXPECT_EQ(componentsWithoutMarkers(s.mesh, s.markers), 1);
    EXPECT_EQ(componentsWithoutMarkers(s.walker.rest, s.bodyMarkers), 0);
    EXPECT_EQ(componentsWithoutMarkers(s.mesh, {}), 0);  // nothing to follow: solved as before
}

TEST(ComponentsWithoutMarkers, RestMarkersGiveBackTheRestMeshForBothParts) {
    const WalkerWithBall& s = subject();
    Reconstruction solver;
    solver.prepare(s.mesh, s.markers, takeOptions());
    const SolveResult r = solver.solve(rows(s.mesh.V, s.markers));
    ASSERT_EQ(r.V.rows(), s.mesh.vertexCount());
    EXPECT_LE(maxDistance(r.V, s.mesh.V), 1e-9);
}

TEST(ComponentsWithoutMarkers, ARigidMotionOfTheMarkersMovesTheUnmarkedPartByTheSameMotion) {
    const WalkerWithBall& s = subject();
    Reconstruction solver;
    solver.prepare(s.mesh, s.markers, takeOptions());
    std::mt19937 rng(5);
    const Mat3 R = randomRotation(rng);
    const Vec3 t(0.3, -1.2, 0.4);
    const Positions expected = moved(s.mesh.V, R, t);
    const SolveResult r = solver.solve(rows(expected, s.markers));
    EXPECT_LE(maxDistance(r.V.topRows(s.ball), expected.topRows(s.ball)), 1e-6);
}

TEST(ComponentsWithoutMarkers, TheMarkedPartComesOutAsIfSolvedWithoutTheUnmarkedOne) {
    const WalkerWithBall& s = subject();
    Reconstruction whole, alone;
    whole.prepare(s.mesh, s.markers, takeOptions());
    alone.prepare(s.walker.rest, s.bodyMarkers, takeOptions());
    for (int frame : {3, 6}) {
        const Positions& pose = s.walker.frames[frame];
        const SolveResult a = alone.solve(rows(pose, s.bodyMarkers));
        const SolveResult w = whole.solve(rows(pose, s.bodyMarkers));
        EXPECT_LE(maxDistance(w.V.bottomRows(a.V.rows()), a.V), 1e-9) << "frame " << frame;
        EXPECT_EQ(w.report.foldedFaces, a.report.foldedFaces);
        // The energy and the markers' places are the walker's too.
        EXPECT_NEAR(whole.energy(w.V, rows(pose, s.bodyMarkers)),
                    alone.energy(a.V, rows(pose, s.bodyMarkers)), 1e-9);
        EXPECT_LE(maxDistance(whole.markerPositions(w.V), alone.markerPositions(a.V)), 1e-12);
    }
}

// Before, the ball was held only by the Tikhonov pull towards the rest moved rigidly onto all
// the markers: the head turned under it and it stayed.
TEST(ComponentsWithoutMarkers, AnUnmarkedPartNearTheHeadTurnsWithTheHead) {
    const WalkerWithBall& s = subject();
    Reconstruction solver;
    solver.prepare(s.mesh, s.markers, takeOptions());
    // The head's markers (above the neck) nodded 20 degrees forward about the neck.
    const double neck = s.crown.z() - 0.25;
    const Vec3 pivot(s.crown.x(), s.crown.y(), neck);
    const Mat3 R = Eigen::AngleAxisd(20.0 * M_PI / 180, Vec3::UnitX()).matrix();
    const Vec3 t = pivot - R * pivot;
    Positions targets = rows(s.mesh.V, s.markers);
    int turned = 0;
    for (int k = 0; k < targets.rows(); ++k)
        if (targets(k, 2) > neck) {
            targets.row(k) = (R * targets.row(k).transpose() + t).transpose();
            ++turned;
        }
    ASSERT_GE(turned, 3);
    const SolveResult r = solver.solve(targets);
    const Positions expected = moved(s.mesh.V.topRows(s.ball), R, t);
    const Positions untouched = s.mesh.V.topRows(s.ball);
    ASSERT_GT(maxDistance(expected, untouched), 0.1);  // the nod moves the ball by 10 cm
    EXPECT_LE(maxDistance(r.V.topRows(s.ball), expected), 0.01);
}

TEST(ComponentsWithoutMarkers, AFrameComesOutTheSameWhateverFramesCameBefore) {
    const WalkerWithBall& s = subject();
    Reconstruction fresh, visited;
    fresh.prepare(s.mesh, s.markers, takeOptions());
    visited.prepare(s.mesh, s.markers, takeOptions());
    for (int frame : {7, 1, 4}) visited.solve(rows(s.walker.frames[frame], s.bodyMarkers));
    const Positions targets = rows(s.walker.frames[5], s.bodyMarkers);
    EXPECT_EQ(maxDistance(visited.solve(targets).V, fresh.solve(targets).V), 0.0);
}

// A stopped solve has no positions to carry a part with (the app's scrub that moved on).
TEST(ComponentsWithoutMarkers, AStoppedSolveIsSaidToBeStopped) {
    const WalkerWithBall& s = subject();
    Reconstruction solver;
    solver.prepare(s.mesh, s.markers, takeOptions());
    const std::atomic<bool> stop{true};
    EXPECT_TRUE(solver.solve(rows(s.mesh.V, s.markers), nullptr, &stop).report.stopped);
}
