#pragma once
// Scratch folders and the generated demo for the model tests (Document, Project, FrameSolver,
// Export). Each test executable gets its own folder: ctest runs them as parallel processes.

#include <QCoreApplication>
#include <QDir>
#include <QStandardPaths>
#include <QString>
#include <QtTest>

#include "boneless/ui/DemoProject.h"
#include "boneless/ui/Document.h"
#include "boneless/ui/Project.h"

namespace boneless::ui::test {

// A fresh folder BONELESS_TEST_WORK_BASE/<name>/<sub>.
inline QString scratchFolder(const QString& name, const QString& sub = {}) {
    QDir dir(QStringLiteral(BONELESS_TEST_WORK_BASE) + "/" + name +
             (sub.isEmpty() ? "" : "/" + sub));
    dir.removeRecursively();
    QDir().mkpath(dir.absolutePath());
    return dir.absolutePath();
}

// Settings and per-user folders of tests stay away from the user's (and from each other's).
inline void isolateSettings(const QString& name) {
    QStandardPaths::setTestModeEnabled(true);
    QCoreApplication::setOrganizationName("BonelessTest");
    QCoreApplication::setApplicationName(name);
}

// The demo project (the walker, 60 frames, 39 markers all mapped) written into `folder`.
inline QString demoProject(const QString& folder) {
    QString error;
    const QString path = DemoProject::write(folder, &error);
    if (path.isEmpty()) qFatal("cannot write the demo: %s", qPrintable(error));
    return path;
}

inline bool loadDemo(Document& document, const QString& folder) {
    QString error;
    if (Project::load(document, demoProject(folder), &error)) return true;
    qWarning("%s", qPrintable(error));
    return false;
}

}  // namespace boneless::ui::test
