#include <gtest/gtest.h>

#include "DemoCreature.h"
#include "boneless/MeshTopology.h"
#include "boneless/Metrics.h"
#include "boneless/Reconstruction.h"
#include "boneless/Sampling.h"

using namespace boneless;

TEST(DemoCreature, IsAClosedManifoldThatReallyMoves) {
    const DemoCreature demo = makeDemoCreature(40);
    MeshTopology topology(demo.rest);  // throws on a non-manifold vertex
    EXPECT_EQ(topology.boundaryVertexCount(), 0);
    EXPECT_GT(demo.rest.faceCount(), 2000);
    EXPECT_LT(demo.rest.faceCount(), 10000);
    ASSERT_EQ(demo.frames.size(), 40u);
    EXPECT_EQ(demo.frames[0], demo.rest.V);
    const double diagonal = boundingBoxDiagonal(demo.rest.V);
    EXPECT_GT(maxVertexError(demo.frames[30], demo.rest.V), 0.1 * diagonal);
    // A swim bends the body; it should not stretch it much.
    EXPECT_LT(edgeLengthDistortion(demo.rest.F, demo.frames[30], demo.rest.V), 0.1);
    EXPECT_EQ(flippedFaceCount(demo.rest.F, demo.rest.V, demo.rest.V), 0);
}

// Outward faces make the ring normals, and with them the demo take's marker offsets, point out of
// the body: markers sit on the skin's outside, where a viewer sees them.
TEST(DemoCreature, FacesPointOutwards) {
    const DemoCreature demo = makeDemoCreature(2);
    double signedVolume = 0;
    for (int f = 0; f < demo.rest.faceCount(); ++f) {
        const Eigen::Vector3d a = demo.rest.V.row(demo.rest.F(f, 0));
        const Eigen::Vector3d b = demo.rest.V.row(demo.rest.F(f, 1));
        const Eigen::Vector3d c = demo.rest.V.row(demo.rest.F(f, 2));
        signedVolume += a.dot(b.cross(c)) / 6.0;
    }
    EXPECT_GT(signedVolume, 0.0);
}
