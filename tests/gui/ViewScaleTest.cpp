// The 3D view's text on a high-DPI screen (QT_SCALE_FACTOR=2, a device pixel ratio of 2): the
// labels and the legend are as large as the widgets' text, and the legend stays in the view.
#include <QFontMetrics>
#include <QtTest>

#include "ViewTestSupport.h"
#include "boneless/MeshReader.h"

using namespace boneless;
using namespace boneless::ui;

class ViewScaleTest : public QObject {
    Q_OBJECT
  public:
    static void initMain() {
        qputenv("QT_SCALE_FACTOR", "2");
        setDefaultSurfaceFormat();
    }

  private slots:
    void initTestCase() { test::demoProjectFor("ViewScaleTest", &folder_); }

    // At a scale of 2 the text was drawn at the size it has at 1, half the widgets' size, and
    // the legend's title ran off the view's right edge ("Shape error (mn").
    void atTwiceTheScaleTheLegendIsAsLargeAsTheWidgetsTextAndInsideTheView() {
        QCOMPARE(qApp->devicePixelRatio(), 2.0);
        MeshView view;
        const TriMesh mesh = readMesh((folder_ + "/demo/walker.obj").toStdString()).mesh;
        QVERIFY(test::showMesh(view, mesh));
        QCOMPARE(view.devicePixelRatioF(), 2.0);
        std::vector<float> mm(mesh.V.rows());
        for (Eigen::Index i = 0; i < mesh.V.rows(); ++i) mm[i] = float(24.0 * i / mesh.V.rows());
        const QString title = "Shape error (mm)";
        view.setHeatMap(mm, title);
        const QImage image = view.grabImage();
        const QRect legend = view.legendRect();
        const QString where = QString("the legend at (%1, %2) %3x%4 in a %5x%6 view")
                                  .arg(legend.x())
                                  .arg(legend.y())
                                  .arg(legend.width())
                                  .arg(legend.height())
                                  .arg(view.width())
                                  .arg(view.height());
        QVERIFY2(!legend.isEmpty() && view.rect().contains(legend), qPrintable(where));
        // The legend is as wide as its title: as wide as the widgets would write it.
        const int titleWidth = QFontMetrics(view.font()).horizontalAdvance(title);
        QVERIFY2(
            legend.width() > 0.7 * titleWidth,
            qPrintable(where + QString(", the title %1 px in the widgets' font").arg(titleWidth)));
        // Nothing of the title is cut by the view's right edge: its last columns are background.
        const QColor background = image.pixelColor(image.width() - 1, image.height() / 2);
        for (int y = 0; y < image.height() / 10; ++y)
            for (int x = image.width() - 4; x < image.width(); ++x)
                QVERIFY2(image.pixelColor(x, y) == background,
                         qPrintable(QString("text at (%1, %2) of the %3x%4 image")
                                        .arg(x)
                                        .arg(y)
                                        .arg(image.width())
                                        .arg(image.height())));
    }

    void atTwiceTheScaleMarkerLabelsAreAsTallAsTheWidgetsText() {
        MeshView view;
        const TriMesh mesh = readMesh((folder_ + "/demo/walker.obj").toStdString()).mesh;
        QVERIFY(test::showMesh(view, mesh));
        Positions markers(1, 3);
        markers.row(0) = mesh.V.colwise().mean();
        view.setMarkers(markers, {MarkerState::Selected}, {"LFHD"});
        view.setLabelsVisible(true);
        (void)view.grabImage();
        const QList<QRect> boxes = view.labelBoxes();
        QCOMPARE(boxes.size(), 1);
        const int textHeight = QFontMetrics(view.font()).ascent();
        QVERIFY2(boxes[0].height() > 0.7 * textHeight,
                 qPrintable(QString("a label %1 px tall, the widgets' capitals %2 px")
                                .arg(boxes[0].height())
                                .arg(textHeight)));
    }

  private:
    QString folder_;
};

QTEST_MAIN(ViewScaleTest)
#include "ViewScaleTest.moc"
