// The sidecar's strain gauge: rest lengths measured once, every frame's strains against them.
#include <gtest/gtest.h>

#include "TestMeshes.h"
#include "boneless/ActorCalibration.h"
#include "boneless/Metrics.h"

namespace boneless::testing {
namespace {

TEST(EdgeStrain, EachFaceCornersEdgeOfAUniformScaleIsStrainedByTheScale) {
    const TriMesh mesh = icosphere(1);
    const std::vector<double> strains = EdgeStrain(mesh.F, mesh.V).strains(1.1 * mesh.V);
    ASSERT_EQ(strains.size(), 3u * mesh.F.rows());  // interior edges twice, as face corners
    for (double s : strains) EXPECT_NEAR(s, 0.1, 1e-12);
}

TEST(EdgeStrain, ItsRootMeanSquareIsTheEdgeDistortionToTheLastDigit) {
    const TriMesh mesh = tube(12, 10, 4.0);
    const EdgeStrain gauge(mesh.F, mesh.V);
    for (double amount : {0.2, 0.7, 1.4}) {
        const Positions V = bent(mesh.V, amount);
        EXPECT_EQ(rootMeanSquare(gauge.strains(V)), edgeLengthDistortion(mesh.F, V, mesh.V));
    }
}

TEST(EdgeStrain, AnEdgeWithNoLengthAtRestHasNoStrain) {
    TriMesh mesh = icosphere(1);
    mesh.V.row(mesh.F(0, 1)) = mesh.V.row(mesh.F(0, 0));  // face 0's first edge collapsed
    const EdgeStrain gauge(mesh.F, mesh.V);
    const std::vector<double> strains = gauge.strains(1.5 * mesh.V);
    EXPECT_LT(strains.size(), 3u * mesh.F.rows());
    for (double s : strains) EXPECT_NEAR(s, 0.5, 1e-12);
    EXPECT_EQ(rootMeanSquare({}), 0.0);
}

}  // namespace
}  // namespace boneless::testing
