// Scrub latency: from moving the playhead to the render that shows the frame, for a frame the
// solver has to solve and for one from its cache. Printed, never asserted (machines differ).
// The 100K-face koala runs only with BONELESS_KOALA_LATENCY=1: its frames take many seconds.
#include <QtTest>
#include <cmath>
#include <map>

#include "ViewTestSupport.h"
#include "boneless/C3dWriter.h"
#include "boneless/Correspondence.h"
#include "boneless/MeshReader.h"
#include "boneless/Sampling.h"
#include "boneless/ui/Document.h"
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

struct Latency {
    double previewMs = -1, uncachedMs = -1, cachedMs = -1;
};

Latency measure(MainWindow& window, int farFrame, int timeoutMs) {
    std::map<int, std::pair<double, bool>> seen;
    std::map<int, double> preview;
    QObject::connect(&window, &MainWindow::latencyMeasured,
                     [&](int frame, double ms, bool cached, bool isPreview) {
                         if (isPreview)
                             preview[frame] = ms;
                         else
                             seen[frame] = {ms, cached};
                     });
    Latency result;
    window.timeline()->scrubTo(farFrame);
    if (!test::waitForFrame(window, timeoutMs)) return result;
    window.timeline()->scrubTo(0);
    if (!test::waitForFrame(window, timeoutMs)) return result;
    if (seen.count(farFrame) && !seen[farFrame].second) result.uncachedMs = seen[farFrame].first;
    if (seen.count(0) && seen[0].second) result.cachedMs = seen[0].first;
    if (preview.count(farFrame)) result.previewMs = preview[farFrame];
    return result;
}

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
        const Latency latency = measure(window, 40, 60000);
        QVERIFY(latency.uncachedMs > 0 && latency.cachedMs > 0);
        QCOMPARE(latency.previewMs, -1.0);  // too small a mesh for previews to pay
        qInfo("demo (%d vertices, %d faces): uncached frame %.0f ms, cached frame %.0f ms",
              window.document()->mesh().vertexCount(), window.document()->mesh().faceCount(),
              latency.uncachedMs, latency.cachedMs);
    }

    void koala() {
        const QString mesh = QStringLiteral(BONELESS_SHARED_DATA "/meshes/koala/koala.obj");
        if (qgetenv("BONELESS_KOALA_LATENCY") != "1")
            QSKIP("set BONELESS_KOALA_LATENCY=1 to measure on the 100K-face koala");
        if (!QFileInfo::exists(mesh)) QSKIP("no koala mesh in the shared data");
        writeSyntheticTake(mesh, folder_, 40, 12);
        MainWindow window;
        window.setMessageBoxesEnabled(false);
        window.resize(1280, 800);
        QVERIFY(window.openFile(mesh));
        QVERIFY(window.openFile(folder_ + "/synthetic.c3d"));
        QVERIFY(window.openFile(folder_ + "/synthetic.map.json"));
        QElapsedTimer first;
        first.start();
        QVERIFY(test::showAndWait(window, 900000));
        qInfo("koala: first frame (continuation from the rest pose) shown after %.1f s",
              first.elapsed() / 1000.0);
        const Latency latency = measure(window, 3, 900000);  // the take's farthest pose from 0
        QVERIFY(latency.uncachedMs > 0 && latency.cachedMs > 0);
        QVERIFY(latency.previewMs > 0 && latency.previewMs < latency.uncachedMs);
        qInfo(
            "koala (%d vertices, %d faces): uncached frame %.0f ms (its preview %.0f ms), "
            "cached frame %.0f ms",
            window.document()->mesh().vertexCount(), window.document()->mesh().faceCount(),
            latency.uncachedMs, latency.previewMs, latency.cachedMs);
    }

  private:
    QString folder_;
};

QTEST_MAIN(ScrubLatencyTest)
#include "ScrubLatencyTest.moc"
