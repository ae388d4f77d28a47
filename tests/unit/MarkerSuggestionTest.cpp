#include <gtest/gtest.h>

#include <filesystem>
#include <random>

#include "TestMeshes.h"
#include "boneless/C3dReader.h"
#include "boneless/C3dTake.h"
#include "boneless/Error.h"
#include "boneless/MarkerSuggestion.h"
#include "boneless/MeshReader.h"

using namespace boneless;
using namespace boneless::testing;

namespace {

// A take whose markers sit on the given vertices of `mesh` (from the `liftFrom`-th marker on,
// `lift` off the skin), seen in millimetres from another orientation and origin.
C3dTake takeOnVertices(const TriMesh& mesh, const std::vector<int>& ids, double lift,
                       size_t liftFrom) {
    std::mt19937 rng(9);
    const Mat3 R = randomRotation(rng);
    C3dTake take;
    take.file = "synthetic.c3d";
    take.samples = C3dSamples(3, ids.size());
    for (size_t k = 0; k < ids.size(); ++k) {
        C3dPoint p;
        p.label = "actor:M" + std::to_string(k);
        splitC3dLabel(p.label, p.subject, p.name);
        take.points.push_back(p);
        const Vec3 onSkin = mesh.V.row(ids[k]).transpose();
        const Vec3 x = onSkin * (k >= liftFrom ? 1.0 + lift : 1.0);  // normal = position
        for (int f = 0; f < 3; ++f) {
            const Vec3 y = 1000.0 * R * x + Vec3(100, 200, 300 + f);
            take.samples.set(f, k, y.x(), y.y(), y.z());
        }
    }
    return take;
}

}  // namespace

TEST(MarkerSuggestion, FindsTheVerticesUnderTheUnmappedMarkers) {
    const TriMesh mesh = icosphere(2);
    const std::vector<int> ids{0, 7, 19, 33, 48, 77, 101, 150};
    const C3dTake take = takeOnVertices(mesh, ids, 0.01, 4);
    Correspondence partial;
    partial.meshVertices = mesh.vertexCount();
    for (int k = 0; k < 4; ++k)
        partial.markers.push_back({"M" + std::to_string(k), ids[k], 0, "{}"});
    const Suggestion s = suggestMappings(mesh, take, partial);
    EXPECT_EQ(s.suggested, 4);
    ASSERT_EQ(s.map.markers.size(), 8u);
    for (size_t k = 4; k < 8; ++k) {
        EXPECT_EQ(s.map.markers[k].label, "M" + std::to_string(k));
        EXPECT_EQ(s.map.markers[k].vertex, ids[k]);
        EXPECT_NEAR(s.map.markers[k].offsetMm, 10.0, 0.5);  // 1 % of a 1 m radius, in mm
    }
    EXPECT_NEAR(s.calibration.takeToMesh.scale, 1e-3, 1e-12);
}

TEST(MarkerSuggestion, NeedsFourMappedMarkers) {
    const TriMesh mesh = icosphere(1);
    const C3dTake take = takeOnVertices(mesh, {0, 1, 2, 3, 4}, 0.0, 0);
    Correspondence partial;
    for (int k = 0; k < 3; ++k) partial.markers.push_back({"M" + std::to_string(k), k, 0, "{}"});
    EXPECT_THROW(suggestMappings(mesh, take, partial), Error);
}

// From 6 correct picks (shoulders, wrists, ankles) on CMU 85_02, the MakeHuman map in tests/data
// is found again for the markers the fit pins down. Measured: 14 of 35 within 30 mm (the rigid
// alignment alone: 5 of 35 in issue 28's trial), median 38 mm; the target is 80 %.
TEST(MarkerSuggestion, SixPicksOnTheCmuTakeLandNearThePublishedMap) {
    const std::filesystem::path data = BONELESS_SHARED_DATA;
    const auto take = data / "c3d" / "cmu" / "85_02.c3d";
    const auto mesh = data / "meshes" / "makehuman" / "makehuman_base.obj";
    if (!std::filesystem::exists(take) || !std::filesystem::exists(mesh))
        GTEST_SKIP() << "no shared data (" << data << ")";
    MeshReadOptions group;
    group.group = "body";
    const TriMesh body = readMesh(mesh.string(), group).mesh;
    const C3dTake cmu = readC3d(take.string());
    const Correspondence published =
        Correspondence::read(BONELESS_SOURCE_DIR "/tests/data/cmu-85_02-makehuman-body.map.json");
    Correspondence picks = published;
    picks.markers.clear();
    for (const char* label : {"LSHO", "RSHO", "LWRA", "RWRA", "LANK", "RANK"})
        picks.markers.push_back(*published.find(label));
    const Suggestion s = suggestMappings(body, cmu, picks);
    const SuggestionCheck check = checkSuggestion(body, cmu, s, published, 30.0);
    std::printf("%d of %d within 30 mm, median %.1f mm, %d to review\n", check.within,
                check.compared, check.medianMm, s.needsReview);
    EXPECT_EQ(check.compared, 35);
    EXPECT_GE(check.within, 12);
    EXPECT_LT(check.medianMm, 50.0);
}
