// The ARAP deformer eval compares Boneless with: its invariants, and errors that give the counts.
#include <gtest/gtest.h>

#include <random>

#include "TestMeshes.h"
#include "boneless/ArapDeformer.h"
#include "boneless/Error.h"

namespace boneless::testing {
namespace {

TEST(ArapDeformer, RestMarkersGiveBackTheRestAndARigidMotionMovesItRigidly) {
    const TriMesh rest = icosphere(2);
    const std::vector<int> markers = everyNth(rest.vertexCount(), 9);
    ArapDeformer arap;
    arap.prepare(rest, markers, {});
    EXPECT_LT(maxDistance(arap.solve(rows(rest.V, markers)).V, rest.V), 1e-9);
    std::mt19937 rng(5);
    const Positions turned = moved(rest.V, randomRotation(rng), {0.3, -1.0, 2.0});
    EXPECT_LT(maxDistance(arap.solve(rows(turned, markers)).V, turned), 1e-6);
}

TEST(ArapDeformer, AMarkerOffTheMeshAndAWrongTargetCountAreErrorsWithTheirCounts) {
    const TriMesh rest = icosphere(1);
    ArapDeformer arap;
    try {
        arap.prepare(rest, {0, 5, rest.vertexCount()}, {});
        FAIL() << "a marker past the last vertex was accepted";
    } catch (const SolverError& e) {
        EXPECT_EQ(std::string(e.what()),
                  "ARAP: marker 2 is attached to vertex " + std::to_string(rest.vertexCount()) +
                      ", but the mesh has " + std::to_string(rest.vertexCount()) + " vertices");
    }
    arap.prepare(rest, {0, 5, 9}, {});
    try {
        arap.solve(Positions::Zero(2, 3));
        FAIL() << "two targets for three markers were accepted";
    } catch (const SolverError& e) {
        EXPECT_EQ(std::string(e.what()), "ARAP: expected 3 marker targets, got 2");
    }
}

}  // namespace
}  // namespace boneless::testing
