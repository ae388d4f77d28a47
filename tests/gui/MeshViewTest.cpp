// The 3D view's picking: a click at the projected position of a known vertex maps the selected
// marker to exactly that vertex, undoably.
#include <QAction>
#include <QTableView>
#include <QUndoStack>
#include <QtTest>
#include <limits>

#include "ViewTestSupport.h"
#include "boneless/MeshReader.h"
#include "boneless/ui/Document.h"
#include "boneless/ui/MainWindow.h"
#include "boneless/ui/MarkerListModel.h"
#include "boneless/ui/MeshView.h"

using namespace boneless;
using namespace boneless::ui;

namespace {

// The vertices nearest to the camera first: the nearest point of a surface to the eye is never
// hidden behind another part of it, so these are known to be visible.
std::vector<int> verticesByCameraDistance(const MeshView& view) {
    const Eigen::RowVector3d eye = view.cameraPosition().transpose();
    const Positions& V = view.positions();
    std::vector<int> order(V.rows());
    for (int i = 0; i < int(order.size()); ++i) order[i] = i;
    std::sort(order.begin(), order.end(), [&](int a, int b) {
        return (V.row(a) - eye).squaredNorm() < (V.row(b) - eye).squaredNorm();
    });
    return order;
}

}  // namespace

class MeshViewTest : public QObject {
    Q_OBJECT
  public:
    static void initMain() { setDefaultSurfaceFormat(); }

  private slots:
    void initTestCase() {
        test::isolate("MeshViewTest");
        folder_ = test::freshFolder("MeshViewTest");
        project_ = test::writeDemoProject(folder_ + "/demo");
    }

    void projectedVertexPicksBack() {
        MeshView view;
        view.setMultiSampling(0);
        view.resize(640, 480);
        view.setMesh(readMesh((folder_ + "/demo/walker.obj").toStdString()).mesh);
        view.show();
        QVERIFY(QTest::qWaitForWindowExposed(&view));
        QVERIFY(!view.grabImage().isNull());  // one render: the camera is fitted

        const std::vector<int> order = verticesByCameraDistance(view);
        for (int k = 0; k < 5; ++k) {
            const int v = order[k];
            const QPoint p = view.projectVertex(v);
            QVERIFY2(view.rect().contains(p), qPrintable(QString("vertex %1 off screen").arg(v)));
            QCOMPARE(view.pickPoint(p).vertex, v);
        }
        QCOMPARE(view.pickPoint(QPoint(1, 1)).vertex, -1);  // the background
    }

    // A click names the point of the surface it lands on, not only the nearest vertex: that
    // point, drawn again, is under the cursor.
    void aPickedPointIsWhereTheClickLanded() {
        MeshView view;
        view.setMultiSampling(0);
        view.resize(640, 480);
        const TriMesh mesh = readMesh((folder_ + "/demo/walker.obj").toStdString()).mesh;
        view.setMesh(mesh);
        view.show();
        QVERIFY(QTest::qWaitForWindowExposed(&view));
        QVERIFY(!view.grabImage().isNull());
        int faces = 0, offVertex = 0;
        for (int y = view.height() / 4; y < 3 * view.height() / 4; y += 23)
            for (int x = view.width() / 4; x < 3 * view.width() / 4; x += 19) {
                const SurfacePoint p = view.pickPoint(QPoint(x, y));
                if (p.vertex < 0) continue;
                QVERIFY(p.face >= 0 && p.face < mesh.faceCount());
                QVERIFY((mesh.F.row(p.face).array() == p.vertex).any());
                QVERIFY(std::abs(p.barycentric.sum() - 1) < 1e-9 && p.barycentric.minCoeff() >= 0);
                const Vec3 at = surfacePosition(mesh, view.positions(), p);
                const QPoint back = view.projectPoint(at);
                QVERIFY2((back - QPoint(x, y)).manhattanLength() <= 2,
                         qPrintable(QString("(%1, %2) drawn again at (%3, %4)")
                                        .arg(x)
                                        .arg(y)
                                        .arg(back.x())
                                        .arg(back.y())));
                ++faces;
                offVertex += view.projectVertex(p.vertex) != QPoint(x, y);
            }
        QVERIFY2(faces >= 20, qPrintable(QString::number(faces)));
        QVERIFY(offVertex > faces / 2);  // a vertex would have put most of them elsewhere
    }

    void clickMapsSelectedMarkerAndUndoRedo() {
        MainWindow window;
        window.setMessageBoxesEnabled(false);
        QSignalSpy errors(&window, &MainWindow::errorShown);
        QVERIFY(window.openProject(project_));
        QVERIFY(test::showAndWait(window));
        Document* document = window.document();
        MeshView* view = window.meshView();
        QVERIFY(document->markerCount() > 0);

        // Select a marker the way a user does: click its row in the list.
        const int marker = 3;
        const int before = document->mappedVertex(marker);
        QVERIFY(before >= 0);
        QTableView* table = window.markerTable();
        const QModelIndex index =
            table->model()->index(window.markerProxy()->rowOfMarker(marker), 0);
        table->scrollTo(index);
        QTest::mouseClick(table->viewport(), Qt::LeftButton, {}, table->visualRect(index).center());
        QCOMPARE(document->selectedMarker(), marker);

        // The visible vertex nearest the eye that carries no marker yet.
        int target = -1;
        for (int v : verticesByCameraDistance(*view)) {
            if (document->markerForVertex(v) < 0 && v != before &&
                view->rect().contains(view->projectVertex(v))) {
                target = v;
                break;
            }
        }
        QVERIFY(target >= 0);

        auto* mapping = window.findChild<QAction*>("actionMapMarkers");  // as the README says
        QVERIFY(mapping);
        mapping->trigger();
        QSignalSpy picked(view, &MeshView::pointPicked);
        QTest::mouseClick(view, Qt::LeftButton, {}, view->projectVertex(target));
        QCOMPARE(picked.count(), 1);
        QCOMPARE(picked.at(0).at(0).value<SurfacePoint>().vertex, target);
        QCOMPARE(document->mappedVertex(marker), target);
        QCOMPARE(document->markerForVertex(target), marker);

        // Undo and redo through the window's shortcuts, as a user would.
        QTest::keyClick(&window, Qt::Key_Z, Qt::ControlModifier);
        QCOMPARE(document->mappedVertex(marker), before);
        QTest::keyClick(&window, Qt::Key_Z, Qt::ControlModifier | Qt::ShiftModifier);
        QCOMPARE(document->mappedVertex(marker), target);
        QCOMPARE(errors.count(), 0);

        // Leaving Map Markers, the edited map is solved and shown again.
        mapping->trigger();
        QVERIFY(test::waitForFrame(window));
    }

    void dragTurnsCameraWithoutPicking() {
        MainWindow window;
        window.setMessageBoxesEnabled(false);
        QVERIFY(window.openProject(project_));
        QVERIFY(test::showAndWait(window));
        MeshView* view = window.meshView();
        window.document()->setSelectedMarker(0);
        const int before = window.document()->mappedVertex(0);
        const Eigen::Vector3d eye = view->cameraPosition();

        QSignalSpy picked(view, &MeshView::pointPicked);
        const QPoint start = view->rect().center();
        QTest::mousePress(view, Qt::LeftButton, {}, start);
        for (int step = 1; step <= 5; ++step)
            QTest::mouseMove(view, start + QPoint(12 * step, 4 * step));
        QTest::mouseRelease(view, Qt::LeftButton, {}, start + QPoint(60, 20));

        QCOMPARE(picked.count(), 0);
        QCOMPARE(window.document()->mappedVertex(0), before);
        QVERIFY((view->cameraPosition() - eye).norm() > 1e-6);
    }

    void overlaysRender() {
        MainWindow window;
        window.setMessageBoxesEnabled(false);
        QVERIFY(window.openProject(project_));
        QVERIFY(test::showAndWait(window));
        MeshView* view = window.meshView();
        const QImage plain = view->grabImage();
        view->setLabelsVisible(true);
        view->setHighlightedPoint(SurfacePoint{0});
        std::vector<float> heat(view->positions().rows());
        for (std::size_t i = 0; i < heat.size(); ++i) heat[i] = float(i % 7);
        view->setHeatMap(heat);
        const QImage decorated = view->grabImage();
        QCOMPARE(decorated.size(), plain.size());
        QVERIFY(decorated != plain);
        view->setHeatMap({});
        view->setLabelsVisible(false);
        view->resetCamera();
        QVERIFY(!view->grabImage().isNull());
        // Multisampling as the application uses it by default: still a picture, same size.
        view->setMultiSampling(4);
        const QImage smooth = view->grabImage();
        QCOMPARE(smooth.size(), plain.size());
        int covered = 0;
        for (int y = 0; y < smooth.height(); y += 4)
            for (int x = 0; x < smooth.width(); x += 4)
                covered += smooth.pixel(x, y) != smooth.pixel(0, 0);
        QVERIFY(covered > smooth.width() * smooth.height() / 16 / 20);  // > 5 % is mesh
        view->setMultiSampling(0);
    }

  private:
    QString folder_, project_;
};

QTEST_MAIN(MeshViewTest)
#include "MeshViewTest.moc"
