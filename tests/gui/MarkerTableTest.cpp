// The marker list beside the view: the Residual column holds the solver's residuals of the frame
// on screen, in full, and double-clicking a marker brings the camera to it.
#include <QHeaderView>
#include <QScrollBar>
#include <QTableView>
#include <QtTest>
#include <limits>

#include "ViewTestSupport.h"
#include "boneless/TakeSolver.h"
#include "boneless/ui/Document.h"
#include "boneless/ui/FrameSolver.h"
#include "boneless/ui/MainWindow.h"
#include "boneless/ui/MarkerListModel.h"
#include "boneless/ui/MeshView.h"
#include "boneless/ui/Timeline.h"

using namespace boneless;
using namespace boneless::ui;

namespace {

// Per marker row: the residual (mm) of frame `frame`, solved here with core's TakeSolver alone.
std::vector<double> residualsOf(const Document& document, int frame) {
    TakeSolver solver(document.mesh(), document.take(), document.correspondence(),
                      document.solveOptions());
    FrameReport report;
    const Positions V = solver.solve(frame, report);
    const Positions predicted = solver.predictedMarkers(V);
    const Positions targets = solver.targets(frame);
    const double meshUnitsPerMm = solver.calibration().takeToMesh.scale / document.take().unitToMm;
    const std::vector<std::size_t> points = document.correspondence().resolve(document.take());
    std::vector<double> mm(document.markerCount(), std::numeric_limits<double>::quiet_NaN());
    for (int m = 0; m < document.markerCount(); ++m)
        for (std::size_t k = 0; k < points.size(); ++k)
            if (int(points[k]) == document.markerPoint(m) && targets.row(k).allFinite())
                mm[m] = (predicted.row(k) - targets.row(k)).norm() / meshUnitsPerMm;
    return mm;
}

}  // namespace

class MarkerTableTest : public QObject {
    Q_OBJECT
  public:
    static void initMain() { setDefaultSurfaceFormat(); }

  private slots:
    void initTestCase() { project_ = test::demoProjectFor("MarkerTableTest"); }
    void init() {
        window_ = test::openShown(project_);
        QVERIFY(window_);
    }
    void cleanup() { window_.reset(); }

    void theResidualColumnHoldsTheSolversResidualsOfTheFrameShown() {
        Document* document = window_->document();
        QTableView* table = window_->markerTable();
        for (const int frame : {17, 42}) {
            window_->timeline()->setFrame(frame);
            QVERIFY(test::waitForFrame(*window_));
            const std::vector<double> expected = residualsOf(*document, frame);
            int filled = 0;
            for (int m = 0; m < document->markerCount(); ++m) {
                const QModelIndex cell = table->model()->index(
                    window_->markerProxy()->rowOfMarker(m), MarkerListModel::ResidualColumn);
                const QString text = cell.data().toString();
                if (!std::isfinite(expected[m])) {
                    QCOMPARE(text, QString());
                    continue;
                }
                ++filled;
                QCOMPARE(text, QString::number(expected[m], 'f', 2));
                QVERIFY(std::abs(cell.data(MarkerListModel::ResidualRole).toDouble() -
                                 expected[m]) < 1e-6);
            }
            QVERIFY2(filled > document->markerCount() / 2,
                     qPrintable(QString("%1 residuals at frame %2").arg(filled).arg(frame)));
        }
    }

    void theResidualColumnIsNotCutOff() {
        QTableView* table = window_->markerTable();
        QHeaderView* header = table->horizontalHeader();
        const int column = MarkerListModel::ResidualColumn;
        // Its right edge is inside the list, and it is as wide as its widest cell and title.
        const int right = header->sectionViewportPosition(column) + header->sectionSize(column);
        QVERIFY2(
            right <= table->viewport()->width(),
            qPrintable(QString("ends at %1 of %2").arg(right).arg(table->viewport()->width())));
        int widest = 0;
        for (int row = 0; row < table->model()->rowCount(); ++row)
            widest = std::max(widest, table->fontMetrics().horizontalAdvance(
                                          table->model()->index(row, column).data().toString()));
        QVERIFY2(widest > 0, "no residual shown");
        QVERIFY(header->sectionSize(column) > widest);
        QVERIFY(header->sectionSize(column) >= header->sectionSizeHint(column));
        QVERIFY(table->horizontalScrollBar()->maximum() == 0);
    }

    void doubleClickingAMarkerBringsTheCameraToIt() {
        Document* document = window_->document();
        MeshView* view = window_->meshView();
        QTableView* table = window_->markerTable();
        // Where the view draws the markers: the solver's answer for the frame shown.
        FrameSolver solver;
        QVERIFY(solver.setProblem(*document));
        QSignalSpy ready(&solver, &FrameSolver::frameReady);
        solver.requestFrame(window_->displayedFrame());
        QVERIFY(ready.wait(60000));
        const Positions markers = ready.at(0).at(0).value<FrameResult>().markers;
        for (const int marker : {4, 30}) {
            QVERIFY(markers.row(marker).allFinite());
            const double before = (view->cameraPosition() - view->focalPoint()).norm();
            const QModelIndex cell =
                table->model()->index(window_->markerProxy()->rowOfMarker(marker), 0);
            table->scrollTo(cell);
            const QPoint at = table->visualRect(cell).center();
            QTest::mouseClick(table->viewport(), Qt::LeftButton, {}, at);
            QTest::mouseDClick(table->viewport(), Qt::LeftButton, {}, at);
            const Eigen::Vector3d target = markers.row(marker).transpose();
            QVERIFY2((view->focalPoint() - target).norm() < 1e-6,
                     qPrintable(QString("focal point %1 from the marker")
                                    .arg((view->focalPoint() - target).norm())));
            // Closer, not farther.
            QVERIFY((view->cameraPosition() - view->focalPoint()).norm() <= before + 1e-9);
        }
    }

  private:
    QString project_;
    std::unique_ptr<MainWindow> window_;
};

QTEST_MAIN(MarkerTableTest)
#include "MarkerTableTest.moc"
