// What the view draws besides the mesh: the floor grid at the take's floor, the axes gizmo, the
// heat map's legend and marker labels that do not pile up.
#include <QAction>
#include <QtTest>
#include <cmath>
#include <limits>

#include "ViewTestSupport.h"
#include "boneless/MeshReader.h"
#include "boneless/ui/Document.h"
#include "boneless/ui/MainWindow.h"
#include "boneless/ui/MeshView.h"
#include "boneless/ui/Timeline.h"

using namespace boneless;
using namespace boneless::ui;

namespace {

QAction* actionNamed(MainWindow& window, const QString& text) {
    for (QAction* action : window.findChildren<QAction*>())
        if (action->text() == text) return action;
    return nullptr;
}

// How many pixels of `image` inside `area` are strongly of one hue: red, green or blue.
struct Hues {
    int red = 0, green = 0, blue = 0;
    int violet = 0, yellow = 0;  // the heat map's ends
};

// CIE L*, the lightness a reader sees whatever their colour vision: 0 black to 100 white.
double lightness(const QColor& c) {
    const auto linear = [](double v) {
        return v <= 0.04045 ? v / 12.92 : std::pow((v + 0.055) / 1.055, 2.4);
    };
    const double y =
        0.2126 * linear(c.redF()) + 0.7152 * linear(c.greenF()) + 0.0722 * linear(c.blueF());
    return y > 216.0 / 24389 ? 116 * std::cbrt(y) - 16 : y * 24389.0 / 27;
}
Hues huesIn(const QImage& image, const QRect& area) {
    Hues h;
    for (int y = area.top(); y <= area.bottom(); ++y)
        for (int x = area.left(); x <= area.right(); ++x) {
            const QColor c = image.pixelColor(x, y);
            const int r = c.red(), g = c.green(), b = c.blue();
            h.red += r > 150 && r > 2 * g && r > 2 * b;
            h.green += g > 150 && g > 1.6 * r && g > 1.6 * b;
            h.blue += b > 150 && b > 1.6 * r && b > 1.3 * g;
            h.violet += b > 60 && r > 40 && g < 30;
            h.yellow += r > 200 && g > 200 && b < 100;
        }
    return h;
}

}  // namespace

class ViewOverlayTest : public QObject {
    Q_OBJECT
  public:
    static void initMain() { setDefaultSurfaceFormat(); }

  private slots:
    void initTestCase() { project_ = test::demoProjectFor("ViewOverlayTest", &folder_); }

    void theFloorGridLiesAtTheLowestMarkerOfTheTake() {
        const auto shown = test::openShown(project_);
        QVERIFY(shown);
        MainWindow& window = *shown;
        const Document* document = window.document();
        // The walker stands on z = 0 with z up; its markers sit on the skin, so the floor is the
        // lowest foot marker of the whole take, not of this frame.
        double lowest = std::numeric_limits<double>::infinity(), lowestAtFrame0 = lowest;
        for (int f = 0; f < document->frameCount(); ++f) {
            const Positions P = document->markerPositions(f);
            for (Eigen::Index k = 0; k < P.rows(); ++k)
                if (P.row(k).allFinite()) {
                    lowest = std::min(lowest, P(k, 2));
                    if (f == 0) lowestAtFrame0 = std::min(lowestAtFrame0, P(k, 2));
                }
        }
        QVERIFY(std::isfinite(lowest));
        QVERIFY2(lowest < lowestAtFrame0, "the take's floor must not be one frame's");
        const double height = window.meshView()->floorHeight();
        QVERIFY2(std::abs(height - lowest) < 1e-9,
                 qPrintable(QString("grid at %1, floor at %2").arg(height).arg(lowest)));
    }

    void withoutATakeTheFloorIsTheRestMeshsLowestPoint() {
        MainWindow window;
        window.setMessageBoxesEnabled(false);
        QVERIFY(window.openFile(folder_ + "/demo/walker.obj"));
        QVERIFY(test::showAndWait(window));
        const Positions& V = window.document()->mesh().V;
        // Without a take nothing says which way is up: the view's default, y.
        QCOMPARE(window.meshView()->floorHeight(), V.col(1).minCoeff());
        window.document()->reset();
        QVERIFY(std::isnan(window.meshView()->floorHeight()));
    }

    void theAxesGizmoSitsInACornerAndTurnsWithTheCamera() {
        MeshView view;
        QVERIFY(test::showMesh(view, readMesh((folder_ + "/demo/walker.obj").toStdString()).mesh));
        QVERIFY(view.axesVisible());
        const QRect corner(0, view.height() - view.height() / 5, view.width() / 6,
                           view.height() / 5);
        const QImage before = view.grabImage();
        const Hues h = huesIn(before, corner);
        QVERIFY2(h.red > 10 && h.green > 10 && h.blue > 10,
                 qPrintable(QString("red %1, green %2, blue %3 pixels in the corner")
                                .arg(h.red)
                                .arg(h.green)
                                .arg(h.blue)));
        const Hues elsewhere =
            huesIn(before, QRect(view.width() / 2, 0, view.width() / 6, view.height() / 5));
        QCOMPARE(elsewhere.red + elsewhere.green + elsewhere.blue, 0);

        // Turn the camera by a drag: the gizmo's picture changes with it.
        const QPoint start = view.rect().center();
        QTest::mousePress(&view, Qt::LeftButton, {}, start);
        for (int step = 1; step <= 5; ++step) QTest::mouseMove(&view, start + QPoint(20 * step, 0));
        QTest::mouseRelease(&view, Qt::LeftButton, {}, start + QPoint(100, 0));
        const QImage after = view.grabImage();
        QVERIFY(before.copy(corner) != after.copy(corner));
    }

    void theHeatMapHasALegendWithItsQuantityAndUnits() {
        const auto shown = test::openShown(project_);
        QVERIFY(shown);
        MainWindow& window = *shown;
        MeshView* view = window.meshView();
        const QRect strip(int(view->width() * 0.88), 0, view->width() - int(view->width() * 0.88),
                          view->height());
        QVERIFY(!view->legendVisible());
        const Hues plain = huesIn(view->grabImage(), strip);
        QCOMPARE(plain.red + plain.blue, 0);

        QAction* heatMap = actionNamed(window, "Shape Error &Heat Map");
        QVERIFY(heatMap);
        heatMap->setChecked(true);
        QVERIFY(QTest::qWaitFor([&] { return window.frameUpToDate() && view->legendVisible(); },
                                60000));
        QCOMPARE(view->legendTitle(), QString("Shape error (mm)"));
        // The legend's colour bar is drawn: dark violet at its low end, yellow at its high end,
        // and no red (a rainbow's red reads darker than its yellow).
        const Hues legend = huesIn(view->grabImage(), strip);
        QVERIFY2(legend.violet > 20 && legend.yellow > 20 && legend.red == 0,
                 qPrintable(QString("violet %1, yellow %2, red %3")
                                .arg(legend.violet)
                                .arg(legend.yellow)
                                .arg(legend.red)));
        // The demo's first frame, the take at rest, is no error: its scale is at least 2 mm.
        QVERIFY2(view->legendTop() >= 2.0, qPrintable(QString::number(view->legendTop())));

        heatMap->setChecked(false);
        QVERIFY(!view->legendVisible());
        const Hues off = huesIn(view->grabImage(), strip);
        QCOMPARE(off.red + off.blue, 0);
    }

    // The rainbow (blue to red) gave a deuteranope a mid-scale green and a three-quarter yellow
    // about alike (ΔE 20), and its red read darker than its yellow. Along the scale each tenth
    // is lighter than the one below, by as much as a reader tells apart.
    void theHeatMapGrowsLighterAlongItsScale() {
        double previous = -1;
        for (int i = 0; i <= 10; ++i) {
            const double l = lightness(heatMapColour(i / 10.0));
            QVERIFY2(
                l > previous + 4,
                qPrintable(QString("L* %1 at %2 after %3").arg(l).arg(i / 10.0).arg(previous)));
            previous = l;
        }
        QVERIFY(lightness(heatMapColour(0)) < 35 && lightness(heatMapColour(1)) > 85);
    }

    // A frame at rest (1e-6 mm of shape error) filled the scale, and the head and chest were
    // drawn red: the scale reaches the floor given.
    void aHeatMapOfNoiseStaysAtTheBottomOfItsScale() {
        MeshView view;
        const TriMesh mesh = readMesh((folder_ + "/demo/walker.obj").toStdString()).mesh;
        QVERIFY(test::showMesh(view, mesh));
        std::vector<float> noise(mesh.V.rows());
        for (std::size_t i = 0; i < noise.size(); ++i) noise[i] = 4e-6f * float(i % 7) / 6;
        view.setHeatMap(noise, "Shape error (mm)", 2.0);
        QCOMPARE(view.legendTop(), 2.0);
        view.setHeatMap(noise, "Shape error (mm)");
        QVERIFY(view.legendTop() < 1e-5);
    }

    // Mapped green (70, 200, 90) and unmapped orange (240, 130, 40) spheres differed by ΔE 24
    // and 16 for a deuteranope and a protanope, nearly alike in lightness.
    void markerStatesDifferInLightness() {
        const double unmapped = lightness(markerColour(MarkerState::Unmapped));
        const double mapped = lightness(markerColour(MarkerState::Mapped));
        const double selected = lightness(markerColour(MarkerState::Selected));
        const QString said = QString("L* unmapped %1, mapped %2, selected %3")
                                 .arg(unmapped)
                                 .arg(mapped)
                                 .arg(selected);
        QVERIFY2(std::abs(unmapped - mapped) >= 20, qPrintable(said));
        QVERIFY2(std::abs(selected - mapped) >= 15 && std::abs(selected - unmapped) >= 15,
                 qPrintable(said));
    }

    // The legend's top value sat against its colour bar, the "5" of "23.5" touching it: every
    // value label keeps clear of the bar.
    void theLegendsValuesKeepClearOfItsColourBar() {
        MeshView view;
        const TriMesh mesh = readMesh((folder_ + "/demo/walker.obj").toStdString()).mesh;
        QVERIFY(test::showMesh(view, mesh, Eigen::Vector3d::UnitZ()));
        std::vector<float> mm(mesh.V.rows());
        for (Eigen::Index v = 0; v < mesh.V.rows(); ++v) mm[v] = float(v % 97) / 4;
        view.setHeatMap(mm, "Shape error (mm)");
        const QImage image = view.grabImage().convertToFormat(QImage::Format_RGB32);
        const QRect box = view.legendRect();
        QVERIFY2(!box.isEmpty(), "the legend is drawn");
        // The bar: strongly coloured pixels; the labels: light grey ones, as the text is drawn.
        QRect bar;
        QList<QPoint> text;
        for (int y = box.top(); y <= box.bottom(); ++y)
            for (int x = box.left(); x <= box.right(); ++x) {
                const QColor c = image.pixelColor(x, y);
                const int high = std::max({c.red(), c.green(), c.blue()});
                const int low = std::min({c.red(), c.green(), c.blue()});
                if (high - low > 100) bar |= QRect(x, y, 1, 1);
                if (low > 120 && high - low < 40) text << QPoint(x, y);
            }
        QVERIFY2(bar.width() > 5 && bar.height() > 50,
                 qPrintable(QString("bar %1x%2").arg(bar.width()).arg(bar.height())));
        QVERIFY2(text.size() > 50, qPrintable(QString("%1 text pixels").arg(text.size())));
        constexpr int kClearance = 2;  // pixels of background between a label and the bar
        const QRect near = bar.adjusted(-kClearance, -kClearance, kClearance, kClearance);
        int touching = 0;
        for (const QPoint& p : text) touching += near.contains(p);
        QVERIFY2(touching == 0, qPrintable(QString("%1 label pixels within %2 px of the bar (%3, "
                                                   "%4 %5x%6)")
                                               .arg(touching)
                                               .arg(kClearance)
                                               .arg(bar.x())
                                               .arg(bar.y())
                                               .arg(bar.width())
                                               .arg(bar.height())));
    }

    // In a 1024x600 window the legend, 65 % of the view's height down its right edge, lay over
    // the body's arm as the actor walked. It keeps to the top-right corner, under half the view's
    // height, and over none of the walker's vertices at any frame of the demo.
    void theLegendKeepsToACornerBesideTheMeshInASmallWindow() {
        MainWindow window;
        window.setMessageBoxesEnabled(false);
        window.resize(1024, 600);
        QVERIFY(window.openProject(project_));
        QVERIFY(test::showAndWait(window));
        MeshView* view = window.meshView();
        QAction* heatMap = actionNamed(window, "Shape Error &Heat Map");
        QVERIFY(heatMap);
        heatMap->setChecked(true);
        for (int frame = 0; frame < window.timeline()->frameCount(); frame += 6) {
            window.timeline()->scrubTo(frame);
            QVERIFY(QTest::qWaitFor([&] { return window.frameUpToDate() && view->legendVisible(); },
                                    60000));
            const QImage image = view->grabImage();  // renders, placing the legend for this size
            const QRect legend = view->legendRect();
            const QString where = QString("frame %1: the legend at (%2, %3) %4x%5 in a %6x%7 view")
                                      .arg(frame)
                                      .arg(legend.x())
                                      .arg(legend.y())
                                      .arg(legend.width())
                                      .arg(legend.height())
                                      .arg(view->width())
                                      .arg(view->height());
            QVERIFY2(!legend.isEmpty(), qPrintable(where));
            QVERIFY2(legend.top() < view->height() / 20 && legend.height() < view->height() / 2 &&
                         legend.right() > view->width() * 19 / 20,
                     qPrintable(where));
            int covered = 0;
            for (int v = 0; v < view->positions().rows(); ++v)
                covered += legend.contains(view->projectVertex(v));
            if (covered) image.save(folder_ + QString("/legend-frame%1.png").arg(frame));
            QVERIFY2(covered == 0,
                     qPrintable(QString("%1 covers %2 vertices").arg(where).arg(covered)));
            if (frame == 0) image.save(folder_ + "/legend-1024x600.png");
        }
    }

    void markerLabelsDoNotOverlap() {
        const auto shown = test::openShown(project_);
        QVERIFY(shown);
        MainWindow& window = *shown;
        MeshView* view = window.meshView();
        QAction* labels = actionNamed(window, "Marker &Labels");
        QVERIFY(labels);
        labels->setChecked(true);
        // Zoomed out, 39 labels cannot all fit: some must give way.
        QWheelEvent wheel(QPointF(view->rect().center()), view->mapToGlobal(view->rect().center()),
                          {}, QPoint(0, -120), Qt::NoButton, {}, Qt::NoScrollPhase, false);
        for (int k = 0; k < 3; ++k) QCoreApplication::sendEvent(view, &wheel);
        const QImage image = view->grabImage();
        const QList<QRect> boxes = view->labelBoxes();
        QVERIFY2(boxes.size() >= 5, qPrintable(QString("%1 labels drawn").arg(boxes.size())));
        QVERIFY2(view->hiddenLabelCount() > 0, "nothing was crowded: the test shows nothing");
        for (int i = 0; i < boxes.size(); ++i)
            for (int j = i + 1; j < boxes.size(); ++j)
                QVERIFY2(!boxes[i].intersects(boxes[j]),
                         qPrintable(QString("labels %1 and %2 overlap").arg(i).arg(j)));
        // The boxes are where the text is: no label-coloured pixel lies outside them.
        int inside = 0, outside = 0;
        for (int y = 0; y < image.height(); ++y)
            for (int x = 0; x < image.width(); ++x) {
                const QColor c = image.pixelColor(x, y);
                if (c.red() < 245 || c.green() < 245 || c.blue() < 190 || c.blue() > 235) continue;
                const bool in = std::any_of(boxes.begin(), boxes.end(), [&](const QRect& b) {
                    return b.adjusted(-2, -2, 2, 2).contains(x, y);
                });
                ++(in ? inside : outside);
            }
        QVERIFY2(
            inside > 20 && outside == 0,
            qPrintable(
                QString("%1 label pixels inside the boxes, %2 outside").arg(inside).arg(outside)));
    }

  private:
    QString folder_, project_;
};

QTEST_MAIN(ViewOverlayTest)
#include "ViewOverlayTest.moc"
