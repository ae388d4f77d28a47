// A mesh its exporter split at UV seams animates as the welded mesh does: the copies of a vertex
// stay together in every frame and every output (they tore up to 14 cm apart on a MakeHuman body).
#include <gtest/gtest.h>

#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "boneless/C3dReader.h"
#include "boneless/Correspondence.h"
#include "boneless/DemoFiles.h"
#include "boneless/MeshReader.h"
#include "boneless/OutputFolder.h"
#include "boneless/TakeExport.h"
#include "boneless/TakeSolver.h"

using namespace boneless;
namespace fs = std::filesystem;

namespace {

struct Split {
    std::string path;
    std::vector<int> copyOf;  // per copy (vertex N + k), the vertex it copies
};

// The faces on one side of the plane x = x0 (by their centroids) take copies, appended after the
// file's vertices, of the vertices they share with the other side: a seam along the plane.
Split splitAtPlane(const TriMesh& m, double x0, const std::string& path) {
    const int n = m.vertexCount();
    std::vector<int> side(m.faceCount());
    std::vector<int> usedBy(n, 0);  // bit 1: a face on side 0, bit 2: side 1
    for (int t = 0; t < m.faceCount(); ++t) {
        double x = 0;
        for (int k = 0; k < 3; ++k) x += m.V(m.F(t, k), 0) / 3;
        side[t] = x > x0;
        for (int k = 0; k < 3; ++k) usedBy[m.F(t, k)] |= 1 << side[t];
    }
    Split s;
    s.path = path;
    std::vector<int> copy(n, -1);
    for (int v = 0; v < n; ++v)
        if (usedBy[v] == 3) copy[v] = n + static_cast<int>(s.copyOf.size()), s.copyOf.push_back(v);
    std::ostringstream text;
    text.precision(17);
    const auto vertex = [&](int v) {
        text << "v " << m.V(v, 0) << ' ' << m.V(v, 1) << ' ' << m.V(v, 2) << '\n';
    };
    for (int v = 0; v < n; ++v) vertex(v);
    for (int v : s.copyOf) vertex(v);
    for (int t = 0; t < m.faceCount(); ++t) {
        text << 'f';
        for (int k = 0; k < 3; ++k) {
            const int v = m.F(t, k);
            text << ' ' << (side[t] && copy[v] >= 0 ? copy[v] : v) + 1;
        }
        text << '\n';
    }
    std::ofstream(path) << text.str();
    return s;
}

struct Demo {
    DemoFiles files;
    TriMesh mesh;
    C3dTake take;
    Correspondence map;
    Split split;
    MeshReadResult splitRead;
};

// The demo creature, split along the plane through its first marker's vertex.
Demo demo(const std::string& name) {
    Demo d;
    d.files = writeDemoFiles(freshTestDir(name), 20, 10.0, false);
    d.mesh = readMesh(d.files.mesh).mesh;
    d.take = readC3d(d.files.take);
    d.map = Correspondence::read(d.files.map);
    d.map.meshVertices = 0;  // made on the unsplit file, and good for both
    const double x0 = d.mesh.V(d.map.markers[0].vertex, 0);
    d.split =
        splitAtPlane(d.mesh, x0, (fs::path(d.files.mesh).parent_path() / "split.obj").string());
    d.splitRead = readMesh(d.split.path);
    return d;
}

double maxDistance(const Positions& a, const Positions& b) {
    return (a - b).rowwise().norm().maxCoeff();
}

// Every copy where the vertex it copies is, in V.
void expectCopiesTogether(const Demo& d, const Positions& V, const std::string& what) {
    const int n = d.mesh.vertexCount();
    ASSERT_EQ(V.rows(), n + static_cast<int>(d.split.copyOf.size())) << what;
    for (size_t k = 0; k < d.split.copyOf.size(); ++k)
        ASSERT_EQ(V.row(n + k), V.row(d.split.copyOf[k])) << what << ", copy " << n + k;
}

}  // namespace

TEST(SeamWeldSolve, ASeamSplitCopyOfAMeshSolvesToTheSamePositionsAsTheWeldedMesh) {
    const Demo d = demo("seam-solve");
    ASSERT_GT(d.split.copyOf.size(), 10u);
    EXPECT_EQ(d.splitRead.weldedVertices, static_cast<int>(d.split.copyOf.size()));
    const double diagonal = boundingBoxDiagonal(d.mesh.V);
    TakeSolver whole(d.mesh, d.take, d.map), split(d.splitRead.mesh, d.take, d.map);
    expectCopiesTogether(d, split.rest().V, "calibrated rest");
    for (int f : {0, 7, 19}) {
        FrameReport a, b;
        const Positions Va = whole.solve(f, a), Vb = split.solve(f, b);
        expectCopiesTogether(d, Vb, "frame " + std::to_string(f));
        EXPECT_LT(maxDistance(Va, Vb.topRows(d.mesh.vertexCount())), 1e-6 * diagonal)
            << "frame " << f;
    }
}

// The rule for maps: any copy names the welded vertex, and solves as its first copy does.
TEST(SeamWeldSolve, AMapNamingACopySolvesAsTheMapNamingItsFirstCopy) {
    const Demo d = demo("seam-map");
    Correspondence onCopies = d.map;
    int renamed = 0;
    for (MarkerMapping& m : onCopies.markers)
        for (size_t k = 0; k < d.split.copyOf.size(); ++k)
            if (d.split.copyOf[k] == m.vertex && m.face < 0) {
                m.vertex = d.mesh.vertexCount() + static_cast<int>(k);
                ++renamed;
            }
    ASSERT_GT(renamed, 0);
    TakeSolver first(d.splitRead.mesh, d.take, d.map), copies(d.splitRead.mesh, d.take, onCopies);
    FrameReport a, b;
    EXPECT_EQ(maxDistance(first.solve(5, a), copies.solve(5, b)), 0.0);
}

// Markers where the rest mesh puts them (on the skin, no calibration) give back the rest, copies
// and all.
TEST(SeamWeldSolve, RestMarkersGiveBackTheRest) {
    Demo d = demo("seam-rest");
    const TriMesh& mesh = d.splitRead.mesh;
    const std::vector<std::size_t> points = d.map.resolve(d.take);
    for (MarkerMapping& m : d.map.markers) m.offsetMm = 0, m.face = -1;
    for (std::size_t f = 0; f < d.take.frameCount(); ++f)
        for (size_t k = 0; k < points.size(); ++k) {
            const Vec3 x = mesh.V.row(d.map.markers[k].vertex).transpose() * 1000.0;
            d.take.samples.set(f, points[k], x.x(), x.y(), x.z());
        }
    TakeSolveOptions options;
    options.calibrate = CalibrateMode::None;
    Similarity mmToMesh;  // as the samples were made, with nothing left to fit
    mmToMesh.scale = 0.001;
    options.alignment = mmToMesh;
    TakeSolver solver(mesh, d.take, d.map, options);
    FrameReport r;
    const Positions V = solver.solve(3, r);
    expectCopiesTogether(d, V, "frame 3");
    EXPECT_LT(maxDistance(V, mesh.V), 1e-4 * boundingBoxDiagonal(mesh.V));
}

// Each format's frames hold the file's vertices in its order, every copy where its vertex is.
TEST(SeamWeldSolve, EveryExportFormatKeepsTheFilesVerticesWithTheCopiesTogether) {
    const Demo d = demo("seam-export");
    const int n = d.splitRead.mesh.vertexCount();
    for (ExportFormat format : {ExportFormat::Obj, ExportFormat::Pc2, ExportFormat::Mdd}) {
        ExportRequest request;
        request.meshPath = d.split.path;
        request.c3dPath = d.files.take;
        request.outDir = freshTestDir("seam-export-" + std::to_string(int(format)));
        request.format = format;
        request.first = 4;
        request.end = 6;
        exportTake(d.splitRead.mesh, d.take, d.map, request);
        const fs::path dir = request.outDir;
        Positions V(n, 3);
        if (format == ExportFormat::Obj) {
            const MeshReadResult frame = readMesh((dir / objFrameFile("split", 5)).string());
            V = frame.mesh.V;
        } else {
            std::ifstream in(dir / (format == ExportFormat::Pc2 ? "split.pc2" : "split.mdd"),
                             std::ios::binary);
            const std::string bytes{std::istreambuf_iterator<char>(in), {}};
            // PC2: a 32-byte header, then frames of floats; MDD: big-endian frame and vertex
            // counts, a time per frame, then the frames. Frame 5 is the second of two.
            const bool mdd = format == ExportFormat::Mdd;
            const size_t head = mdd ? 8 + 4 * 2 : 32, frameStart = head + 12 * size_t(n);
            ASSERT_EQ(bytes.size(), head + 2 * 12 * size_t(n)) << "vertex count";
            for (int i = 0; i < 3 * n; ++i) {
                unsigned char b[4];
                std::memcpy(b, bytes.data() + frameStart + 4 * i, 4);
                if (mdd) std::swap(b[0], b[3]), std::swap(b[1], b[2]);
                float x;
                std::memcpy(&x, b, 4);
                V(i / 3, i % 3) = x;
            }
        }
        expectCopiesTogether(d, V, exportFormatInfo(format).name);
    }
}
