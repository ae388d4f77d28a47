// Markers on surface points (docs/markers.md): version 2 correspondence files, markers on thin
// parts, dents, and the solver's invariants with face points.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "MarkerPatch.h"  // core/solver/src
#include "TestFiles.h"
#include "TestMeshes.h"
#include "TestWorkDir.h"
#include "boneless/C3dReader.h"
#include "boneless/Correspondence.h"
#include "boneless/DemoFiles.h"
#include "boneless/DentGauge.h"
#include "boneless/Error.h"
#include "boneless/MeshReader.h"
#include "boneless/Metrics.h"
#include "boneless/TakeSolver.h"

using namespace boneless;
using namespace boneless::testing;

namespace {

// A closed finger: the unit sphere stretched to 12 long along z (radius 1, so that 1.25 is a
// 10 mm offset on an 8 mm finger).
TriMesh finger() {
    TriMesh m = icosphere(3);
    m.V.col(2) *= 6.0;
    return m;
}

// The face whose centroid is nearest x, as a surface point a third of the way to each corner.
SurfacePoint facePointNear(const TriMesh& m, const Vec3& x) {
    int best = 0;
    double bestDistance = 1e300;
    for (int f = 0; f < m.faceCount(); ++f) {
        const Vec3 c = (m.V.row(m.F(f, 0)) + m.V.row(m.F(f, 1)) + m.V.row(m.F(f, 2))) / 3.0;
        if ((c - x).norm() < bestDistance) bestDistance = (c - x).norm(), best = f;
    }
    SurfacePoint p;
    p.face = best;
    p.vertex = m.F(best, 0);
    p.barycentric = Vec3(0.5, 0.3, 0.2);
    return p;
}

// Markers around the base, the middle and the tip of the finger, the tip's on its very end.
std::vector<SurfacePoint> fingerMarkers(const TriMesh& m) {
    std::vector<SurfacePoint> points;
    for (double z : {-5.0, -1.0, 3.0})
        for (int s = 0; s < 3; ++s) {
            const double a = 2 * M_PI * s / 3 + z;
            points.push_back(facePointNear(m, Vec3(std::cos(a), std::sin(a), z)));
        }
    points.push_back(facePointNear(m, Vec3(0, 0, 6)));
    return points;
}

// Where each marker is seen on the pose `truth`: its point there, `offset` along its face's
// normal.
Positions seenMarkers(const TriMesh& m, const Positions& truth,
                      const std::vector<SurfacePoint>& points, double offset) {
    Positions T(points.size(), 3);
    for (size_t k = 0; k < points.size(); ++k) {
        const auto f = m.F.row(points[k].face);
        const Vec3 a = truth.row(f[0]), b = truth.row(f[1]), c = truth.row(f[2]);
        const Vec3 n = (b - a).cross(c - a).normalized();
        T.row(k) = (surfacePosition(m, truth, points[k]) + offset * n).transpose();
    }
    return T;
}

Reconstruction softSolver(const TriMesh& m, const std::vector<SurfacePoint>& points,
                          double offset) {
    SolverOptions o;
    o.constraints = SolverOptions::Constraints::Soft;
    o.markerOffsets.assign(points.size(), offset);
    Reconstruction r;
    r.prepare(m, points, o);
    return r;
}

}  // namespace

TEST(Correspondence, AVersion2EntryNamesAPointOfAFaceAndIsWrittenBackAsVersion2) {
    const std::string path = writeTestFile("v2.json", R"({"format": "boneless-correspondence",
      "version": 2, "mesh": {"file": "finger.obj", "vertices": 642},
      "markers": [{"label": "TIP", "vertex": 7, "face": 30, "barycentric": [0.5, 0.3, 0.2],
                   "offset_mm": 10, "note": "kept"},
                  {"label": "BASE", "vertex": 3}]})");
    const Correspondence c = Correspondence::read(path);
    ASSERT_EQ(c.markers.size(), 2u);
    EXPECT_EQ(c.markers[0].face, 30);
    EXPECT_DOUBLE_EQ(c.markers[0].barycentric[1], 0.3);
    EXPECT_EQ(c.markers[1].face, -1);
    const auto j = nlohmann::json::parse(c.toJson());
    EXPECT_EQ(j["version"], 2);
    EXPECT_EQ(j["markers"][0]["face"], 30);
    EXPECT_EQ(j["markers"][0]["note"], "kept");
    EXPECT_FALSE(j["markers"][1].contains("face"));
    EXPECT_EQ(Correspondence::fromJson(c.toJson(), "again").toJson(), c.toJson());
}

// Older readers keep reading what this one rewrites, as long as no marker names a face point;
// and a version 1 file's own "face" key is a key of its own, not a point.
TEST(Correspondence, AMapWithoutFacePointsIsStillWrittenAsVersion1) {
    const std::string path = writeTestFile("v1.json", R"({"format": "boneless-correspondence",
      "version": 1, "markers": [{"label": "A", "vertex": 3, "face": "left"}]})");
    const Correspondence c = Correspondence::read(path);
    EXPECT_EQ(c.markers[0].face, -1);
    const auto j = nlohmann::json::parse(c.toJson());
    EXPECT_EQ(j["version"], 1);
    EXPECT_EQ(j["markers"][0]["face"], "left");
}

TEST(Correspondence, ABadFacePointIsAnErrorNamingTheFileAndTheEntry) {
    auto v2 = [](const std::string& entry) {
        return std::string(R"({"format": "boneless-correspondence", "version": 2,
          "markers": [{"label": "OK", "vertex": 1}, )") +
               entry + "]}";
    };
    const std::string negative =
        writeTestFile("neg.json", v2(R"({"label": "TIP", "vertex": 0, "face": 2,
                                    "barycentric": [1.2, -0.2, 0]})"));
    std::string e = errorOf([&] { Correspondence::read(negative); });
    EXPECT_NE(e.find("neg.json"), std::string::npos) << e;
    EXPECT_NE(e.find("marker TIP: "), std::string::npos) << e;
    EXPECT_NE(e.find("barycentric"), std::string::npos) << e;

    const TriMesh mesh = finger();
    const std::string farFace =
        writeTestFile("far.json", v2(R"({"label": "TIP", "vertex": 0, "face": 100000,
                                    "barycentric": [1, 0, 0]})"));
    const Correspondence far = Correspondence::read(farFace);
    e = errorOf([&] { far.checkMesh(mesh.vertexCount(), "finger.obj", &mesh); });
    EXPECT_NE(e.find("far.json"), std::string::npos) << e;
    EXPECT_NE(e.find("TIP: face 100000 is out of range"), std::string::npos) << e;

    const int notCorner = mesh.F(5, 0) == 0 || mesh.F(5, 1) == 0 || mesh.F(5, 2) == 0 ? 6 : 5;
    const std::string wrong = writeTestFile(
        "corner.json", v2(R"({"label": "TIP", "vertex": 0, "face": )" + std::to_string(notCorner) +
                          R"(, "barycentric": [1, 0, 0]})"));
    const Correspondence c = Correspondence::read(wrong);
    e = errorOf([&] { c.checkMesh(mesh.vertexCount(), "finger.obj", &mesh); });
    EXPECT_NE(e.find("corner.json"), std::string::npos) << e;
    EXPECT_NE(e.find("TIP: vertex 0 is not a corner of face"), std::string::npos) << e;
}

// A version 1 marker sits on its vertex, as it did: the same map written as version 2 points
// that put all their weight on those vertices solves every frame to the same answer, bit for bit,
// and the markers' rest places are their vertices plus the offset along the ring normal.
TEST(MarkerPatches, Version1MapsSolveAsTheirVertexMarkersDid) {
    const DemoFiles files = writeDemoFiles(freshTestDir("marker-patch-v1"), 12, 10.0, false, 1);
    const TriMesh mesh = readMesh(files.mesh).mesh;
    const C3dTake take = readC3d(files.take);
    const Correspondence v1 = Correspondence::read(files.map);
    Correspondence v2 = v1;
    for (auto& m : v2.markers) {
        for (int f = 0; f < mesh.faceCount() && m.face < 0; ++f)
            for (int c = 0; c < 3; ++c)
                if (mesh.F(f, c) == m.vertex) {
                    m.face = f;
                    m.barycentric = {0, 0, 0};
                    m.barycentric[c] = 1.0;
                }
    }
    ASSERT_EQ(nlohmann::json::parse(v2.toJson())["version"], 2);
    TakeSolver a(mesh, take, v1), b(mesh, take, Correspondence::fromJson(v2.toJson(), "v2"));
    for (int f : {0, 6, 11}) {
        FrameReport ra, rb;
        EXPECT_EQ(maxDistance(a.solve(f, ra), b.solve(f, rb)), 0.0) << "frame " << f;
        EXPECT_EQ(ra.residualRmsMm, rb.residualRmsMm);
    }
    const Positions atRest = a.predictedMarkers(mesh.V);
    const MeshTopology topology(mesh);
    const ShapeEncoding encoding(mesh, topology);
    const double unitsPerMm = a.calibration().takeToMesh.scale / take.unitToMm;
    for (size_t k = 0; k < v1.markers.size(); ++k) {
        const int v = v1.markers[k].vertex;
        const Vec3 expected = mesh.V.row(v).transpose() +
                              v1.markers[k].offsetMm * unitsPerMm * encoding.ringNormal(v, mesh.V);
        EXPECT_LT((atRest.row(k).transpose() - expected).norm(), 1e-12) << v1.markers[k].label;
    }
}

// A marker 10 mm off the end of a finger, the finger bent and twisted: the offset goes along
// the rest normal turned with the marker's face, which does not turn over the way the tip's
// ring normal can, and nothing folds.
TEST(MarkerPatches, AMarkerOnAFingerTenMillimetresOffTheSkinFoldsNothing) {
    const TriMesh mesh = finger();
    const std::vector<SurfacePoint> points = fingerMarkers(mesh);
    Reconstruction solver = softSolver(mesh, points, 1.25);
    for (double amount : {0.05, 0.1, 0.2}) {
        const Positions truth = bent(mesh.V, amount);
        const SolveResult r = solver.solve(seenMarkers(mesh, truth, points, 1.25));
        EXPECT_EQ(r.report.foldedFaces, 0) << amount;
        EXPECT_EQ(foldedFaceCount(mesh.F, r.V, mesh.V), 0) << amount;
    }
}

// The markers pull face points: around each, the surface stays within twice its rest curvature
// (DentGauge), and within a tenth of what the true bend gives, with the markers 10 mm off.
TEST(MarkerPatches, FacePointMarkersDoNotDent) {
    const TriMesh mesh = finger();
    const std::vector<SurfacePoint> points = fingerMarkers(mesh);
    Reconstruction solver = softSolver(mesh, points, 1.25);
    const MeshTopology topology(mesh);
    const ShapeEncoding encoding(mesh, topology);
    const DentGauge gauge(mesh, topology, encoding, points, 1.0);
    for (double amount : {0.05, 0.1, 0.15}) {
        const SolveResult r = solver.solve(seenMarkers(mesh, bent(mesh.V, amount), points, 1.25));
        // The bend itself curves the finger (1.2 to 1.8 times); the markers add nothing to it.
        const double ratio = gauge.worstRatio(r.V);
        EXPECT_LE(ratio, 2.0) << amount;
        EXPECT_LE(ratio, 1.1 * gauge.worstRatio(bent(mesh.V, amount))) << amount;
    }
    EXPECT_DOUBLE_EQ(gauge.worstRatio(mesh.V), 1.0);
}

// The solver's invariants hold with face points: the rest places give the rest mesh, a rigid
// motion of them the rest mesh moved rigidly, and a frame's answer does not depend on the frame
// solved before it.
TEST(MarkerPatches, FacePointMarkersKeepTheSolversInvariants) {
    const TriMesh mesh = finger();
    const std::vector<SurfacePoint> points = fingerMarkers(mesh);
    Reconstruction solver = softSolver(mesh, points, 1.25);
    const double tolerance = 1e-6 * boundingBoxDiagonal(mesh.V);
    const Positions atRest = solver.markerPositions(mesh.V);
    EXPECT_LE(maxDistance(solver.solve(atRest).V, mesh.V), tolerance);

    std::mt19937 rng(28);
    const Eigen::Matrix3d R = randomRotation(rng);
    const Vec3 t(1, -2, 0.5);
    const Positions expected = moved(mesh.V, R, t);
    EXPECT_LE(maxDistance(solver.solve(moved(atRest, R, t)).V, expected), tolerance);

    const Positions bentTargets = seenMarkers(mesh, bent(mesh.V, 0.1), points, 1.25);
    const Positions first = solver.solve(bentTargets).V;
    solver.solve(seenMarkers(mesh, bent(mesh.V, -0.2), points, 1.25));
    EXPECT_EQ(maxDistance(solver.solve(bentTargets).V, first), 0.0);
}

// A marker missing from a frame is taken out of the one factor by a low-rank correction: the
// same answer as a solver prepared without it.
TEST(MarkerPatches, AMissingFacePointMarkerIsTheSolverWithoutIt) {
    const TriMesh mesh = finger();
    std::vector<SurfacePoint> points = fingerMarkers(mesh);
    Reconstruction all = softSolver(mesh, points, 1.25);
    Positions targets = seenMarkers(mesh, bent(mesh.V, 0.1), points, 1.25);
    targets.row(4).setConstant(std::numeric_limits<double>::quiet_NaN());
    const Positions withGap = all.solve(targets).V;
    std::vector<SurfacePoint> fewer = points;
    fewer.erase(fewer.begin() + 4);
    Positions fewerTargets(targets.rows() - 1, 3);
    for (int k = 0, j = 0; k < targets.rows(); ++k)
        if (k != 4) fewerTargets.row(j++) = targets.row(k);
    Reconstruction without = softSolver(mesh, fewer, 1.25);
    EXPECT_LE(maxDistance(without.solve(fewerTargets).V, withGap),
              1e-8 * boundingBoxDiagonal(mesh.V));
}

TEST(MarkerPatches, AHitOnAPosedFaceNamesTheSamePointOfTheRestSurface) {
    const TriMesh m = finger();
    // A pose that no similarity gives: each corner moved on its own.
    Positions posed = m.V;
    for (int v = 0; v < posed.rows(); ++v)
        posed.row(v) += Eigen::RowVector3d(0.3 * std::sin(v), 0.2 * std::cos(3 * v), 0.1 * (v % 7));
    const int face = 17;
    const Vec3 w(0.2, 0.7, 0.1);
    Vec3 hit = Vec3::Zero();
    for (int k = 0; k < 3; ++k) hit += w[k] * posed.row(m.F(face, k)).transpose();
    const SurfacePoint p = surfacePointAt(m.F, posed, face, hit);
    EXPECT_EQ(p.face, face);
    EXPECT_NEAR((p.barycentric - w).norm(), 0.0, 1e-9);
    EXPECT_EQ(p.vertex, m.F(face, 1));  // the corner nearest the hit
    EXPECT_NEAR((surfacePosition(m, posed, p) - hit).norm(), 0.0, 1e-9);
    // Off the triangle, beside its first corner: that corner alone.
    const Vec3 a = posed.row(m.F(face, 0)).transpose(), b = posed.row(m.F(face, 1)).transpose();
    const SurfacePoint beside = surfacePointAt(m.F, posed, face, a + 0.5 * (a - b));
    EXPECT_NEAR((beside.barycentric - Vec3(1, 0, 0)).norm(), 0.0, 1e-9);
    EXPECT_EQ(beside.vertex, m.F(face, 0));
}
