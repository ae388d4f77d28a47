// The local/global method: what it adds to the invariants every method keeps
// (ReconstructionTest.cpp): no history, gaps without refactorising, no folds, a coarse level.
#include <gtest/gtest.h>

#include <limits>
#include <random>

#include "LocalGlobal.h"
#include "TestMeshes.h"
#include "boneless/Metrics.h"
#include "boneless/Reconstruction.h"

using namespace boneless;
using namespace boneless::testing;

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// Large enough for a coarse level of its own (more than twice the thousand vertices of one).
TriMesh largeTube() {
    return tube(60, 40, 12.0);
}

SolverOptions soft() {
    SolverOptions o;
    o.constraints = SolverOptions::Constraints::Soft;
    return o;
}

}  // namespace

// The app shows a frame it solves when the playhead stops there, and the export solves frames
// in order on two cores: both must give the same answer, whatever came before.
TEST(LocalGlobal, TheSameFrameComesOutWhateverFramesWereSolvedBefore) {
    for (const TriMesh& mesh : {tube(20, 16, 6.0), largeTube()}) {
        for (SolverOptions options : {SolverOptions{}, soft()}) {
            const auto markers = everyNth(mesh.vertexCount(), 23);
            auto frame = [&](double amount) {
                Positions targets = rows(bent(mesh.V, amount), markers);
                if (amount > 0.5) targets.row(2).setConstant(kNaN);  // a gap in some frames
                return targets;
            };
            Reconstruction fresh, visited;
            fresh.prepare(mesh, markers, options);
            visited.prepare(mesh, markers, options);
            const Positions first = fresh.solve(frame(0.3)).V;
            for (double amount : {0.6, 0.05, 0.9}) visited.solve(frame(amount));
            const Positions later = visited.solve(frame(0.3)).V;
            EXPECT_EQ(maxDistance(first, later), 0.0) << mesh.vertexCount() << " vertices";
            // A guess changes nothing either: there is no history to pass in.
            const Positions guessed = visited.solve(frame(0.3), &mesh.V).V;
            EXPECT_EQ(maxDistance(first, guessed), 0.0);
        }
    }
}

// The invariants every method keeps, on a mesh that goes through the coarse level.
TEST(LocalGlobal, ThroughItsCoarseLevelRestIsRestAndARigidMotionIsRigid) {
    const TriMesh mesh = largeTube();
    const auto markers = everyNth(mesh.vertexCount(), 31);
    const double diagonal = boundingBoxDiagonal(mesh.V);
    Reconstruction solver;
    solver.prepare(mesh, markers);
    EXPECT_LE(maxDistance(solver.solve(rows(mesh.V, markers)).V, mesh.V), 1e-9 * diagonal);
    std::mt19937 rng(7);
    const Positions expected = moved(mesh.V, randomRotation(rng), Vec3(3, -1, 2));
    EXPECT_LE(maxDistance(solver.solve(rows(expected, markers)).V, expected), 1e-7 * diagonal);
    // And a bend comes out close to the truth, from one marker in 31.
    const Positions pose = bent(mesh.V, 0.15);
    const Positions V = solver.solve(rows(pose, markers)).V;
    EXPECT_LT(std::sqrt((V - pose).rowwise().squaredNorm().mean()), 0.005 * diagonal);
}

// A gap is the factor of every marker corrected for the missing ones (a Schur complement when
// hard, Woodbury when soft), never a factorisation of its own: the answer must be the one a
// solver prepared without those markers gives, from the same start and the same rotations.
TEST(LocalGlobal, AGapGivesWhatASolverWithoutThoseMarkersGives) {
    const TriMesh mesh = tube(16, 14, 6.0);
    const MeshTopology topology(mesh);
    const ShapeEncoding encoding(mesh, topology);
    const auto markers = everyNth(mesh.vertexCount(), 9);
    const Positions pose = bent(mesh.V, 0.4);
    const std::vector<int> missing = {1, 4, 5};
    std::vector<int> kept;
    for (int k = 0; k < static_cast<int>(markers.size()); ++k)
        if (std::find(missing.begin(), missing.end(), k) == missing.end())
            kept.push_back(markers[k]);
    for (bool hard : {true, false}) {
        LocalGlobalSolver::Settings settings;
        settings.hard = hard;
        settings.iterations = 4;
        LocalGlobalSolver all(mesh, topology, encoding, vertexPatches(mesh, encoding, markers),
                              settings);
        LocalGlobalSolver some(mesh, topology, encoding, vertexPatches(mesh, encoding, kept),
                               settings);
        Positions targets = rows(pose, markers);
        for (int k : missing) targets.row(k).setConstant(kNaN);
        const std::vector<Mat3> identity(mesh.vertexCount(), Mat3::Identity());
        const LocalGlobalSolver::FirstRotations first{&identity, &identity, false};
        const Positions withGap = all.solve(targets, {}, mesh.V, first).V;
        const Positions without = some.solve(rows(pose, kept), {}, mesh.V, first).V;
        EXPECT_LE(maxDistance(withGap, without), 1e-8 * boundingBoxDiagonal(mesh.V))
            << (hard ? "hard" : "soft");
        // And the missing markers' vertices did move: they are solved for, not held.
        for (int k : missing)
            EXPECT_GT((withGap.row(markers[k]) - mesh.V.row(markers[k])).norm(), 1e-3)
                << "marker " << k;
    }
}

// Slivers bent hard, soft markers: the single-level solver without repair leaves faces turned
// over (the global step's compromise), and the same solver with it.
struct BentSlivers {
    TriMesh mesh = tubeWithSlivers();
    MeshTopology topology{mesh};
    ShapeEncoding encoding{mesh, topology};
    std::vector<int> markers;
    Positions truth = bent(mesh.V, 1.0);
    BentSlivers() {
        for (int r = 0; r < 10; r += 3)
            for (int s = 0; s < 12; s += 3) markers.push_back(r * 12 + s);
    }
    SolveResult solve(const Positions& targets, bool repair) const {
        LocalGlobalSolver::Settings settings;
        settings.hard = false;
        settings.iterations = 20;
        settings.repairFolds = repair;
        LocalGlobalSolver solver(mesh, topology, encoding, vertexPatches(mesh, encoding, markers),
                                 settings);
        return solver.solve(targets, {}, mesh.V, {});
    }
};

TEST(LocalGlobal, FacesTheGlobalStepTurnsOverAreRepaired) {
    const BentSlivers c;
    const Positions targets = rows(c.truth, c.markers);
    const Positions unrepaired = c.solve(targets, false).V;
    ASSERT_GT(foldedFaceCount(c.mesh.F, unrepaired, c.mesh.V), 0) << "the case no longer folds";
    const SolveResult r = c.solve(targets, true);
    EXPECT_EQ(foldedFaceCount(c.mesh.F, r.V, c.mesh.V), 0);
    EXPECT_EQ(r.report.foldedFaces, 0);
    // Faces the repair did not need are where they were.
    EXPECT_LE(maxDistance(r.V, c.truth), 1.05 * maxDistance(unrepaired, c.truth));
}

// The same with one marker missing beside the slivers: the repair solves the frame's own
// quadratic, so the missing marker's weight is not on the diagonal and its vertex is not pulled
// towards the origin.
TEST(LocalGlobal, ARepairBesideAMissingSoftMarkerLeavesItsVertexWhereTheShapePutsIt) {
    const BentSlivers c;
    Positions targets = rows(c.truth, c.markers);
    const int missing = 5;  // ring 3, next to the slivers
    targets.row(missing).setConstant(kNaN);
    const Positions unrepaired = c.solve(targets, false).V;
    ASSERT_GT(foldedFaceCount(c.mesh.F, unrepaired, c.mesh.V), 0) << "the case no longer folds";
    const SolveResult r = c.solve(targets, true);
    EXPECT_EQ(r.report.foldedFaces, 0);
    const int v = c.markers[missing];
    EXPECT_LT((r.V.row(v) - unrepaired.row(v)).norm(), 0.1 * boundingBoxDiagonal(c.mesh.V));
    EXPECT_LE(maxDistance(r.V, c.truth), 1.05 * maxDistance(unrepaired, c.truth));
}
