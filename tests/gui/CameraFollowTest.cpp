// Camera follow: an energetic take (the demo walker sprinting, leaping, swaying and turning back)
// never leaves the screen, the camera does not shake with the body's sway, and View → Follow the
// Mesh is on by default and kept in the project.
#include <QAction>
#include <QtTest>
#include <cmath>

#include "ViewTestSupport.h"
#include "boneless/MeshReader.h"
#include "boneless/ui/MeshView.h"

using namespace boneless;
using namespace boneless::ui;

namespace {

// The demo walker (z up, metres) carried 6 m along x and back, with leaps of 30 cm and a quick
// sway of 5 cm (a period of 8 frames), far more ground than the view shows at once.
std::vector<Positions> energeticTake(const Positions& rest) {
    std::vector<Positions> frames;
    const int n = 120;
    for (int t = 0; t < n; ++t) {
        const double s = double(t) / (n - 1);
        const double x = 6.0 * std::sin(M_PI * s) + 0.05 * std::sin(2 * M_PI * t / 8.0);
        const double y = 1.5 * std::sin(2 * M_PI * s);
        const double z = 0.3 * std::abs(std::sin(6 * M_PI * s));
        Positions V = rest;
        V.rowwise() += Eigen::RowVector3d(x, y, z);
        frames.push_back(V);
    }
    return frames;
}

Eigen::Vector3d centroidOf(const Positions& V) {
    return V.colwise().mean().transpose();
}

// Whether a point appears inside the widget, projected with the camera state alone (VTK's
// vertical view angle), so the check does not lean on the code under test.
bool insideView(MeshView& view, const Eigen::Vector3d& p) {
    const QVariantMap camera = view.cameraState();
    auto vec = [&](const char* key) {
        const QVariantList l = camera.value(key).toList();
        return Eigen::Vector3d(l[0].toDouble(), l[1].toDouble(), l[2].toDouble());
    };
    const Eigen::Vector3d eye = vec("position"), focal = vec("focal_point"), up = vec("view_up");
    const Eigen::Vector3d forward = (focal - eye).normalized();
    const Eigen::Vector3d right = forward.cross(up).normalized();
    const Eigen::Vector3d trueUp = right.cross(forward);
    const Eigen::Vector3d d = p - eye;
    const double depth = d.dot(forward);
    if (depth <= 0) return false;
    const double halfHeight = std::tan(0.5 * camera.value("view_angle").toDouble() * M_PI / 180);
    const double aspect = double(view.width()) / view.height();
    const double y = d.dot(trueUp) / depth / halfHeight, x = d.dot(right) / depth / halfHeight;
    return std::abs(y) < 1 && std::abs(x) < aspect;
}

}  // namespace

class CameraFollowTest : public QObject {
    Q_OBJECT
  public:
    static void initMain() { setDefaultSurfaceFormat(); }

  private slots:
    void initTestCase() { project_ = test::demoProjectFor("CameraFollowTest", &folder_); }

    void followIsOnByDefaultAndAProjectKeepsItTurnedOff() {
        const QString saved = folder_ + "/still.boneless";
        {
            const auto window = test::openShown(project_);
            QVERIFY(window);
            auto* follow = window->findChild<QAction*>("actionFollow");
            QVERIFY(follow && follow->isChecked());
            QVERIFY(window->meshView()->cameraFollow());
            follow->setChecked(false);
            QVERIFY(!window->meshView()->cameraFollow());
            QVERIFY(window->saveProjectAs(saved));
        }
        const auto reopened = test::openShown(saved);
        QVERIFY(reopened);
        QVERIFY(!reopened->findChild<QAction*>("actionFollow")->isChecked());
        QVERIFY(!reopened->meshView()->cameraFollow());
    }

    void anEnergeticTakeStaysOnScreenOnlyWithFollow() {
        const TriMesh walker = readMesh((folder_ + "/demo/walker.obj").toStdString()).mesh;
        const std::vector<Positions> take = energeticTake(walker.V);
        for (const bool follow : {false, true}) {
            MeshView view;
            QVERIFY(test::showMesh(view, walker, Eigen::Vector3d::UnitZ()));
            view.setCameraFollow(follow);
            view.setPlaying(true);
            int outside = 0;
            for (const Positions& V : take) {
                view.setPositions(V);
                outside += !insideView(view, centroidOf(V));
            }
            if (follow)
                QCOMPARE(outside, 0);
            else
                QVERIFY2(outside > 10, "the take is not energetic enough to show anything");
        }
    }

    void theCameraDoesNotShakeWithTheBody() {
        const TriMesh walker = readMesh((folder_ + "/demo/walker.obj").toStdString()).mesh;
        const std::vector<Positions> take = energeticTake(walker.V);
        MeshView view;
        QVERIFY(test::showMesh(view, walker, Eigen::Vector3d::UnitZ()));
        view.setPlaying(true);
        // Jitter is what changes direction from frame to frame: the sum of |second differences|.
        auto roughness = [](const std::vector<Eigen::Vector3d>& path) {
            double sum = 0;
            for (std::size_t i = 2; i < path.size(); ++i)
                sum += (path[i] - 2 * path[i - 1] + path[i - 2]).norm();
            return sum;
        };
        std::vector<Eigen::Vector3d> body, camera;
        double lowest = 1e9, highest = -1e9;
        for (const Positions& V : take) {
            view.setPositions(V);
            body.push_back(centroidOf(V));
            camera.push_back(view.focalPoint());
            lowest = std::min(lowest, view.focalPoint().z());
            highest = std::max(highest, view.focalPoint().z());
        }
        QVERIFY2(
            roughness(camera) < 0.5 * roughness(body),
            qPrintable(QString("camera %1, body %2").arg(roughness(camera)).arg(roughness(body))));
        // The leaps are not followed up and down: the floor stays put on screen.
        QVERIFY2(highest - lowest < 1e-9,
                 qPrintable(QString("camera rose %1").arg(highest - lowest)));

        // Paused, the camera stays where it is for a step within the screen...
        view.setPlaying(false);
        const Eigen::Vector3d paused = view.focalPoint();
        Positions V = take.back();
        V.col(0).array() += 0.2;
        view.setPositions(V);
        QVERIFY((view.focalPoint() - paused).norm() < 1e-12);
        // ...and moves only to keep the body on screen for a jump off it.
        V.col(0).array() += 8.0;
        view.setPositions(V);
        QVERIFY(insideView(view, centroidOf(V)));
        QVERIFY((view.focalPoint() - paused).norm() < 8.0);
    }

    // Double-click a marker (the camera zooms onto it), then step a frame: paused, the camera is
    // the user's, and it jumped back to the hips, which the zoom had put off the middle.
    void pausedACameraZoomedOntoAMarkerStaysThereForTheNextFrame() {
        const TriMesh walker = readMesh((folder_ + "/demo/walker.obj").toStdString()).mesh;
        MeshView view;
        QVERIFY(test::showMesh(view, walker, Eigen::Vector3d::UnitZ()));
        int foot = 0;
        for (int v = 0; v < walker.V.rows(); ++v)
            if (walker.V(v, 2) < walker.V(foot, 2)) foot = v;
        const Eigen::Vector3d zoomed = walker.V.row(foot).transpose();
        view.frame(zoomed);
        QVERIFY(!insideView(view, centroidOf(walker.V)));
        Positions V = walker.V;
        for (int step = 0; step < 2; ++step) {  // the next frames: the body a step on each
            V.col(0).array() += 0.02;
            view.setPositions(V);
            QVERIFY2((view.focalPoint() - zoomed).norm() < 1e-9,
                     qPrintable(QString("the camera moved %1 at step %2")
                                    .arg((view.focalPoint() - zoomed).norm())
                                    .arg(step)));
        }
        // Playing, it follows the body as before.
        view.setPlaying(true);
        V.col(0).array() += 0.02;
        view.setPositions(V);
        QVERIFY((view.focalPoint() - zoomed).norm() > 1e-6);
    }

    // Paused, as when scrubbing to the deepest pose: the centroid stays near the middle, but a leg
    // swung out sideways leaves the view unless the camera makes room for it.
    void aLegSwungOutComesOnScreenWhileTheBodyFits() {
        const TriMesh walker = readMesh((folder_ + "/demo/walker.obj").toStdString()).mesh;
        for (const bool follow : {false, true}) {
            MeshView view;
            QVERIFY(test::showMesh(view, walker, Eigen::Vector3d::UnitZ()));
            view.setCameraFollow(follow);
            const QVariantList l = view.cameraState().value("view_up").toList();
            const Eigen::Vector3d up(l[0].toDouble(), l[1].toDouble(), l[2].toDouble());
            const Eigen::Vector3d forward =
                (view.focalPoint() -
                 [&] {
                     const QVariantList p = view.cameraState().value("position").toList();
                     return Eigen::Vector3d(p[0].toDouble(), p[1].toDouble(), p[2].toDouble());
                 }())
                    .normalized();
            const Eigen::Vector3d right = forward.cross(up).normalized();
            const Eigen::Vector3d c = centroidOf(walker.V);
            const double height = walker.V.col(2).maxCoeff() - walker.V.col(2).minCoeff();
            Positions V = walker.V;
            int swung = 0;
            for (int v = 0; v < V.rows(); ++v)
                if (V(v, 2) < walker.V.col(2).minCoeff() + 0.35 * height &&
                    (V.row(v).transpose() - c).dot(right) > 0) {
                    V.row(v) += 1.1 * height * right.transpose();
                    ++swung;
                }
            QVERIFY(swung > 0);
            view.setPositions(V);
            int outside = 0;
            for (int v = 0; v < V.rows(); ++v) outside += !insideView(view, V.row(v).transpose());
            if (follow)
                QCOMPARE(outside, 0);
            else
                QVERIFY2(outside > 0, "the leg did not leave the view: swing it farther");
        }
    }

  private:
    QString folder_, project_;
};

QTEST_MAIN(CameraFollowTest)
#include "CameraFollowTest.moc"
