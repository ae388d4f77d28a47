#include <gtest/gtest.h>

#include <algorithm>
#include <limits>
#include <random>

#include "SolverChecks.h"
#include "TestMeshes.h"
#include "boneless/Error.h"
#include "boneless/Metrics.h"
#include "boneless/Reconstruction.h"

using namespace boneless;
using namespace boneless::testing;

namespace {

SolverOptions exactOptions() {
    SolverOptions options;
    options.method = SolverOptions::Method::Exact;
    return options;
}

// Each method's name in test names: LocalGlobal, Exact.
std::string methodLabel(const ::testing::TestParamInfo<SolverOptions::Method>& info) {
    return info.param == SolverOptions::Method::Exact ? "Exact" : "LocalGlobal";
}

// Steps taken until the energy is within `relative` of its last value.
int stepsUntilWithin(const std::vector<double>& energies, double relative) {
    int steps = 0;
    while (energies[steps] - energies.back() > relative * energies.back()) ++steps;
    return steps;
}

class EveryMethod : public ::testing::TestWithParam<SolverOptions::Method> {
  protected:
    SolverOptions options() const {
        SolverOptions o;
        o.method = GetParam();
        return o;
    }
};

}  // namespace

INSTANTIATE_TEST_SUITE_P(, EveryMethod,
                         ::testing::Values(SolverOptions::Method::LocalGlobal,
                                           SolverOptions::Method::Exact),
                         methodLabel);

TEST_P(EveryMethod, RestPoseTargetsGiveBackTheRestMesh) {
    for (const TriMesh& mesh : {icosphere(2), tube(8, 12, 4.0)}) {
        Reconstruction solver;
        const auto markers = everyNth(mesh.vertexCount(), 9);
        solver.prepare(mesh, markers, options());
        const SolveResult r = solver.solve(rows(mesh.V, markers));
        EXPECT_LE(maxDistance(r.V, mesh.V), 1e-9 * boundingBoxDiagonal(mesh.V));
    }
}

// From a pose a round-off away from the answer, every Gauss–Newton step still removes most of
// what is left, so the relative-decrease test alone would take all maxIterations factorisations
// (it did: 10, each a second on a 100K-face mesh) for nothing anyone could see.
TEST(ExactReconstruction, AnAnswerAtRoundOffTakesNoMoreSteps) {
    const TriMesh mesh = icosphere(3);
    const auto markers = everyNth(mesh.vertexCount(), 9);
    Reconstruction solver;
    solver.prepare(mesh, markers, exactOptions());
    std::mt19937 rng(3);
    std::uniform_real_distribution<double> noise(-1e-13, 1e-13);
    Positions guess = mesh.V;
    for (int i = 0; i < guess.size(); ++i) guess.data()[i] += noise(rng);
    const SolveResult r = solver.solve(rows(mesh.V, markers), &guess);
    EXPECT_LE(r.report.iterations, 1);
    EXPECT_TRUE(r.report.converged);
    EXPECT_LE(maxDistance(r.V, mesh.V), 1e-9 * boundingBoxDiagonal(mesh.V));
}

TEST_P(EveryMethod, RigidMotionOfTheMarkersMovesTheMeshRigidly) {
    const TriMesh mesh = tube(10, 12, 4.0);
    const auto markers = everyNth(mesh.vertexCount(), 11);
    const double tolerance = 1e-6 * boundingBoxDiagonal(mesh.V);
    std::mt19937 rng(11);
    for (int trial = 0; trial < 3; ++trial) {
        const Mat3 R = randomRotation(rng);
        const Vec3 t(trial, 2.0 - trial, 0.5);
        const Positions expected = moved(mesh.V, R, t);
        Reconstruction solver;
        SolverOptions o = options();  // Exact: converge fully, to check the minimiser
        o.maxIterations = 200;
        o.relativeTolerance = 1e-14;
        solver.prepare(mesh, markers, o);
        // Without a guess: any rotation, the rest pose is fitted onto the markers first.
        const SolveResult cold = solver.solve(rows(expected, markers));
        EXPECT_LE(maxDistance(cold.V, expected), tolerance) << "trial " << trial;
        // Exact, started from a pose 25 degrees away, as between fast frames: Gauss–Newton has
        // to find the remaining rotation itself (LocalGlobal uses no guess).
        const Mat3 away = Eigen::AngleAxisd(25.0 * M_PI / 180, Vec3(1, 2, 3).normalized()).matrix();
        const Positions previous = moved(mesh.V, away * R, t);
        const SolveResult warm = solver.solve(rows(expected, markers), &previous);
        EXPECT_LE(maxDistance(warm.V, expected), tolerance)
            << "trial " << trial << ", " << warm.report.iterations << " iterations";
    }
}

TEST(ExactReconstruction, EnergyNeverIncreasesAndDropsFromTheStart) {
    const TriMesh mesh = tube(12, 14, 5.0);
    const auto markers = everyNth(mesh.vertexCount(), 13);
    Reconstruction solver;
    SolverOptions options = exactOptions();
    options.relativeTolerance = 1e-9;
    options.maxIterations = 25;
    solver.prepare(mesh, markers, options);
    const Positions pose = bent(mesh.V, 0.6);
    const SolveResult r = solver.solve(rows(pose, markers), &mesh.V);
    ASSERT_GE(r.report.energies.size(), 3u);
    for (size_t i = 1; i < r.report.energies.size(); ++i)
        EXPECT_LE(r.report.energies[i], r.report.energies[i - 1]) << "iteration " << i;
    EXPECT_LT(r.report.energyAfter, 1e-2 * r.report.energyBefore);
    EXPECT_DOUBLE_EQ(r.report.energyAfter, solver.energy(r.V, rows(pose, markers)));
    for (size_t k = 0; k < markers.size(); ++k)
        EXPECT_EQ(r.V.row(markers[k]), pose.row(markers[k]));  // hard constraints are exact
}

// With its rotations held, the fold guard's Gauss–Newton matrix converges slowly where a bend
// turns the rings: here 0.85 per step, 5e-5 of the energy still to go after 40 steps (a koala
// frame took all 10 factorisations). With the rotations' derivative (its exact Hessian), which
// the exact method takes near a minimum when the orientation guard is on, it reaches 1e-10 in
// 14.
TEST(ExactReconstruction, TheFoldGuardsExactHessianConvergesOnABend) {
    const TriMesh mesh = tube(12, 14, 5.0);
    const auto markers = everyNth(mesh.vertexCount(), 13);
    Reconstruction solver;
    SolverOptions options = exactOptions();
    options.relativeTolerance = 0;  // until no step can be seen
    options.maxIterations = 40;
    options.orientationGuard = 100;  // as for takes; no face comes near its threshold here
    solver.prepare(mesh, markers, options);
    const Positions pose = bent(mesh.V, 0.6);
    const SolveResult r = solver.solve(rows(pose, markers), &mesh.V);
    ASSERT_TRUE(r.report.converged) << "still going after " << r.report.iterations << " steps";
    const auto& e = r.report.energies;
    EXPECT_LE(stepsUntilWithin(e, 1e-10), 20);
    EXPECT_TRUE(std::is_sorted(e.rbegin(), e.rend()));
    // The control: without the orientation guard the exact method keeps the fixed-rotation
    // matrix (converged further there, it flips more faces), and the same bend is not done
    // after 40 steps.
    options.orientationGuard = 0;
    solver.setOptions(options);
    const SolveResult fixed = solver.solve(rows(pose, markers), &mesh.V);
    EXPECT_FALSE(fixed.report.converged) << fixed.report.iterations << " steps";
}

// The exact method solves a step with its last factor, from an earlier step of the same solve,
// as the preconditioner of conjugate gradients, to a residual of 1e-6: a factorisation costs
// dozens of such iterations on large meshes. Each step must be the one a factorisation gives: a
// solve of six steps lands where six solves of one step each (each factorising) land; a marker is
// missing, and the hard ones stay exactly on their targets. A factor is never taken from another
// solve (another frame): the answer would depend on which frame came before.
TEST(ExactReconstruction, StepsSolvedWithAnEarlierFactorAreTheStepsAFactorisationGives) {
    const TriMesh mesh = tube(40, 24, 10.0);
    const auto markers = everyNth(mesh.vertexCount(), 13);
    const double diagonal = boundingBoxDiagonal(mesh.V);
    SolverOptions options = exactOptions();
    options.relativeTolerance = 0;
    options.maxIterations = 6;
    Reconstruction solver;
    solver.prepare(mesh, markers, options);
    Positions target = rows(bent(mesh.V, 0.15), markers);
    target.row(3).setConstant(std::numeric_limits<double>::quiet_NaN());
    const SolveResult r = solver.solve(target, &mesh.V);
    ASSERT_EQ(r.report.iterations, 6);
    EXPECT_LT(r.report.directSteps, r.report.iterations) << "the factor was never reused";

    options.maxIterations = 1;
    Positions V = mesh.V;
    for (int step = 0; step < 6; ++step) {
        Reconstruction fresh;
        fresh.prepare(mesh, markers, options);
        const SolveResult one = fresh.solve(target, &V);
        ASSERT_EQ(one.report.directSteps, 1);
        V = one.V;
    }
    EXPECT_LE(maxDistance(r.V, V), 1e-7 * diagonal);
    for (size_t k = 0; k < markers.size(); ++k)
        if (k != 3) EXPECT_EQ(r.V.row(markers[k]), target.row(k));

    // The same solve again, after others: the same answer, to the last bit.
    solver.solve(rows(bent(mesh.V, 0.4), markers), &mesh.V);
    EXPECT_EQ(maxDistance(solver.solve(target, &mesh.V).V, r.V), 0.0);
}

TEST_P(EveryMethod, ReconstructsASmoothBendCloselyFromFewMarkers) {
    const TriMesh mesh = tube(16, 16, 6.0);
    const auto markers = everyNth(mesh.vertexCount(), 7);
    Reconstruction solver;
    solver.prepare(mesh, markers, options());
    const Positions pose = bent(mesh.V, 0.15);
    const SolveResult r = solver.solve(rows(pose, markers));
    const double rms = std::sqrt((r.V - pose).rowwise().squaredNorm().mean());
    EXPECT_LT(rms, 0.01 * boundingBoxDiagonal(mesh.V));
}

TEST_P(EveryMethod, MissingMarkersAreSolvedForAndStayFinite) {
    const TriMesh mesh = icosphere(3);
    const auto markers = everyNth(mesh.vertexCount(), 17);
    Reconstruction solver;
    solver.prepare(mesh, markers, options());
    Positions pose = mesh.V;
    pose.col(0) *= 1.2;  // a squash
    Positions targets = rows(pose, markers);
    targets.row(1).setConstant(std::numeric_limits<double>::quiet_NaN());
    const SolveResult r = solver.solve(targets, &mesh.V);
    EXPECT_TRUE(r.V.allFinite());
    EXPECT_GT((r.V.row(markers[1]) - mesh.V.row(markers[1])).norm(), 0.0);  // it moved freely
    // It sits where its neighbours' shape puts it, as the markers around it do: the squash
    // reaches it too (x grew by a fifth everywhere).
    EXPECT_GT(std::abs(r.V(markers[1], 0)), 1.05 * std::abs(mesh.V(markers[1], 0)));
}

TEST_P(EveryMethod, SoftConstraintsApproachTheTargetsAsTheWeightGrows) {
    const TriMesh mesh = tube(10, 10, 4.0);
    const auto markers = everyNth(mesh.vertexCount(), 9);
    const Positions pose = bent(mesh.V, 0.3);
    double previous = std::numeric_limits<double>::infinity();
    for (double weight : {1.0, 100.0, 1e4}) {
        SolverOptions o = options();
        o.constraints = SolverOptions::Constraints::Soft;
        o.markerWeight = weight;
        Reconstruction solver;
        solver.prepare(mesh, markers, o);
        const SolveResult r = solver.solve(rows(pose, markers));
        const double miss = maxDistance(rows(r.V, markers), rows(pose, markers));
        EXPECT_LT(miss, previous);
        previous = miss;
    }
    EXPECT_LT(previous, 1e-3);
}

TEST_P(EveryMethod, MeshesWithBoundariesAndDegenerateFacesGiveFiniteResults) {
    TriMesh mesh = tube(8, 10, 3.0);
    mesh.V.row(25) = mesh.V.row(26);  // two zero-area faces
    const auto markers = everyNth(mesh.vertexCount(), 8);
    Reconstruction solver;
    solver.prepare(mesh, markers, options());
    const SolveResult r = solver.solve(rows(bent(mesh.V, 0.5), markers));
    EXPECT_TRUE(r.V.allFinite());
}

// Scans carry stray slivers: a triangle of its own whose corners lie on a line up to rounding has
// no angles to keep, but computed naively cotangents of ±1e15, which took over the ARAP term's
// scale (a solve of the MakeHuman-sized walker failed: "could not be factorised").
TEST_P(EveryMethod, AStrayTriangleWhoseCornersLieOnALineChangesNothingElse) {
    const TriMesh mesh = tube(8, 10, 3.0);
    const int n = mesh.vertexCount();
    TriMesh withSliver = mesh;
    withSliver.V.conservativeResize(n + 3, 3);
    const Vec3 start(5.1, 0.3, 0.7), step = Vec3(0.1, 0.2, 0.3) / 3.0;
    for (int i = 0; i < 3; ++i) withSliver.V.row(n + i) = (start + i * step).transpose();
    withSliver.F.conservativeResize(mesh.faceCount() + 1, 3);
    withSliver.F.row(mesh.faceCount()) << n, n + 1, n + 2;
    const Vec3 a = withSliver.V.row(n), b = withSliver.V.row(n + 1), c = withSliver.V.row(n + 2);
    ASSERT_GT((b - a).cross(c - a).norm(), 0.0);  // rounded, not exactly flat
    const auto markers = everyNth(n, 8);
    const Positions pose = bent(mesh.V, 0.5);
    for (const auto constraints :
         {SolverOptions::Constraints::Hard, SolverOptions::Constraints::Soft}) {
        SolverOptions o = options();
        o.constraints = constraints;
        Reconstruction plain, sliver;
        plain.prepare(mesh, markers, o);
        sliver.prepare(withSliver, markers, o);
        const SolveResult r = sliver.solve(rows(pose, markers));
        const Positions& V = r.V;
        ASSERT_TRUE(V.allFinite());
        // It has no side to fold over: counted from the shapes, since Exact reports −1 (not
        // counted), and by the method where it counts.
        EXPECT_EQ(foldedFaceCount(withSliver.F, V, withSliver.V), 0);
        if (r.report.foldedFaces >= 0) EXPECT_EQ(r.report.foldedFaces, 0);
        EXPECT_LE(maxDistance(V.topRows(n), plain.solve(rows(pose, markers)).V), 1e-6);
    }
}

TEST_P(EveryMethod, RejectsBadMarkerSetsAndTargets) {
    const TriMesh mesh = icosphere(1);
    Reconstruction solver;
    EXPECT_THROW(solver.prepare(mesh, {0, 5, 5}, options()), SolverError);
    EXPECT_THROW(solver.prepare(mesh, {0, 500}, options()), SolverError);
    solver.prepare(mesh, {0, 1, 2}, options());
    EXPECT_THROW(solver.solve(Positions::Zero(2, 3)), SolverError);
}

namespace {
// Markers sitting `offset` off the skin of `pose`, along each marker vertex's ring normal.
Positions offsetTargets(const Reconstruction& solver, const Positions& pose,
                        const std::vector<int>& markers, double offset) {
    Positions targets(markers.size(), 3);
    for (size_t k = 0; k < markers.size(); ++k)
        targets.row(k) = pose.row(markers[k]) +
                         offset * solver.encoding().ringNormal(markers[k], pose).transpose();
    return targets;
}
}  // namespace

TEST_P(EveryMethod, MarkersOffTheSkinGiveBackTheRestMeshAndMoveRigidly) {
    const TriMesh mesh = tube(10, 12, 4.0);
    const auto markers = everyNth(mesh.vertexCount(), 9);
    SolverOptions o = options();
    o.constraints = SolverOptions::Constraints::Soft;
    o.markerOffsets.assign(markers.size(), 0.15);
    o.maxIterations = 100;
    o.relativeTolerance = 1e-14;
    Reconstruction solver;
    solver.prepare(mesh, markers, o);
    const double tolerance = 1e-6 * boundingBoxDiagonal(mesh.V);

    // Soft markers make the system worse conditioned than hard ones: 1e-7 is round-off here.
    const SolveResult rest = solver.solve(offsetTargets(solver, mesh.V, markers, 0.15), &mesh.V);
    EXPECT_LE(maxDistance(rest.V, mesh.V), 1e-7 * boundingBoxDiagonal(mesh.V));

    std::mt19937 rng(21);
    const Positions expected = moved(mesh.V, randomRotation(rng), Vec3(1, 2, 3));
    const SolveResult r = solver.solve(offsetTargets(solver, expected, markers, 0.15));
    EXPECT_LE(maxDistance(r.V, expected), tolerance);

    // Ignoring the offset would swell the tube towards the markers: the model matters.
    SolverOptions onSkin = o;
    onSkin.markerOffsets.clear();
    Reconstruction naive;
    naive.prepare(mesh, markers, onSkin);
    const SolveResult swollen = naive.solve(offsetTargets(naive, expected, markers, 0.15));
    EXPECT_GT(maxDistance(swollen.V, expected), 0.05);
}

TEST_P(EveryMethod, OffsetsNeedSoftConstraintsAndOnePerMarker) {
    const TriMesh mesh = icosphere(1);
    SolverOptions o = options();
    o.markerOffsets = {0.1, 0.1, 0.1};
    Reconstruction solver;
    EXPECT_THROW(solver.prepare(mesh, {0, 1, 2}, o), SolverError);
    o.constraints = SolverOptions::Constraints::Soft;
    EXPECT_THROW(solver.prepare(mesh, {0, 1}, o), SolverError);
    EXPECT_NO_THROW(solver.prepare(mesh, {0, 1, 2}, o));
}

// A caller whose request has been superseded (the app's scrub) raises the stop flag: the solve
// returns before its first iteration, says so, and a flag left down changes nothing.
TEST_P(EveryMethod, ARaisedStopEndsTheSolveAndALoweredOneChangesNothing) {
    const TriMesh mesh = tube(16, 16, 6.0);
    const auto markers = everyNth(mesh.vertexCount(), 7);
    Reconstruction solver;
    solver.prepare(mesh, markers, options());
    const Positions targets = rows(bent(mesh.V, 0.3), markers);
    const SolveResult plain = solver.solve(targets);
    std::atomic<bool> stop{false};
    const SolveResult down = solver.solve(targets, nullptr, &stop);
    EXPECT_FALSE(down.report.stopped);
    EXPECT_EQ(maxDistance(down.V, plain.V), 0.0);
    stop = true;
    const SolveResult up = solver.solve(targets, nullptr, &stop);
    EXPECT_TRUE(up.report.stopped);
    EXPECT_EQ(up.report.iterations, 0);
}
