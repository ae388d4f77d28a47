// The walker: the demo a newcomer sees, so it must be a body, move like one and be captured like
// one.
#include <gtest/gtest.h>

#include <map>
#include <set>

#include "DemoWalker.h"
#include "boneless/MeshTopology.h"
#include "boneless/Metrics.h"
#include "boneless/ShapeEncoding.h"

using namespace boneless;

namespace {

const DemoWalker& walker() {
    static const DemoWalker w = makeDemoWalker(40);
    return w;
}

Vec3 markerOnSkin(const std::string& label, int frame = 0) {
    for (const auto& [name, vertex] : walker().markerVertices)
        if (name == label) return walker().frames[frame].row(vertex).transpose();
    ADD_FAILURE() << "no marker " << label;
    return Vec3::Zero();
}

}  // namespace

TEST(DemoWalker, IsOneClosedSurfaceFacingOutwards) {
    const TriMesh& rest = walker().rest;
    MeshTopology topology(rest);  // throws on a non-manifold vertex
    EXPECT_EQ(topology.boundaryVertexCount(), 0);
    // One closed surface without handles: V − E + F = 2, with E = 3F/2.
    EXPECT_EQ(rest.vertexCount() - rest.faceCount() * 3 / 2 + rest.faceCount(), 2);
    EXPECT_GT(rest.faceCount(), 2000);
    EXPECT_LT(rest.faceCount(), 10000);
    double signedVolume = 0;
    for (int f = 0; f < rest.faceCount(); ++f) {
        const Vec3 a = rest.V.row(rest.F(f, 0)), b = rest.V.row(rest.F(f, 1)),
                   c = rest.V.row(rest.F(f, 2));
        signedVolume += a.dot(b.cross(c)) / 6.0;
    }
    // Outward faces (ring normals, and so the markers' offsets, point out), and a body's
    // volume: tens of litres.
    EXPECT_GT(signedVolume, 0.03);
    EXPECT_LT(signedVolume, 0.15);
}

TEST(DemoWalker, StandsAsTallAsAPersonAndWalksWithoutStretching) {
    const DemoWalker& w = walker();
    const Vec3 low = w.rest.V.colwise().minCoeff(), high = w.rest.V.colwise().maxCoeff();
    EXPECT_NEAR(high.z() - low.z(), 1.8, 0.15);  // metres, z up
    EXPECT_NEAR(low.z(), 0.0, 0.05);             // feet on the floor
    ASSERT_EQ(w.frames.size(), 40u);
    EXPECT_EQ(w.frames[0], w.rest.V);
    // Frames 7 and 22 are half a gait cycle apart: feet and hands swing from front to back by
    // tens of centimetres, and the limbs keep their length.
    EXPECT_GT((markerOnSkin("LTOE", 22) - markerOnSkin("LTOE", 7)).norm(), 0.3);
    EXPECT_GT((markerOnSkin("RWRA", 22) - markerOnSkin("RWRA", 7)).norm(), 0.1);
    for (int f : {10, 22, 35}) {
        EXPECT_LT(edgeLengthDistortion(w.rest.F, w.frames[f], w.rest.V), 0.25) << "frame " << f;
        EXPECT_EQ(foldedFaceCount(w.rest.F, w.frames[f], w.rest.V), 0) << "frame " << f;
    }
}

TEST(DemoWalker, WearsAFullBodyMarkerSetWhereItsNamesSay) {
    const DemoWalker& w = walker();
    ASSERT_GE(w.markerVertices.size(), 30u);
    ASSERT_LE(w.markerVertices.size(), 40u);
    std::set<int> vertices;
    for (const auto& [label, vertex] : w.markerVertices) {
        EXPECT_TRUE(vertices.insert(vertex).second) << label << " shares a vertex";
        const Vec3 p = markerOnSkin(label);
        if (label[0] == 'L' && label != "LFHD") EXPECT_GT(p.x(), 0.02) << label;  // left is +x
        if (label[0] == 'R' && label != "RBAK") EXPECT_LT(p.x(), -0.02) << label;
    }
    // Top to bottom, as on a person standing.
    for (const char* side : {"L", "R"}) {
        const std::string s = side;
        EXPECT_GT(markerOnSkin(s + "FHD").z(), markerOnSkin(s + "SHO").z());
        EXPECT_GT(markerOnSkin(s + "SHO").z(), markerOnSkin(s + "ELB").z());
        EXPECT_GT(markerOnSkin(s + "ELB").z(), markerOnSkin(s + "WRA").z());
        EXPECT_GT(markerOnSkin(s + "ASI").z(), markerOnSkin(s + "KNE").z());
        EXPECT_GT(markerOnSkin(s + "KNE").z(), markerOnSkin(s + "ANK").z());
        EXPECT_LT(markerOnSkin(s + "FHD").y(), markerOnSkin(s + "BHD").y());  // front is −y
        EXPECT_LT(markerOnSkin(s + "TOE").y(), markerOnSkin(s + "HEE").y());
    }
}

TEST(DemoWalker, TheTakeHasItsMarkersOffTheSkinAndSomeGaps) {
    const DemoWalker& w = walker();
    const DemoTake t = makeDemoWalkerTake(w, 10.0);
    const int K = static_cast<int>(t.take.points.size());
    ASSERT_EQ(K, static_cast<int>(w.markerVertices.size()));
    ASSERT_EQ(t.map.markers.size(), w.markerVertices.size());
    int missing = 0;
    for (int f = 0; f < static_cast<int>(t.take.frameCount()); ++f)
        for (int k = 0; k < K; ++k) missing += t.take.samples.valid(f, k) ? 0 : 1;
    EXPECT_GT(missing, 0);
    EXPECT_LT(missing, K * static_cast<int>(t.take.frameCount()) / 20);
    // Two markers on one rigid piece (the head) keep their distance, 10 mm off the skin on each
    // side making it larger than on the skin.
    auto at = [&](const std::string& label, int f) {
        for (int k = 0; k < K; ++k)
            if (t.take.points[k].name == label) return t.take.samples.position(f, k).value();
        ADD_FAILURE() << "no marker " << label;
        return Vec3(Vec3::Zero());
    };
    const double onSkinMm = 1000 * (markerOnSkin("LFHD") - markerOnSkin("LBHD")).norm();
    const double capturedMm = (at("LFHD", 0) - at("LBHD", 0)).norm();
    EXPECT_NEAR(capturedMm, onSkinMm + 20, 3);
}
