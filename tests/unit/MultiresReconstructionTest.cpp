// The multiresolution method (algorithm.md §1.6) minimises the same energy as the single-level
// solvers through a hierarchy of coarser meshes; these pin down its invariants and that it
// tracks the converged answer along a sequence.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numeric>
#include <random>

#include "SolverChecks.h"
#include "TestMeshes.h"
#include "TestWorkDir.h"
#include "boneless/C3dReader.h"
#include "boneless/Correspondence.h"
#include "boneless/DemoFiles.h"
#include "boneless/Error.h"
#include "boneless/MeshReader.h"
#include "boneless/Reconstruction.h"
#include "boneless/TakeSolver.h"

using namespace boneless;
using namespace boneless::testing;

namespace {

// Small enough a coarsest level that a test mesh of a few thousand vertices gets several levels.
SolverOptions multiresOptions(int fineIterations = 1, int correctionSteps = 0) {
    SolverOptions o;
    o.method = SolverOptions::Method::Multiresolution;
    o.coarsestVertices = 200;
    o.fineIterations = fineIterations;
    o.correctionSteps = correctionSteps;
    return o;
}

SolverOptions convergedOptions() {
    SolverOptions o;
    o.method = SolverOptions::Method::Iterative;
    o.maxIterations = 100;
    o.relativeTolerance = 1e-14;
    o.cgTolerance = 1e-10;
    o.maxCgIterations = 500;
    return o;
}

// Keyframes every third frame, made early by the given tolerance and turn (1e9: never).
SolverOptions keyframeOptions(double tolerance, double turn = SolverOptions{}.keyframeTurn) {
    SolverOptions o = multiresOptions(3);
    o.keyframeEvery = 3;
    o.keyframeTolerance = tolerance;
    o.keyframeTurn = turn;
    // Keyframes start from the prediction, so close to their minimum that the default relative
    // decrease (1e-3) stopped them after one step (0.0019 % from it); the bench's tolerance.
    o.relativeTolerance = 1e-5;
    return o;
}

double rms(const Positions& a, const Positions& b) {
    return std::sqrt((a - b).rowwise().squaredNorm().mean());
}

// A sphere bent a little more each frame, and a solver that converges each frame's answer.
struct BendingSphere {
    TriMesh mesh = icosphere(4);
    std::vector<int> markers = everyNth(mesh.vertexCount(), 53);
    double diagonal = boundingBoxDiagonal(mesh.V);
    Reconstruction reference;
    BendingSphere() { reference.prepare(mesh, markers, convergedOptions()); }
    Positions targets(double bend) const { return rows(bent(mesh.V, bend), markers); }
};

}  // namespace

TEST(MultiresReconstruction, RestPoseTargetsGiveBackTheRestMesh) {
    const TriMesh mesh = icosphere(4);
    const auto markers = everyNth(mesh.vertexCount(), 97);
    for (const auto& [fine, corrections] : {std::pair{0, 0}, {1, 0}, {0, 1}}) {
        Reconstruction solver;
        solver.prepare(mesh, markers, multiresOptions(fine, corrections));
        const double tolerance = 1e-9 * boundingBoxDiagonal(mesh.V);
        EXPECT_LE(maxDistance(solver.solve(rows(mesh.V, markers)).V, mesh.V), tolerance);
        EXPECT_LE(maxDistance(solver.solve(rows(mesh.V, markers), &mesh.V).V, mesh.V), tolerance);
    }
}

// Prolongation decodes each removed vertex from its ring's shape code, which is invariant under
// rigid motions: a rigidly moved coarse answer must prolong to the rigidly moved mesh, cold,
// from an unrelated guess, and warm-started from the last answer.
TEST(MultiresReconstruction, RigidMotionOfTheMarkersMovesTheMeshRigidly) {
    const TriMesh mesh = icosphere(4);
    const auto markers = everyNth(mesh.vertexCount(), 97);
    std::mt19937 rng(11);
    for (int corrections : {0, 1}) {
        Reconstruction solver;
        solver.prepare(mesh, markers, multiresOptions(1, corrections));
        expectRigidMotionsRecovered(solver, mesh, markers, rng, 20.0);
    }
}

// With the orientation guard on, the coarsest level is solved by the direct method with the
// guard (the input level's conjugate gradients carry it too): the same invariants hold on that
// path, and correction steps, which need the coarsest level's conjugate gradients, are refused.
TEST(MultiresReconstruction, TheGuardedCoarsestLevelKeepsTheInvariants) {
    const TriMesh mesh = icosphere(4);
    const auto markers = everyNth(mesh.vertexCount(), 97);
    SolverOptions o = multiresOptions(1, 0);
    o.orientationWeight = 100;
    o.coarsestIterations = 20;  // a 20° jump, to 1e-6 of the diagonal, by Gauss–Newton steps
    Reconstruction solver;
    solver.prepare(mesh, markers, o);
    EXPECT_LE(maxDistance(solver.solve(rows(mesh.V, markers)).V, mesh.V),
              1e-9 * boundingBoxDiagonal(mesh.V));
    std::mt19937 rng(13);
    expectRigidMotionsRecovered(solver, mesh, markers, rng, 20.0);
    o.correctionSteps = 1;
    Reconstruction refused;
    EXPECT_THROW(refused.prepare(mesh, markers, o), SolverError);
}

// The guarded method's energy is the direct method's, the orientation guard included, and its
// input level minimises it: a sphere bent to 1.5 while one marker sinks to half its radius, in
// three frames. Measured at the last frame: 0.169 against the direct answer's 0.164. With the
// guard on the coarsest level only, the input's energy lacked the guard's terms (0.183 against
// the direct method's 0.185 for the same pose), and that was what its step minimised.
TEST(MultiresReconstruction, TheGuardedInputLevelMinimisesTheDirectMethodsEnergy) {
    const TriMesh mesh = icosphere(4);
    const auto markers = everyNth(mesh.vertexCount(), 97);
    SolverOptions o = multiresOptions(1, 0);
    o.orientationWeight = 100;
    SolverOptions d = o;
    d.method = SolverOptions::Method::Direct;
    Reconstruction multires, direct;
    multires.prepare(mesh, markers, o);
    direct.prepare(mesh, markers, d);
    Positions m = mesh.V, x = mesh.V, targets;
    for (int f = 1; f <= 3; ++f) {
        targets = rows(bent(mesh.V, 0.5 * f), markers);
        targets.row(0) *= 1.0 - f / 6.0;
        const SolveResult r = multires.solve(targets, &m);
        m = r.V;
        x = direct.solve(targets, &x).V;
        const double E = direct.energy(m, targets);
        EXPECT_NEAR(multires.energy(m, targets), E, 1e-12 * E) << "frame " << f;
        // The input level's step lowered that energy, not another.
        EXPECT_NEAR(r.report.energyAfter, E, 1e-12 * E) << "frame " << f;
        EXPECT_LT(r.report.energyAfter, r.report.energyBefore) << "frame " << f;
    }
    // One step a frame: frame 2 ends 10 % above the direct answer's energy, the last 3 %.
    EXPECT_LE(direct.energy(m, targets), 1.05 * direct.energy(x, targets));
}

// A bending sequence, each frame warm-started from the last: every frame stays close to that
// frame's converged minimum (the single-level solver run to a standstill), and closer with a
// fine Gauss–Newton step than with prolongation alone.
TEST(MultiresReconstruction, TracksTheConvergedSolutionAlongASequence) {
    BendingSphere sphere;
    auto& [mesh, markers, diagonal, reference] = sphere;
    // Prolongation alone, one fine Gauss–Newton step, one correction step.
    const std::pair<int, int> variants[] = {{0, 0}, {1, 0}, {0, 1}};
    double worst[3] = {0, 0, 0};
    for (int variant = 0; variant < 3; ++variant) {
        const auto [fine, corrections] = variants[variant];
        Reconstruction solver;
        solver.prepare(mesh, markers, multiresOptions(fine, corrections));
        Positions previous = mesh.V;
        for (int f = 1; f <= 12; ++f) {
            const Positions targets = sphere.targets(0.05 * f);
            SolveResult r = solver.solve(targets, &previous);
            ASSERT_TRUE(r.V.allFinite());
            const double energy = solver.energy(r.V, targets);
            // Prolongation alone leaves the input's energy unevaluated; a step reports it.
            if (fine + corrections == 0)
                EXPECT_TRUE(std::isnan(r.report.energyAfter));
            else
                EXPECT_NEAR(r.report.energyAfter, energy, 1e-9 * std::max(1.0, energy));
            const SolveResult c = reference.solve(targets, &r.V);
            // The answer is near the minimum, so converging it lowers the energy only a little.
            EXPECT_LE(c.report.energyAfter, energy * (1 + 1e-9) + 1e-12);
            worst[variant] = std::max(worst[variant], rms(r.V, c.V) / diagonal);
            previous.swap(r.V);
        }
    }
    // Measured (of the bounding-box diagonal): prolongation alone 0.36 % (0.54 % without the
    // coarsest level's fold guard scaled up), one fine step 0.016 %, one correction step 0.21 %.
    EXPECT_LT(worst[0], 4.5e-3);
    EXPECT_LT(worst[1], 5e-4);
    EXPECT_LT(worst[1], 0.1 * worst[0]);
    // The correction steps remove part of what prolongation leaves.
    EXPECT_LT(worst[2], 0.8 * worst[0]);
}

// SolverOptions::keyframeEvery: a frame between keyframes takes no step on the input (its
// energies are NaN, as with prolongation alone), and adds the input's correction over the last
// keyframe interval, scaled by the coarsest level's progress along it. That keeps it near its
// minimum where the prolongation alone from the same keyframe drifts. A jump starts over.
TEST(MultiresReconstruction, FramesBetweenKeyframesExtrapolateTheInputsCorrection) {
    BendingSphere sphere;
    auto& [mesh, markers, diagonal, reference] = sphere;
    // The bend is fast for this mesh: its keyframes move 1.7e-4 to 5.4e-4 of the diagonal, more
    // than the default tolerance, which would make every frame a keyframe (see the next test).
    Reconstruction solver;
    solver.prepare(mesh, markers, keyframeOptions(1e9));
    Positions previous = mesh.V;
    double worstKeyframe = 0, worstBetween = 0;
    int between = 0;
    for (int f = 1; f <= 12; ++f) {
        const Positions targets = sphere.targets(0.05 * f);
        SolveResult r = solver.solve(targets, &previous);
        ASSERT_TRUE(r.V.allFinite());
        const double error = rms(r.V, reference.solve(targets, &r.V).V) / diagonal;
        // Frames 1 and 2 are keyframes (the second one closes the first interval); then every
        // third frame is.
        const bool isBetween = f > 2 && (f - 2) % 3 != 0;
        EXPECT_EQ(std::isnan(r.report.energyAfter), isBetween) << "frame " << f;
        if (isBetween) {
            ++between;
            worstBetween = std::max(worstBetween, error);
        } else {
            worstKeyframe = std::max(worstKeyframe, error);
        }
        previous.swap(r.V);
    }
    EXPECT_EQ(between, 7);
    // Measured (of the diagonal): keyframes 0.0001 %, frames between them 0.027 %; with the
    // extrapolated correction left out, 0.079 %.
    EXPECT_LT(worstKeyframe, 5e-6);
    EXPECT_LT(worstBetween, 4e-4);
    // A jump back: no interval belongs to it, so it and the frame after it are keyframes.
    for (double bend : {0.1, 0.15}) {
        const Positions targets = sphere.targets(bend);
        const SolveResult r = solver.solve(targets, bend == 0.1 ? &mesh.V : &previous);
        EXPECT_FALSE(std::isnan(r.report.energyAfter)) << "bend " << bend;
        EXPECT_LT(rms(r.V, reference.solve(targets, &r.V).V) / diagonal, 5e-5);
        previous = r.V;
    }
}

// When the last interval stops predicting: a slow bend turns, after frame 6, into a fast second
// bend about another axis. SolverOptions::keyframeTurn sees it a priori, on the coarsest level:
// frame 7's coarsest move lies off the last interval's, so frame 7 is a keyframe.
// SolverOptions::keyframeTolerance sees it a posteriori: without the turn test, the keyframe
// after the turn (frame 8) moves far from its extrapolated start, so frame 9 is a keyframe too.
// Before the turn neither fires, and the schedule holds.
TEST(MultiresReconstruction, KeyframesComeEarlyWhenTheMotionTurns) {
    BendingSphere sphere;
    auto& [mesh, markers, diagonal, reference] = sphere;
    auto pose = [&](int f) {
        const Positions first = bent(mesh.V, 0.02 * std::min(f, 6));
        if (f <= 6) return first;
        // bent() bends along z; swapping x and z around it bends along x.
        Positions swapped = first;
        swapped.col(0).swap(swapped.col(2));
        Positions second = bent(swapped, 0.05 * (f - 6));
        second.col(0).swap(second.col(2));
        return second;
    };
    // Returns the mean error over the frames after the turn; `keyframes`: which frames were.
    auto run = [&](double tolerance, double turn, std::vector<int>& keyframes) {
        Reconstruction solver;
        solver.prepare(mesh, markers, keyframeOptions(tolerance, turn));
        Positions previous = mesh.V;
        double sum = 0;
        for (int f = 1; f <= 12; ++f) {
            const Positions targets = rows(pose(f), markers);
            SolveResult r = solver.solve(targets, &previous);
            if (!std::isnan(r.report.energyAfter)) keyframes.push_back(f);
            if (f > 6) sum += rms(r.V, reference.solve(targets, &r.V).V) / diagonal;
            previous.swap(r.V);
        }
        return sum / 6;
    };
    const SolverOptions defaults;
    std::vector<int> scheduled, byTurn, byTolerance, byBoth;
    const double onSchedule = run(1e9, 1e9, scheduled);
    run(1e9, defaults.keyframeTurn, byTurn);
    run(defaults.keyframeTolerance, 1e9, byTolerance);
    const double adaptive = run(defaults.keyframeTolerance, defaults.keyframeTurn, byBoth);
    auto firstFive = [](const std::vector<int>& k) {
        return std::vector<int>(k.begin(), k.begin() + std::min<size_t>(5, k.size()));
    };
    EXPECT_EQ(scheduled, (std::vector<int>{1, 2, 5, 8, 11}));
    // Measured: frames 1, 2, 5, 7, 8, 11; keyframe moves (of the diagonal) 2.5e-5 to 7.4e-5
    // before the turn, 3.9e-4 at frame 8 without the turn test.
    EXPECT_EQ(firstFive(byTurn), (std::vector<int>{1, 2, 5, 7, 8}));
    EXPECT_EQ(firstFive(byTolerance), (std::vector<int>{1, 2, 5, 8, 9}));
    // Measured (mean of the diagonal after the turn): 1.22e-4 on schedule, 0.40e-4 with both
    // tests (keyframes 1, 2, 5, 7, 8, 11, 12).
    EXPECT_LT(adaptive, 0.5 * onSchedule);
}

// A keyframe's input steps start from the prediction a frame between keyframes would have made, so
// what they move is that prediction's error. Measured from the warm start alone it held the whole
// frame's correction, which grows with the motion's speed: on this steady bend the keyframes after
// the first early one moved 1.9e-4 to 5.1e-4 of the diagonal, above the tolerance of 1.2e-4, so
// every later frame was a keyframe (the bench's 200K-face mesh did the same at the default). From
// the prediction they move 2.7e-5 to 9.3e-5, and the schedule comes back.
TEST(MultiresReconstruction, AnEarlyKeyframeDoesNotMakeEveryFrameAfterItOne) {
    BendingSphere sphere;
    auto& [mesh, markers, diagonal, reference] = sphere;
    Reconstruction solver;
    solver.prepare(mesh, markers, keyframeOptions(1.2e-4));
    Positions previous = mesh.V;
    int between = 0;
    double worst = 0;
    for (int f = 1; f <= 12; ++f) {
        const Positions targets = sphere.targets(0.05 * f);
        SolveResult r = solver.solve(targets, &previous);
        if (std::isnan(r.report.energyAfter)) ++between;
        worst = std::max(worst, rms(r.V, reference.solve(targets, &r.V).V) / diagonal);
        previous.swap(r.V);
    }
    // Measured: keyframes 1, 2, 3, 6, 7, 10, 11, 12 (so 4 frames between), the worst frame 1.5e-4
    // of the diagonal from its minimum.
    EXPECT_GE(between, 4);
    EXPECT_LT(worst, 4e-4);
}

// SolverOptions::recycledMotions on the input level: a jump restarts the levels, and the input's
// kept motions (they belong to the sequence before it) must go too, or the jump's frame is
// projected on them instead of being solved.
TEST(MultiresReconstruction, AJumpForgetsTheInputsRecycledMotions) {
    BendingSphere sphere;
    auto& [mesh, markers, diagonal, reference] = sphere;
    SolverOptions options = multiresOptions(3);
    options.recycledMotions = 2;
    options.refreshEvery = 2;
    Reconstruction solver;
    solver.prepare(mesh, markers, options);
    Positions previous = mesh.V;
    for (int f = 1; f <= 4; ++f) previous = solver.solve(sphere.targets(0.05 * f), &previous).V;
    // The fifth solve would be projected; it jumps back towards the rest pose instead.
    const Positions targets = sphere.targets(0.1);
    const SolveResult r = solver.solve(targets, &mesh.V);
    // Measured (of the diagonal): 2.2e-7 solved; 4.5e-6 projected on the bend's motions.
    EXPECT_LT(rms(r.V, reference.solve(targets, &r.V).V) / diagonal, 1e-6);
}

// A mesh smaller than the coarsest level is solved on one level: the single-level answer.
TEST(MultiresReconstruction, ASmallMeshIsSolvedOnOneLevel) {
    const TriMesh mesh = icosphere(2);
    const auto markers = everyNth(mesh.vertexCount(), 9);
    const Positions targets = rows(bent(mesh.V, 0.3), markers);
    Reconstruction reference;
    reference.prepare(mesh, markers, convergedOptions());
    const SolveResult expected = reference.solve(targets, &mesh.V);
    SolverOptions options = multiresOptions();
    options.maxIterations = 50;
    options.relativeTolerance = 1e-12;
    Reconstruction solver;
    solver.prepare(mesh, markers, options);
    const SolveResult r = solver.solve(targets, &mesh.V);
    EXPECT_LE(maxDistance(r.V, expected.V), 1e-6 * boundingBoxDiagonal(mesh.V));
}

// A take with markers off the skin and gaps, solved frame after frame by the coarsest level alone
// (the app's preview). A marker whose coarse ring nearly collapses makes conjugate gradients
// stop at a step 1e-7 long; such a frame used to be called converged 22 mm from its markers.
TEST(MultiresReconstruction, ATakeWithOffsetsAndGapsStaysOnItsMarkers) {
    const DemoFiles files = writeDemoFiles(freshTestDir("multires-take"), 30, 10.0, false, 2);
    TakeSolveOptions options;
    options.solver.method = SolverOptions::Method::Multiresolution;
    options.solver.fineIterations = 0;
    options.solver.orientationWeight = 0;
    TakeSolver solver(readMesh(files.mesh).mesh, readC3d(files.take),
                      Correspondence::read(files.map), options);
    double worst = 0;
    for (int f = 0; f < solver.frameCount(); ++f) {
        FrameReport report;
        solver.solve(f, report);
        worst = std::max(worst, report.residualRmsMm);
    }
    // Measured: 4.0 mm at worst (the direct solver: 0.4 mm).
    EXPECT_LT(worst, 6.0);
}

// A large mesh is solved in a spatial order of its vertices (VertexOrder), which depends on the
// geometry alone: the same mesh with its vertices and faces shuffled gives the same answers, in
// its own order, frame after frame, and the same energy and encoding through the public API.
TEST(MultiresReconstruction, TheAnswerDoesNotDependOnTheMeshsVertexOrder) {
    const TriMesh mesh = icosphere(5);
    ASSERT_GE(mesh.vertexCount(), 10000);  // where the solver reorders
    const int n = mesh.vertexCount();
    std::mt19937 rng(17);
    std::vector<int> shuffledOf(n);  // the shuffled index of each vertex
    std::iota(shuffledOf.begin(), shuffledOf.end(), 0);
    std::shuffle(shuffledOf.begin(), shuffledOf.end(), rng);
    std::vector<int> faceOrder(mesh.faceCount());
    std::iota(faceOrder.begin(), faceOrder.end(), 0);
    std::shuffle(faceOrder.begin(), faceOrder.end(), rng);
    TriMesh shuffled;
    shuffled.V.resize(n, 3);
    for (int v = 0; v < n; ++v) shuffled.V.row(shuffledOf[v]) = mesh.V.row(v);
    shuffled.F.resize(mesh.faceCount(), 3);
    for (int f = 0; f < mesh.faceCount(); ++f)
        for (int c = 0; c < 3; ++c) shuffled.F(f, c) = shuffledOf[mesh.F(faceOrder[f], c)];
    const auto markers = everyNth(n, 97);
    std::vector<int> shuffledMarkers;
    for (int v : markers) shuffledMarkers.push_back(shuffledOf[v]);

    Reconstruction a, b;
    a.prepare(mesh, markers, multiresOptions(2));
    b.prepare(shuffled, shuffledMarkers, multiresOptions(2));
    Positions lastA = mesh.V, lastB = shuffled.V;
    const double diagonal = boundingBoxDiagonal(mesh.V);
    for (int f = 1; f <= 3; ++f) {
        const Positions targets = rows(bent(mesh.V, 0.1 * f), markers);
        lastA = a.solve(targets, &lastA).V;
        lastB = b.solve(targets, &lastB).V;
        double worst = 0;
        for (int v = 0; v < n; ++v)
            worst = std::max(worst, (lastA.row(v) - lastB.row(shuffledOf[v])).norm());
        EXPECT_LE(worst, 1e-12 * diagonal) << "frame " << f;
        EXPECT_GT(maxDistance(lastA, mesh.V), 1e-3 * diagonal);  // it did move
        EXPECT_NEAR(a.energy(lastA, targets), b.energy(lastB, targets),
                    1e-12 * (1 + a.energy(lastA, targets)));
    }
    for (int v = 0; v < n; v += 101) {
        ASSERT_EQ(a.encoding().encoded(v), b.encoding().encoded(shuffledOf[v]));
        EXPECT_LE(
            (a.encoding().ringNormal(v, lastA) - b.encoding().ringNormal(shuffledOf[v], lastB))
                .norm(),
            1e-9);
    }
}
