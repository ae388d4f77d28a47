#include <gtest/gtest.h>

#include "boneless/DemoCreature.h"
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
