// Scrub latency: from the playhead stopping to the render that shows that frame's answer, over
// several drags that stop on a frame the solver has to solve, and for frames from its cache.
// Printed as mean and worst, never asserted (machines differ). The 100K-face koala runs only with
// BONELESS_KOALA_LATENCY=1, and skips when the shared data is absent.
#include <QtTest>
#include <algorithm>
#include <cmath>
#include <numeric>
#include <optional>
#include <vector>

#include "ViewTestSupport.h"
#include "boneless/C3dWriter.h"
#include "boneless/Correspondence.h"
#include "boneless/MeshReader.h"
#include "boneless/Sampling.h"
#include "boneless/ui/Document.h"
#include "boneless/ui/FrameSolver.h"
#include "boneless/ui/MainWindow.h"
#include "boneless/ui/Timeline.h"

using namespace boneless;
using namespace boneless::ui;

namespace {

// A take for any mesh: K farthest-point vertices as markers (in mm, 100 mm per mesh unit),
// swaying and bending slowly about the mesh's centre, with the map that goes with it.
void writeSyntheticTake(const QString& meshPath, const QString& folder, int markers, int frames) {
    const TriMesh mesh = readMesh(meshPath.toStdString()).mesh;
    const std::vector<int> ids = euclideanFarthestPoints(mesh.V, markers, 0);
    const Eigen::RowVector3d centre = mesh.V.colwise().mean();
    const double size = boundingBoxDiagonal(mesh.V);

    C3dTake take;
    take.rate = 30;
    take.units = "mm";
    take.unitToMm = 1;
    take.samples = C3dSamples(frames, ids.size());
    Correspondence map;
    map.meshFile = QFileInfo(meshPath).fileName().toStdString();
    map.meshVertices = mesh.vertexCount();
    for (std::size_t k = 0; k < ids.size(); ++k) {
        C3dPoint point;
        point.name = point.label = QString("K%1").arg(k + 1, 2, 10, QChar('0')).toStdString();
        take.points.push_back(point);
        map.markers.push_back({point.label, ids[k], 0.0, "{}"});
    }
    for (int t = 0; t < frames; ++t) {
        const double phase = 2 * M_PI * t / frames;
        const Eigen::Matrix3d R =
            Eigen::AngleAxisd(0.2 * std::sin(phase), Eigen::Vector3d::UnitY()).toRotationMatrix();
        for (std::size_t k = 0; k < ids.size(); ++k) {
            Eigen::Vector3d p = (mesh.V.row(ids[k]) - centre).transpose();
            // Bend: the far side of the mesh swings more than the near side.
            p.z() += 0.05 * size * std::sin(phase) * (p.x() / size);
            p = R * p;
            take.samples.set(t, k, 100 * p.x(), 100 * p.y(), 100 * p.z());
        }
    }
    writeC3d(take, (folder + "/synthetic.c3d").toStdString());
    map.write((folder + "/synthetic.map.json").toStdString());
}

// A mouse dragging the playhead sends a move about every 16 ms.
constexpr int kMoveMs = 16;

struct Times {
    std::vector<double> ms;
    void add(double t) { ms.push_back(t); }
    double mean() const {
        return ms.empty() ? -1 : std::accumulate(ms.begin(), ms.end(), 0.0) / ms.size();
    }
    double worst() const { return ms.empty() ? -1 : *std::max_element(ms.begin(), ms.end()); }
};

struct ScrubLatency {
    Times uncached;  // a stop on a frame nobody asked for before: playhead stopped → answer drawn
    Times solve;     // those frames' solve alone
    Times cached;    // a stop on a cached frame
    int moves = 0, answersWhileDragging = 0;
    bool ok = false;
};

// Drags the playhead from each stop to the next a frame per move, as a user scrubs, and measures
// each stop: from the move that stops on a frame to the end of the render of its answer. The
// cache is emptied before each drag, so every stop is on a frame the solver has to solve (the
// frames dragged through are solved on the way when the worker is free, newest first). Then it
// steps back and forth between two cached frames.
ScrubLatency measure(MainWindow& window, const std::vector<int>& stops, int timeoutMs) {
    ScrubLatency result;
    FrameSolver* solver = window.frameSolver();
    int target = -1;
    bool dragging = false;
    std::optional<std::pair<double, bool>> shown;  // the target's latency, and if cached
    std::optional<double> solveMs;
    QObject context;
    QObject::connect(&window, &MainWindow::latencyMeasured, &context,
                     [&](int frame, double ms, bool fromCache) {
                         if (!dragging && frame == target) shown = {ms, fromCache};
                     });
    // Frames the worker answered during a drag are drawn too, though the playhead has moved on.
    QObject::connect(&window, &MainWindow::frameDisplayed, &context, [&](int) {
        if (dragging) ++result.answersWhileDragging;
    });
    QObject::connect(solver, &FrameSolver::frameReady, &context, [&](const FrameResult& r) {
        if (!dragging && r.frame == target && !r.fromCache) solveMs = r.solveMs;
    });
    auto stopAt = [&](int frame) {
        target = frame;
        shown.reset();
        solveMs.reset();
        window.timeline()->scrubTo(frame);
        return test::waitForFrame(window, timeoutMs) && shown;
    };

    window.timeline()->scrubTo(stops.front());  // perhaps where it is already: no new request
    if (!test::waitForFrame(window, timeoutMs)) return result;
    const std::size_t limit = solver->cacheLimit();
    for (std::size_t i = 1; i < stops.size(); ++i) {
        solver->setCacheLimit(0);  // empties it
        solver->setCacheLimit(limit);
        const int from = stops[i - 1], to = stops[i], step = from < to ? 1 : -1;
        dragging = true;
        for (int f = from + step; f != to; f += step) {
            window.timeline()->scrubTo(f);
            ++result.moves;
            QTest::qWait(kMoveMs);
        }
        dragging = false;
        if (!stopAt(to)) return result;
        if (shown->second) continue;  // cannot happen with the cache emptied; not counted
        result.uncached.add(shown->first);
        if (solveMs) result.solve.add(*solveMs);
    }
    const int last = stops.back(), next = last > 0 ? last - 1 : last + 1;
    if (!stopAt(next)) return result;  // cached or solved now: either way cached from here on
    for (int i = 0; i < 6; ++i) {
        if (!stopAt(i % 2 ? next : last)) return result;
        if (shown->second) result.cached.add(shown->first);
    }
    result.ok = true;
    return result;
}

void report(const char* name, const MainWindow& window, const ScrubLatency& l) {
    qInfo(
        "%s (%d vertices, %d faces): playhead stopped on an uncached frame -> its answer on "
        "screen: mean %.0f ms, worst %.0f ms over %d stops (the solve alone: mean %.0f ms, worst "
        "%.0f ms); on a cached frame: mean %.1f ms, worst %.1f ms over %d stops; %d answers shown "
        "during %d moves of the drags",
        name, window.document()->mesh().vertexCount(), window.document()->mesh().faceCount(),
        l.uncached.mean(), l.uncached.worst(), int(l.uncached.ms.size()), l.solve.mean(),
        l.solve.worst(), l.cached.mean(), l.cached.worst(), int(l.cached.ms.size()),
        l.answersWhileDragging, l.moves);
}

// Stops on a 60-frame take, forwards then back, 12 to 20 frames apart.
const std::vector<int> kStops{0, 12, 30, 45, 59, 40, 20, 5};

}  // namespace

class ScrubLatencyTest : public QObject {
    Q_OBJECT
  public:
    static void initMain() { setDefaultSurfaceFormat(); }

  private slots:
    void initTestCase() {
        test::isolate("ScrubLatencyTest");
        folder_ = test::freshFolder("ScrubLatencyTest");
    }

    void demo() {
        MainWindow window;
        window.setMessageBoxesEnabled(false);
        QVERIFY(window.openProject(test::writeDemoProject(folder_ + "/demo")));
        QVERIFY(test::showAndWait(window));
        const ScrubLatency latency = measure(window, kStops, 60000);
        QVERIFY(latency.ok);
        QCOMPARE(int(latency.uncached.ms.size()), int(kStops.size()) - 1);
        QVERIFY(!latency.cached.ms.empty());
        report("demo", window, latency);
    }

    void koala() {
        const QString mesh = QStringLiteral(BONELESS_SHARED_DATA "/meshes/koala/koala.obj");
        if (qgetenv("BONELESS_KOALA_LATENCY") != "1")
            QSKIP("set BONELESS_KOALA_LATENCY=1 to measure on the 100K-face koala");
        if (!QFileInfo::exists(mesh)) QSKIP("no koala mesh in the shared data");
        writeSyntheticTake(mesh, folder_, 40, 60);
        MainWindow window;
        window.setMessageBoxesEnabled(false);
        window.resize(1280, 800);
        QVERIFY(window.openFile(mesh));
        QVERIFY(window.openFile(folder_ + "/synthetic.c3d"));
        QVERIFY(window.openFile(folder_ + "/synthetic.map.json"));
        QElapsedTimer first;
        first.start();
        QVERIFY(test::showAndWait(window, 300000));
        qInfo("koala: first frame (the solver's set-up, then the frame) shown after %.2f s",
              first.elapsed() / 1000.0);
        const ScrubLatency latency = measure(window, kStops, 300000);
        QVERIFY(latency.ok);
        QCOMPARE(int(latency.uncached.ms.size()), int(kStops.size()) - 1);
        report("koala", window, latency);
    }

  private:
    QString folder_;
};

QTEST_MAIN(ScrubLatencyTest)
#include "ScrubLatencyTest.moc"
