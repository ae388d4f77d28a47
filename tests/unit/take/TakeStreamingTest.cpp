// A take streamed from its file (C3dFrameReader, MarkerTrack) solves as the take read whole.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "TrajectoryFilter.h"
#include "boneless/C3dFrameReader.h"
#include "boneless/C3dReader.h"
#include "boneless/C3dWriter.h"
#include "boneless/Correspondence.h"
#include "boneless/DemoFiles.h"
#include "boneless/MeshReader.h"
#include "boneless/TakeExport.h"
#include "boneless/TakeSolver.h"

using namespace boneless;

namespace {

struct GappyTake {
    TriMesh mesh;
    Correspondence map;
    std::string c3d;
};

// The demo creature over 600 frames (the solver reads 256 frames past the one asked for), with
// gaps of its own and more: short ones across the window's edges, one too long to fill, one at
// the take's end.
GappyTake gappyTake(const std::string& name) {
    const DemoFiles files = writeDemoFiles(freshTestDir(name), 600, 10.0, false, 1);
    C3dTake take = readC3d(files.take);
    auto cut = [&](std::size_t point, std::size_t from, std::size_t to) {
        for (std::size_t f = from; f < to; ++f) take.samples.setMissing(f, point);
    };
    cut(0, 250, 262);
    cut(1, 255, 258);
    cut(2, 270, 330);
    cut(3, 590, 600);
    cut(4, 0, 3);
    const std::string c3d = std::filesystem::path(files.folder) / "gappy.c3d";
    writeC3d(take, c3d);
    return {readMesh(files.mesh).mesh, Correspondence::read(files.map), c3d};
}

bool sameRows(const Positions& a, const Positions& b) {
    // NaN rows (markers missing) must be NaN in both.
    return a.rows() == b.rows() &&
           ((a.array() == b.array()) || (a.array().isNaN() && b.array().isNaN())).all();
}

TakeSolveOptions filteredAndFilled() {
    TakeSolveOptions options;
    options.lowPassHz = 4.0;
    options.fillGapSeconds = 0.4;
    return options;
}

}  // namespace

// Every frame's targets, filtered and with short gaps filled, and the frames solved, bit for
// bit: how the take was read changes no answer.
TEST(TakeStreaming, AStreamedTakeSolvesEveryFrameAsTheTakeReadWhole) {
    const GappyTake t = gappyTake("stream-solve");
    const TakeSolveOptions options = filteredAndFilled();
    TakeSolver whole(t.mesh, readC3d(t.c3d), t.map, options);
    const C3dFrameReader reader(t.c3d);
    TakeSolver streamed(t.mesh, reader, t.map, options);
    ASSERT_EQ(streamed.frameCount(), whole.frameCount());
    EXPECT_EQ(streamed.calibration().frame, whole.calibration().frame);
    EXPECT_TRUE(streamed.rest().V == whole.rest().V);
    // The reference: the whole take filtered, its gaps filled from all of its samples.
    // In double, as the solver filters (a take read whole holds floats).
    C3dTake reference = readC3d(t.c3d);
    C3dSamples wide(reference.frameCount(), reference.points.size(), C3dSamples::Precision::Double);
    for (std::size_t f = 0; f < reference.frameCount(); ++f)
        for (std::size_t k = 0; k < reference.points.size(); ++k)
            if (const auto x = reference.samples.position(f, k))
                wide.set(f, k, x->x(), x->y(), x->z());
    reference.samples = wide;
    lowPassFilter(reference.samples, reference.rate, options.lowPassHz);
    const std::vector<std::size_t> points = t.map.resolve(reference);
    const int maxFrames = static_cast<int>(std::floor(options.fillGapSeconds * reference.rate));
    int filled = 0;
    for (int f = 0; f < whole.frameCount(); ++f) {
        for (bool fill : {false, true}) {
            Positions expected = takeFrame(reference, points, f);
            for (int k = 0; k < expected.rows(); ++k) {
                const auto x = gapFilled(reference.samples, f, points[k], maxFrames);
                if (fill && x) expected.row(k) = x->transpose();
                if (expected.row(k).allFinite())
                    expected.row(k) = whole.calibration()
                                          .takeToMesh.apply(expected.row(k).transpose())
                                          .transpose();
                filled += fill && x;
            }
            ASSERT_TRUE(sameRows(whole.targets(f, fill), expected))
                << "frame " << f << (fill ? ", filled" : "");
            ASSERT_TRUE(sameRows(streamed.targets(f, fill), expected))
                << "frame " << f << (fill ? ", filled" : "");
        }
    }
    EXPECT_GT(filled, 20);  // the gaps were filled, across the window's edges too
    // In the order an export solves them, then scrubbing back: windows move both ways.
    for (int f : {0, 1, 255, 256, 257, 300, 599, 260, 2}) {
        FrameReport a, b;
        EXPECT_TRUE(streamed.solve(f, a) == whole.solve(f, b)) << "frame " << f;
        EXPECT_EQ(a.visibleMarkers, b.visibleMarkers);
    }
}

// A frame's marker residual is measured against the markers as recorded, not as low-passed: a
// strong filter moves the targets off the markers, and the residual must say so (it said 0.66
// mm where the mesh lay 177 mm from the recorded markers). Streamed or read whole alike.
TEST(TakeStreaming, AFilteredFramesResidualIsMeasuredAgainstTheRecordedMarkers) {
    const GappyTake t = gappyTake("stream-residual");
    TakeSolveOptions options = filteredAndFilled();
    options.lowPassHz = 0.5;
    const C3dTake recorded = readC3d(t.c3d);
    const std::vector<std::size_t> points = t.map.resolve(recorded);
    const C3dFrameReader reader(t.c3d);
    TakeSolver whole(t.mesh, recorded, t.map, options), streamed(t.mesh, reader, t.map, options);
    for (TakeSolver* solver : {&whole, &streamed}) {
        const Similarity& s = solver->calibration().takeToMesh;
        const double unitsPerMm = s.scale / recorded.unitToMm;
        for (int f : {40, 256, 300}) {
            FrameReport report;
            const Positions predicted = solver->predictedMarkers(solver->solve(f, report));
            const Positions seen = takeFrame(recorded, points, f);
            double sum = 0;
            int count = 0;
            for (int k = 0; k < seen.rows(); ++k)
                if (seen.row(k).allFinite()) {
                    sum += (predicted.row(k).transpose() - s.apply(seen.row(k).transpose()))
                               .squaredNorm();
                    ++count;
                }
            ASSERT_EQ(report.visibleMarkers, count) << "frame " << f;
            const double expected = std::sqrt(sum / count) / unitsPerMm;
            EXPECT_GT(expected, 5.0) << "frame " << f;  // the filter did move the targets
            EXPECT_NEAR(report.residualRmsMm, expected, 1e-9 * expected) << "frame " << f;
        }
    }
}

// The files `solve` writes from the streamed take are the ones the take read whole gives: the
// point cache byte for byte, the sidecar but for the timings.
TEST(TakeStreaming, AStreamedTakeExportsTheFilesOfTheTakeReadWhole) {
    const GappyTake t = gappyTake("stream-export");
    auto exportTo = [&](const std::string& dir, auto&& take) {
        ExportRequest request;
        request.meshPath = "creature.obj";
        request.c3dPath = t.c3d;
        request.outDir = freshTestDir(dir);
        request.format = ExportFormat::Pc2;
        request.first = 240;
        request.end = 280;
        request.options = filteredAndFilled();
        const ExportResult r = exportTake(t.mesh, take, t.map, request);
        EXPECT_EQ(r.framesWritten, 40);
        std::ifstream cache(std::filesystem::path(request.outDir) / "creature.pc2",
                            std::ios::binary);
        std::ostringstream bytes;
        bytes << cache.rdbuf();
        nlohmann::json sidecar = nlohmann::json::parse(std::ifstream(r.sidecarPath));
        for (auto& f : sidecar["per_frame"]) f.erase("ms");
        for (const char* key : {"ms_per_frame_mean", "ms_per_frame_worst", "ms_per_frame_median"})
            sidecar["summary"].erase(key);
        return std::make_pair(bytes.str(), sidecar);
    };
    const auto whole = exportTo("stream-export-whole", readC3d(t.c3d));
    const C3dFrameReader reader(t.c3d);
    const auto streamed = exportTo("stream-export-streamed", reader);
    EXPECT_GT(whole.first.size(), 40u * 1000u);
    EXPECT_TRUE(streamed.first == whole.first);
    EXPECT_EQ(streamed.second, whole.second);
    EXPECT_EQ(whole.second["per_frame"].size(), 40u);
    EXPECT_EQ(whole.second["per_frame"][39]["frame"], 279);
}
