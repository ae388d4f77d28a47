// The view's aids (docs/view.md) against committed baseline pictures, each a crop where the aid
// is most of what is drawn, so that losing, moving or misdrawing it fails the comparison:
// the floor grid at the take's floor, the axes gizmo and the heat map's legend.
// ViewOverlayTest asserts where they are in numbers (the grid's height, the legend's title, the
// label boxes); this test holds what they look like.
#include <QAction>
#include <QtTest>

#include "BaselineImage.h"
#include "ViewTestSupport.h"
#include "boneless/MeshReader.h"
#include "boneless/ui/MainWindow.h"
#include "boneless/ui/MeshView.h"
#include "boneless/ui/Timeline.h"

using namespace boneless;
using namespace boneless::ui;

namespace {
constexpr double kMaxMismatchShare = 0.01;  // of a crop's pixels
}

class ViewBaselineTest : public QObject {
    Q_OBJECT
  public:
    static void initMain() { setDefaultSurfaceFormat(); }

  private slots:
    void initTestCase() { project_ = test::demoProjectFor("ViewBaselineTest", &folder_); }

    void theFloorGridAtTheTakesFloorMatchesItsBaseline() {
        MainWindow window;
        window.setMessageBoxesEnabled(false);
        window.meshView()->setMultiSampling(0);
        window.meshView()->setFixedSize(480, 360);
        window.setStartFrame(10);
        QVERIFY(window.openProject(project_));
        QVERIFY(test::showAndWait(window));
        QCOMPARE(window.displayedFrame(), 10);
        // Right of the body and in front of it: the grid's lines and its right edge, nothing
        // a solve moves.
        const QImage grid = window.meshView()->grabImage().copy(350, 215, 130, 145);
        const QString failure =
            test::differenceFromBaseline(grid, "view-floor-grid", folder_, kMaxMismatchShare);
        QVERIFY2(failure.isEmpty(), qPrintable(failure));
    }

    void theAxesGizmoMatchesItsBaseline() {
        MeshView view;
        QVERIFY(test::showMesh(view, walker(), Eigen::Vector3d::UnitZ()));
        // The gizmo's viewport is the bottom-left 16 % by 20 %; its thin lines and letters fill
        // about 3 % of this crop of it, so less may differ than elsewhere.
        const QImage corner = view.grabImage().copy(24, 480 - 96, 80, 96);
        const QString failure =
            test::differenceFromBaseline(corner, "view-axes-gizmo", folder_, kMaxMismatchShare / 2);
        QVERIFY2(failure.isEmpty(), qPrintable(failure));
    }

    void theHeatMapLegendMatchesItsBaseline() {
        MeshView view;
        const TriMesh mesh = walker();
        QVERIFY(test::showMesh(view, mesh, Eigen::Vector3d::UnitZ()));
        // A known field, 0 to 24 mm up the body: the legend's range does not hang on a solve.
        const Eigen::VectorXd height = mesh.V.col(2);
        const double low = height.minCoeff(), span = height.maxCoeff() - low;
        std::vector<float> mm(height.size());
        for (Eigen::Index v = 0; v < height.size(); ++v)
            mm[v] = float(24.0 * (height[v] - low) / span);
        view.setHeatMap(mm, "Shape error (mm)");
        QVERIFY(view.legendVisible());
        // The top-right corner: the title, the tick values and the colour bar.
        const QImage legend = view.grabImage().copy(480, 0, 160, 220);
        const QString failure = test::differenceFromBaseline(legend, "view-heat-map-legend",
                                                             folder_, kMaxMismatchShare);
        QVERIFY2(failure.isEmpty(), qPrintable(failure));
    }

  private:
    TriMesh walker() const { return readMesh((folder_ + "/demo/walker.obj").toStdString()).mesh; }

    QString folder_, project_;
};

QTEST_MAIN(ViewBaselineTest)
#include "ViewBaselineTest.moc"
