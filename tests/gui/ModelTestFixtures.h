#pragma once
// Scratch folders, isolated settings and the generated demo for the GUI tests (the model tests use
// these alone; the window tests add ViewTestSupport.h). Each test executable gets its own folder:
// ctest runs them as parallel processes.

#include <QCoreApplication>
#include <QDir>
#include <QStandardPaths>
#include <QString>
#include <QtTest>

#include "boneless/ui/DemoProject.h"
#include "boneless/ui/Document.h"
#include "boneless/ui/Project.h"

namespace boneless::ui::test {

// A fresh folder BONELESS_TEST_WORK_BASE/<name> (name may hold a sub-folder: "Test/demo").
inline QString freshFolder(const QString& name) {
    QDir dir(QStringLiteral(BONELESS_TEST_WORK_BASE) + "/" + name);
    dir.removeRecursively();
    QDir().mkpath(dir.absolutePath());
    return dir.absolutePath();
}

// Test mode keeps QSettings (recent files, cache size) and per-user folders out of the user's
// (and of the other tests').
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

inline bool loadDemo(Document& document, const QString& folder) {
    QString error;
    if (Project::load(document, writeDemoProject(folder), &error)) return true;
    qWarning("%s", qPrintable(error));
    return false;
}

}  // namespace boneless::ui::test
