#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <optional>
#include <random>

#include "DemoWalker.h"
#include "TestMeshes.h"
#include "boneless/ActorCalibration.h"
#include "boneless/C3dReader.h"
#include "boneless/C3dTake.h"
#include "boneless/Error.h"
#include "boneless/MarkerSuggestion.h"
#include "boneless/MeshReader.h"
#include "boneless/SuggestionCheck.h"

using namespace boneless;
using namespace boneless::testing;

namespace {

// A take whose markers stand at frames[f][k] (mesh units) in frame f, seen in millimetres from
// another orientation and origin.
C3dTake takeOver(const std::vector<std::vector<Vec3>>& frames,
                 const std::vector<std::string>& labels = {}) {
    std::mt19937 rng(9);
    const Mat3 R = randomRotation(rng);
    C3dTake take;
    take.file = "synthetic.c3d";
    take.samples = C3dSamples(frames.size(), frames[0].size());
    for (size_t k = 0; k < frames[0].size(); ++k) {
        C3dPoint p;
        p.label = "actor:" + (k < labels.size() ? labels[k] : "M" + std::to_string(k));
        splitC3dLabel(p.label, p.subject, p.name);
        take.points.push_back(p);
        for (size_t f = 0; f < frames.size(); ++f) {
            const Vec3 y = 1000.0 * R * frames[f][k] + Vec3(100, 200, 300.0 + f);
            take.samples.set(f, k, y.x(), y.y(), y.z());
        }
    }
    return take;
}

// Three frames of markers standing still at the given points.
C3dTake takeAt(const std::vector<Vec3>& points, const std::vector<std::string>& labels = {}) {
    return takeOver({points, points, points}, labels);
}

// A take whose markers sit on the given vertices of a sphere `mesh` (from the `liftFrom`-th
// marker on, `lift` off the skin).
C3dTake takeOnVertices(const TriMesh& mesh, const std::vector<int>& ids, double lift,
                       size_t liftFrom, const std::vector<std::string>& labels = {}) {
    std::vector<Vec3> points;
    for (size_t k = 0; k < ids.size(); ++k)  // the normal is the position
        points.push_back(mesh.V.row(ids[k]).transpose() * (k >= liftFrom ? 1.0 + lift : 1.0));
    return takeAt(points, labels);
}

}  // namespace

TEST(MarkerSuggestion, FindsTheVerticesUnderTheUnmappedMarkers) {
    const TriMesh mesh = icosphere(2);
    const std::vector<int> ids{0, 7, 19, 33, 48, 77, 101, 150};
    // Every marker 10 mm off a 1 m sphere, as the picks say (two at 10 mm, two at 12).
    const C3dTake take = takeOnVertices(mesh, ids, 0.01, 0);
    Correspondence partial;
    partial.meshVertices = mesh.vertexCount();
    for (int k = 0; k < 4; ++k)
        partial.markers.push_back({"M" + std::to_string(k), ids[k], k < 2 ? 10.0 : 12.0, "{}"});
    const Suggestion s = suggestMappings(mesh, take, partial);
    EXPECT_EQ(s.suggested, 4);
    ASSERT_EQ(s.map.markers.size(), 8u);
    for (size_t k = 4; k < 8; ++k) {
        const MarkerMapping* m = s.map.find("M" + std::to_string(k));
        ASSERT_NE(m, nullptr);
        EXPECT_EQ(m->vertex, ids[k]);
        EXPECT_EQ(m->offsetMm, 12.0);  // the picks' median, not the distance to a fit
    }
    EXPECT_NEAR(s.calibration.takeToMesh.scale, 1e-3, 1e-5);  // millimetres to metres
}

// The app stops a suggestion when its window closes: it says so and suggests nothing, rather than
// a map made from the fits scanned so far.
TEST(MarkerSuggestion, AStopSetSaysStoppedAndSuggestsNothing) {
    const TriMesh mesh = icosphere(2);
    const std::vector<int> ids{0, 7, 19, 33, 48, 77, 101, 150};
    const C3dTake take = takeOnVertices(mesh, ids, 0.01, 0);
    Correspondence partial;
    partial.meshVertices = mesh.vertexCount();
    for (int k = 0; k < 4; ++k)
        partial.markers.push_back({"M" + std::to_string(k), ids[k], 10.0, "{}"});
    const std::atomic<bool> stop{true};
    const Suggestion s = suggestMappings(mesh, take, partial, std::nullopt, &stop);
    EXPECT_TRUE(s.stopped);
    EXPECT_EQ(s.suggested, 0);
    EXPECT_TRUE(s.proposals.empty() && s.offBody.empty());
    EXPECT_EQ(s.map.toJson(), partial.toJson());
    const std::atomic<bool> go{false};
    EXPECT_FALSE(suggestMappings(mesh, take, partial, std::nullopt, &go).stopped);
}

TEST(MarkerSuggestion, AMapThatHoldsEveryMarkerSeenGetsNothingSuggested) {
    const TriMesh mesh = icosphere(2);
    const std::vector<int> ids{0, 7, 19, 33, 48, 77};
    C3dTake take = takeOnVertices(mesh, ids, 0.01, 0);
    for (std::size_t f = 0; f < take.frameCount(); ++f)  // M5 is never seen
        take.samples.set(f, 5, NAN, NAN, NAN);
    Correspondence full;
    full.meshVertices = mesh.vertexCount();
    for (size_t k = 0; k < 5; ++k)
        full.markers.push_back({"M" + std::to_string(k), ids[k], 10.0, "{}"});
    const Suggestion s = suggestMappings(mesh, take, full);
    EXPECT_EQ(s.suggested, 0);
    EXPECT_TRUE(s.proposals.empty());
    EXPECT_EQ(s.fittedFrame, -1);
    ASSERT_EQ(s.map.markers.size(), 5u);
    EXPECT_EQ(s.map.markers[3].vertex, ids[3]);
}

TEST(MarkerSuggestion, NeedsFourMappedMarkers) {
    const TriMesh mesh = icosphere(1);
    const C3dTake take = takeOnVertices(mesh, {0, 1, 2, 3, 4}, 0.0, 0);
    Correspondence partial;
    for (int k = 0; k < 3; ++k) partial.markers.push_back({"M" + std::to_string(k), k, 0, "{}"});
    EXPECT_THROW(suggestMappings(mesh, take, partial), Error);
}

namespace {

// The first vertex of the icosphere whose x is past `x` on the given side (+1 or −1).
int vertexAt(const TriMesh& mesh, double x, double z) {
    int best = 0;
    for (int v = 0; v < mesh.vertexCount(); ++v)
        if ((mesh.V.row(v) - Eigen::RowVector3d(x, 0, z)).norm() <
            (mesh.V.row(best) - Eigen::RowVector3d(x, 0, z)).norm())
            best = v;
    return best;
}

const Proposal& proposalFor(const Suggestion& s, const std::string& label) {
    for (const Proposal& p : s.proposals)
        if (p.label == label) return p;
    throw std::runtime_error("no proposal for " + label);
}

}  // namespace

TEST(MarkerSuggestion, FlagsAMarkerNamedLeftThatLandsOnTheMeshsRight) {
    const TriMesh mesh = icosphere(2);
    // Two pairs of picks say that +x is the left; LKNE sits on the right, RKNE where it belongs.
    const std::vector<std::string> labels{"LSHO", "RSHO", "LHIP", "RHIP", "LKNE", "RKNE"};
    const std::vector<int> ids{vertexAt(mesh, 0.7, 0.7),  vertexAt(mesh, -0.7, 0.7),
                               vertexAt(mesh, 0.7, -0.7), vertexAt(mesh, -0.7, -0.7),
                               vertexAt(mesh, -1, 0),     vertexAt(mesh, -0.7, 0.3)};
    const C3dTake take = takeOnVertices(mesh, ids, 0.01, 4, labels);
    Correspondence partial;
    partial.meshVertices = mesh.vertexCount();
    for (int k = 0; k < 4; ++k) partial.markers.push_back({labels[k], ids[k], 10, "{}"});
    const Suggestion s = suggestMappings(mesh, take, partial);
    ASSERT_EQ(s.suggested, 2);
    const Proposal& wrong = proposalFor(s, "LKNE");
    EXPECT_EQ(wrong.vertex, ids[4]);
    EXPECT_TRUE(wrong.needsReview);
    EXPECT_NE(wrong.reviewReason.find("left"), std::string::npos) << wrong.reviewReason;
    EXPECT_FALSE(proposalFor(s, "RKNE").needsReview) << proposalFor(s, "RKNE").reviewReason;
    EXPECT_EQ(s.needsReview, 1);
    // The written map carries the flag and the reason with the entry.
    const auto entry = nlohmann::json::parse(s.map.find("LKNE")->extraJson);
    EXPECT_EQ(entry.value("needs_review", false), true);
    EXPECT_EQ(entry.value("review_reason", std::string()), wrong.reviewReason);
    const auto written = nlohmann::json::parse(s.map.toJson());
    for (const auto& m : written["markers"])
        EXPECT_EQ(m.value("needs_review", false), m["label"] == "LKNE") << m.dump();
}

TEST(MarkerSuggestion, AMarkerWhosePartnerIsPickedLandsAtItsMirrorImage) {
    const TriMesh mesh = icosphere(2);  // mirrored across x = 0, vertex onto vertex
    const std::vector<std::string> labels{"LSHO", "RSHO", "LHIP", "RHIP", "LKNE", "RKNE"};
    const int lkne = vertexAt(mesh, 0.7, 0.3);
    std::vector<int> ids{vertexAt(mesh, 0.7, 0.7), vertexAt(mesh, -0.7, 0.7),
                         vertexAt(mesh, 0.7, -0.7), vertexAt(mesh, -0.7, -0.7), lkne};
    std::vector<Vec3> points;
    for (int v : ids) points.push_back(1.01 * mesh.V.row(v).transpose());
    // RKNE stands between the mirror image of LKNE's vertex and a neighbour, a little nearer the
    // neighbour: the take alone would choose the neighbour.
    const Vec3 mirrorPoint(-mesh.V(lkne, 0), mesh.V(lkne, 1), mesh.V(lkne, 2));
    int mirror = -1;
    for (int v = 0; v < mesh.vertexCount(); ++v)
        if ((mesh.V.row(v).transpose() - mirrorPoint).norm() < 1e-9) mirror = v;
    ASSERT_GE(mirror, 0);
    int neighbour = -1;
    for (int f = 0; f < mesh.F.rows(); ++f)
        for (int k = 0; k < 3; ++k)
            if (mesh.F(f, k) == mirror) neighbour = mesh.F(f, (k + 1) % 3);
    ASSERT_GE(neighbour, 0);
    const Vec3 between =
        0.45 * mesh.V.row(mirror).transpose() + 0.55 * mesh.V.row(neighbour).transpose();
    points.push_back(1.01 * between.normalized());
    ASSERT_LT((points.back() - 1.01 * mesh.V.row(neighbour).transpose()).norm(),
              (points.back() - 1.01 * mesh.V.row(mirror).transpose()).norm());
    const C3dTake take = takeAt(points, labels);
    Correspondence partial;
    partial.meshVertices = mesh.vertexCount();
    for (int k = 0; k < 5; ++k) partial.markers.push_back({labels[k], ids[k], 10, "{}"});
    const Suggestion s = suggestMappings(mesh, take, partial);
    ASSERT_EQ(s.suggested, 1);
    EXPECT_EQ(proposalFor(s, "RKNE").vertex, mirror);
}

TEST(MarkerSuggestion, FlagsAMarkerFarOffTheSkin) {
    const TriMesh mesh = icosphere(2);
    const std::vector<int> ids{0, 7, 19, 33, 48, 77};
    // The last marker stands 150 mm off a 1 m sphere, like a marker on a stick or another actor's.
    C3dTake take = takeOnVertices(mesh, ids, 0.15, 5);
    Correspondence partial;
    partial.meshVertices = mesh.vertexCount();
    for (int k = 0; k < 4; ++k)
        partial.markers.push_back({"M" + std::to_string(k), ids[k], 0, "{}"});
    const Suggestion s = suggestMappings(mesh, take, partial);
    EXPECT_FALSE(proposalFor(s, "M4").needsReview) << proposalFor(s, "M4").reviewReason;
    const Proposal& far = proposalFor(s, "M5");
    EXPECT_EQ(far.vertex, ids[5]);
    EXPECT_TRUE(far.needsReview);
    EXPECT_NE(far.reviewReason.find("mm from the fitted mesh"), std::string::npos)
        << far.reviewReason;
}

// A marker that moves against every pick (skin over a joint, a loose strap) may be anywhere the
// picks do not hold; one that keeps its distance to them is held.
TEST(MarkerSuggestion, FlagsAMarkerThatNoPickMovesWith) {
    const TriMesh mesh = icosphere(2);
    const std::vector<int> ids{0, 7, 19, 33, 48, 77};
    std::vector<Vec3> rest;
    for (int v : ids) rest.push_back(1.01 * mesh.V.row(v).transpose());
    // M5 slides over the skin, 10 mm a frame (60 mm either way), the way that changes its
    // distance to every pick: along t, the tangent at M5 most across all of them.
    const Vec3 n = rest[5].normalized(), u = n.unitOrthogonal(), w = n.cross(u);
    Vec3 t = u;
    const auto least = [&](const Vec3& d) {
        double m = 1e9;
        for (int k = 0; k < 4; ++k) m = std::min(m, std::abs(rest[k].dot(d)));
        return m;
    };
    for (int a = 0; a < 180; ++a) {
        const Vec3 d = std::cos(a * M_PI / 180) * u + std::sin(a * M_PI / 180) * w;
        if (least(d) > least(t)) t = d;
    }
    std::vector<std::vector<Vec3>> frames(12, rest);
    for (int f = 0; f < 12; ++f)
        frames[f][5] = Eigen::AngleAxisd(0.01 * (f - 5.5), n.cross(t)) * rest[5];
    Correspondence partial;
    partial.meshVertices = mesh.vertexCount();
    for (int k = 0; k < 4; ++k)
        partial.markers.push_back({"M" + std::to_string(k), ids[k], 10, "{}"});
    const Suggestion s = suggestMappings(mesh, takeOver(frames), partial);
    EXPECT_FALSE(proposalFor(s, "M4").needsReview) << proposalFor(s, "M4").reviewReason;
    const Proposal& sliding = proposalFor(s, "M5");
    EXPECT_TRUE(sliding.needsReview);
    EXPECT_NE(sliding.reviewReason.find("no pick moves with it"), std::string::npos)
        << sliding.reviewReason;
}

// A prop's or another actor's markers are not the body's: proposed anyway, they pulled the mesh
// to them when solved (ezc3d's Vicon.c3d: the box's 8 markers 429 to 706 mm off the fitted body).
TEST(MarkerSuggestion, AMarkerFarFromTheBodyIsLeftUnmappedAndNamed) {
    const TriMesh mesh = icosphere(2);
    const std::vector<int> ids{0, 7, 19, 33, 48, 77};
    // The last marker stands 500 mm off a 1 m sphere, past kUnreachableMm (300).
    C3dTake take = takeOnVertices(mesh, ids, 0.5, 5);
    Correspondence partial;
    partial.meshVertices = mesh.vertexCount();
    for (int k = 0; k < 4; ++k)
        partial.markers.push_back({"M" + std::to_string(k), ids[k], 0, "{}"});
    const Suggestion s = suggestMappings(mesh, take, partial);
    EXPECT_EQ(s.suggested, 1);
    EXPECT_EQ(proposalFor(s, "M4").vertex, ids[4]);
    EXPECT_EQ(s.map.find("M5"), nullptr);
    EXPECT_EQ(s.offBody, std::vector<std::string>{"actor:M5"});
}

TEST(MarkerSuggestion, TheEntriesStillMarkedForReviewAreListedInMapOrder) {
    Correspondence map;
    map.markers.push_back({"LFHD", 1, 10, R"({"suggested": true, "needs_review": true})"});
    map.markers.push_back({"RFHD", 2, 10, R"({"suggested": true})"});
    map.markers.push_back({"T10", 3, 10, R"({"needs_review": true, "review_reason": "far"})"});
    map.markers.push_back({"C7", 4, 10, R"({"needs_review": false})"});
    map.markers.push_back({"STRN", 5, 10, ""});
    map.markers.push_back({"CLAV", 6, 10, R"({"needs_review": "yes"})"});
    EXPECT_EQ(labelsToReview(map), (std::vector<std::string>{"LFHD", "T10"}));
}

TEST(MarkerSuggestion, TheDemoWalkersSuggestionsLandOnTheirOwnVertices) {
    const DemoWalker walker = makeDemoWalker();
    const DemoTake demo = makeDemoWalkerTake(walker);
    // Six picks an animator clicks first: head, pelvis, both wrists, both ankles.
    Correspondence partial = demo.map;
    partial.markers.clear();
    for (const char* label : {"LFHD", "LASI", "LWRA", "RWRA", "LANK", "RANK"})
        partial.markers.push_back(*demo.map.find(label));
    const Suggestion s = suggestMappings(walker.rest, demo.take, partial);
    const SuggestionCheck c = checkSuggestion(walker.rest, demo.take, s, demo.map, 30.0);
    EXPECT_EQ(c.compared, 33);
    EXPECT_EQ(c.within, 33);
    int exact = 0;
    for (const auto& [label, mm] : c.distancesMm) exact += mm == 0.0;
    EXPECT_GE(exact, 32);
    EXPECT_EQ(s.needsReview, 0);
}

// A marker hidden in every fit kept (a gap over the frames that fit best) but seen elsewhere in
// the take got no entry, no review mark and no mention. It is placed from a fit that shows it,
// and marked for review.
TEST(MarkerSuggestion, AMarkerHiddenInTheBestFitsIsPlacedFromAFitThatShowsIt) {
    const DemoWalker walker = makeDemoWalker();
    DemoTake demo = makeDemoWalkerTake(walker);
    Correspondence partial = demo.map;
    partial.markers.clear();
    for (const char* label : {"LFHD", "LASI", "LWRA", "RWRA", "LANK", "RANK"})
        partial.markers.push_back(*demo.map.find(label));
    const std::vector<std::size_t> relb = demo.take.pointsNamed("RELB");
    ASSERT_EQ(relb.size(), 1u);
    const std::size_t frames = demo.take.frameCount();
    for (std::size_t f = 0; f < 2 * frames / 3; ++f) demo.take.samples.setMissing(f, relb[0]);
    const Suggestion s = suggestMappings(walker.rest, demo.take, partial);
    const MarkerMapping* entry = nullptr;
    for (const MarkerMapping& m : s.map.markers)
        if (m.label == "RELB" || m.label == "walker:RELB") entry = &m;
    ASSERT_NE(entry, nullptr) << "RELB was left out";
    // From one fit, near its place (those of the kept fits land on their own vertices).
    const SuggestionCheck c = checkSuggestion(walker.rest, demo.take, s, demo.map, 30.0);
    double mm = -1;
    for (const auto& [label, d] : c.distancesMm)
        if (label == entry->label) mm = d;
    EXPECT_GE(mm, 0.0);
    EXPECT_LE(mm, 30.0);
    bool reviewed = false;
    for (const Proposal& p : s.proposals)
        if (p.label == entry->label) reviewed = p.needsReview;
    EXPECT_TRUE(reviewed);
}

TEST(MarkerSuggestion, OnATakeTwoSubjectsWearItWritesTheSubjectWhereTheBareNameIsAmbiguous) {
    const DemoWalker walker = makeDemoWalker();
    const DemoTake demo = makeDemoWalkerTake(walker);
    // Subject A walks where the demo does; B, wearing the same marker names, three metres aside.
    C3dTake take = demo.take;
    const std::size_t n = demo.take.points.size();
    take.points.clear();
    take.samples = C3dSamples(demo.take.frameCount(), 2 * n);
    for (std::size_t s = 0; s < 2; ++s)
        for (std::size_t k = 0; k < n; ++k) {
            C3dPoint p = demo.take.points[k];
            p.label = (s ? "B:" : "A:") + demo.take.shortLabel(k);
            splitC3dLabel(p.label, p.subject, p.name);
            take.points.push_back(p);
            for (std::size_t f = 0; f < take.frameCount(); ++f)
                if (const auto x = demo.take.samples.position(f, k))
                    take.samples.set(f, s * n + k, x->x() + 3000.0 * s / take.unitToMm, x->y(),
                                     x->z());
        }
    Correspondence reference = demo.map, partial = demo.map;
    for (auto& m : reference.markers) m.label = "A:" + m.label;
    partial.markers.clear();
    for (const char* label : {"A:LFHD", "A:LASI", "A:LWRA", "A:RWRA", "A:LANK", "A:RANK"})
        partial.markers.push_back(*reference.find(label));
    const Suggestion s = suggestMappings(walker.rest, take, partial);
    for (const MarkerMapping& m : s.map.markers) EXPECT_EQ(m.label.substr(0, 2), "A:");
    EXPECT_EQ(s.otherSubjects.size(), n);  // all of B's
    EXPECT_EQ(s.otherSubjects.front(), "B:" + demo.take.shortLabel(0));
    EXPECT_EQ(s.map.resolve(take).size(), s.map.markers.size());
    const SuggestionCheck c = checkSuggestion(walker.rest, take, s, reference, 30.0);
    EXPECT_EQ(c.compared, 33);
    EXPECT_EQ(c.within, 33);
}

// Two points with one label (a take relabelled by hand): an entry for it could not say which, and
// solve refuses it; Suggest gave both an entry, and the map it wrote could not be solved.
TEST(MarkerSuggestion, ALabelTwoPointsOfTheTakeShareIsLeftUnmappedAndNamed) {
    const DemoWalker walker = makeDemoWalker();
    const DemoTake demo = makeDemoWalkerTake(walker);
    C3dTake take = demo.take;
    const std::size_t clav = *take.findPoint("CLAV"), strn = *take.findPoint("STRN");
    take.points[strn].label = take.points[clav].label;
    take.points[strn].name = take.points[clav].name;
    Correspondence partial = demo.map;
    partial.markers.clear();
    for (const char* label : {"LFHD", "LASI", "LWRA", "RWRA", "LANK", "RANK"})
        partial.markers.push_back(*demo.map.find(label));
    const Suggestion s = suggestMappings(walker.rest, take, partial);
    EXPECT_EQ(s.sharedLabels, std::vector<std::string>{take.points[clav].label});
    for (const MarkerMapping& m : s.map.markers)
        EXPECT_FALSE(take.pointsNamed(m.label).size() > 1) << m.label;
    EXPECT_EQ(s.map.markers.size(), demo.map.markers.size() - 2);  // CLAV and STRN, both gone
    EXPECT_NO_THROW(s.map.resolve(take));
}

namespace {

struct CmuBody {
    TriMesh rest;  // MakeHuman's group body
    C3dTake take;  // CMU 85_02
};

// The shared data's CMU take and the MakeHuman body, or nothing when the data is absent.
std::optional<CmuBody> cmuBody() {
    namespace fs = std::filesystem;
    const fs::path data = BONELESS_SHARED_DATA;
    const fs::path mesh = data / "meshes" / "makehuman" / "makehuman_base.obj";
    const fs::path take = data / "c3d" / "cmu" / "85_02.c3d";
    if (!fs::exists(mesh) || !fs::exists(take)) return std::nullopt;
    MeshReadOptions options;
    options.group = "body";
    return CmuBody{readMesh(mesh.string(), options).mesh, readC3d(take.string())};
}

}  // namespace

// The issue's target (80 % within 30 mm from 6 picks) is not reached yet; this holds the ground
// gained (docs/markers.md): the rigid alignment alone put 3 of these 35 within 30 mm, and since
// the reference's toes were corrected 23 land.
TEST(MarkerSuggestion, LandsNearTheReferenceMapOnTheCmuTakeFromSixPicks) {
    const std::optional<CmuBody> cmu = cmuBody();
    if (!cmu) GTEST_SKIP() << "no " << BONELESS_SHARED_DATA;
    const TriMesh& rest = cmu->rest;
    const C3dTake& take = cmu->take;
    const Correspondence reference =
        Correspondence::read((std::filesystem::path(BONELESS_SOURCE_DIR) / "tests" / "data" /
                              "cmu-85_02-makehuman-body.map.json")
                                 .string());
    Correspondence partial = reference;
    partial.markers.clear();
    for (const char* label : {"LFHD", "LFWT", "LWRA", "RWRA", "LANK", "RANK"})
        partial.markers.push_back(*reference.find(label));
    const Suggestion s = suggestMappings(rest, take, partial);
    const SuggestionCheck c = checkSuggestion(rest, take, s, reference, 30.0);
    EXPECT_EQ(c.compared, 35);
    EXPECT_GE(c.within, 22) << "median " << c.medianMm << " mm";
    // RFWT lands where LFWT's vertex mirrors to, as the reference puts it (the fit alone: 37 mm).
    ASSERT_NE(s.map.find("RFWT"), nullptr);
    EXPECT_EQ(s.map.find("RFWT")->vertex, reference.find("RFWT")->vertex);
    // The entries left unflagged can be trusted, and most misses are flagged: a 45 mm bound on
    // the best fit's distance flagged 4 of these 12 misses, and left 8 among 19 unflagged.
    int misses = 0, flaggedMisses = 0, unflagged = 0, unflaggedWithin = 0;
    for (const auto& [label, mm] : c.distancesMm) {
        const bool flagged = suggestionMark(*s.map.find(label)).needsReview;
        misses += mm > 30.0;
        flaggedMisses += mm > 30.0 && flagged;
        unflagged += !flagged;
        unflaggedWithin += !flagged && mm <= 30.0;
    }
    EXPECT_GE(flaggedMisses, misses * 8 / 10) << flaggedMisses << " of " << misses;
    EXPECT_GE(unflaggedWithin, unflagged * 8 / 10) << unflaggedWithin << " of " << unflagged;
    EXPECT_GE(unflagged, 8);  // flagging everything would pass the two lines above
}

// The bound was tested on the RMS distance over the kept fits, and the review reason gave the
// distance on the best fit: from these four picks LWRB and RFIN were written "309 mm" and "336 mm
// from the fitted mesh", where the documentation promises no entry 300 mm off the body.
TEST(MarkerSuggestion, NoEntryLandsFartherThanTheBoundFromTheBestFitOnTheCmuTake) {
    const std::optional<CmuBody> cmu = cmuBody();
    if (!cmu) GTEST_SKIP() << "no " << BONELESS_SHARED_DATA;
    const TriMesh& rest = cmu->rest;
    const C3dTake& take = cmu->take;
    Correspondence partial;
    partial.meshVertices = rest.vertexCount();
    for (const auto& [label, vertex] :
         {std::pair{"LFWT", 10802}, {"RFWT", 4363}, {"LKNE", 11156}, {"RKNE", 4548}})
        partial.markers.push_back({label, vertex, 10, "{}"});
    const Suggestion s = suggestMappings(rest, take, partial);
    for (const Proposal& p : s.proposals) {
        const size_t at = p.reviewReason.find(" mm from the fitted mesh");
        if (at != std::string::npos)
            EXPECT_LE(std::stod(p.reviewReason.substr(0, at)), kUnreachableMm) << p.label;
    }
    EXPECT_FALSE(s.offBody.empty());
    for (const std::string& label : s.offBody)
        for (const Proposal& p : s.proposals)
            EXPECT_NE(take.findPoint(p.label), take.findPoint(label)) << label;
    EXPECT_EQ(s.suggested + s.offBody.size(), 37u);  // 41 markers, 4 picked
}

// Of an even count the median is the mean of the two middle distances: 1, 2, 4 and 9 mm gave 4.
TEST(MarkerSuggestion, TheChecksMedianOfAnEvenCountIsMidwayBetweenItsMiddleTwo) {
    TriMesh rest;
    rest.V = Positions::Zero(5, 3);
    for (int v = 1; v < 5; ++v) rest.V(v, 0) = std::vector<double>{1, 2, 4, 9}[v - 1];
    Suggestion s;
    s.calibration.takeToMesh.scale = 1.0;
    Correspondence reference;
    C3dTake take;  // labels name its points, as solve resolves them
    for (const char* label : {"A", "B", "C", "D"}) {
        C3dPoint point;
        point.label = label;
        splitC3dLabel(point.label, point.subject, point.name);
        take.points.push_back(point);
        const int v = static_cast<int>(s.proposals.size()) + 1;
        s.proposals.push_back({label, v});
        s.map.markers.push_back({label, v, 0.0, "{}"});
        reference.markers.push_back({label, 0, 0.0, "{}"});
    }
    const SuggestionCheck c = checkSuggestion(rest, take, s, reference, 3.0);
    EXPECT_EQ(c.compared, 4);
    EXPECT_EQ(c.within, 2);
    EXPECT_DOUBLE_EQ(c.medianMm, 3.0);
}
