#pragma once
// Shared set-up of the window tests (MeshView, MainWindow, Screenshot): a scratch folder with its
// own demo project, settings kept away from the user's, and a window showing a frame.

#include <QCoreApplication>
#include <QDir>
#include <QStandardPaths>
#include <QString>
#include <QtTest>
#include <memory>

#include "boneless/ui/DemoProject.h"
#include "boneless/ui/MainWindow.h"
#include "boneless/ui/MeshView.h"
#include "boneless/ui/SurfaceFormat.h"

namespace boneless::ui::test {

// A fresh folder BONELESS_TEST_WORK_BASE/<name>.
inline QString freshFolder(const QString& name) {
    QDir dir(QStringLiteral(BONELESS_TEST_WORK_BASE) + "/" + name);
    dir.removeRecursively();
    QDir().mkpath(dir.absolutePath());
    return dir.absolutePath();
}

// Test mode keeps QSettings (recent files, cache size) and per-user folders out of the user's.
inline void isolate(const QString& name) {
    QStandardPaths::setTestModeEnabled(true);
    QCoreApplication::setOrganizationName("BonelessTest");
    QCoreApplication::setApplicationName(name);
}

// The generated demo (the walker, 60 frames, 39 markers all mapped) as a project in `folder`:
// never the user's demo, which may carry their autosaved edits.
inline QString writeDemoProject(const QString& folder) {
    QString error;
    const QString path = DemoProject::write(folder, &error);
    if (path.isEmpty()) qFatal("cannot write the demo: %s", qPrintable(error));
    return path;
}

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

}  // namespace boneless::ui::test
