#pragma once
// Shared set-up of the window tests (MeshView, MainWindow, Screenshot, ...): those of
// ModelTestFixtures.h, and a window showing a solved frame.

#include <QtTest>
#include <memory>

#include "ModelTestFixtures.h"
#include "boneless/ui/Document.h"
#include "boneless/ui/MainWindow.h"
#include "boneless/ui/MeshView.h"
#include "boneless/ui/SurfaceFormat.h"

namespace boneless::ui::test {

// Shows the window and waits until the timeline's frame is solved and rendered.
inline bool showAndWait(MainWindow& window, int timeoutMs = 60000) {
    window.show();
    if (!QTest::qWaitForWindowExposed(&window)) return false;
    window.activateWindow();
    // Without a window manager the window may never become active; shortcuts still work.
    (void)QTest::qWaitForWindowActive(&window, 2000);
    return QTest::qWaitFor([&] { return window.frameUpToDate(); }, timeoutMs);
}

// A test's own settings, scratch folder `name` and demo project in it; returns the project.
inline QString demoProjectFor(const QString& name, QString* folder = nullptr) {
    isolate(name);
    const QString dir = freshFolder(name);
    if (folder) *folder = dir;
    return writeDemoProject(dir + "/demo");
}

// A window without message boxes, showing `project` with its frame solved; null if it fails.
inline std::unique_ptr<MainWindow> openShown(const QString& project) {
    auto window = std::make_unique<MainWindow>();
    window->setMessageBoxesEnabled(false);
    if (!window->openProject(project) || !showAndWait(*window)) return nullptr;
    return window;
}

// A bare view of `mesh`, 640 by 480 without multisampling, shown and rendered once (the camera
// is fitted at the first paint).
inline bool showMesh(MeshView& view, const TriMesh& mesh,
                     const Eigen::Vector3d& up = Eigen::Vector3d::UnitY()) {
    view.setMultiSampling(0);
    view.resize(640, 480);
    view.setMesh(mesh, up);
    view.show();
    return QTest::qWaitForWindowExposed(&view) && !view.grabImage().isNull();
}

inline bool waitForFrame(MainWindow& window, int timeoutMs = 60000) {
    return QTest::qWaitFor([&] { return window.frameUpToDate(); }, timeoutMs);
}

// The unmapped vertex farthest from `marker`'s: mapped there, a head marker on a foot pulls the
// fit away, or makes the take unsolvable.
inline int farthestFreeVertex(const Document& d, int marker) {
    const Positions& V = d.mesh().V;
    const Eigen::RowVector3d from = V.row(d.mappedVertex(marker));
    int far = -1;
    for (int v = 0; v < V.rows(); ++v)
        if (d.markerForVertex(v) < 0 &&
            (far < 0 || (V.row(v) - from).norm() > (V.row(far) - from).norm()))
            far = v;
    return far;
}

}  // namespace boneless::ui::test
