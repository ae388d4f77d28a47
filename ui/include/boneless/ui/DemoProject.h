#pragma once

#include <QString>

namespace boneless::ui {

// The generated demo (walking body mesh, take, map; see boneless/DemoFiles.h) as a project the
// application opens when started without arguments.
namespace DemoProject {

// The per-user folder the demo is written to (QStandardPaths::AppDataLocation + "/demo").
QString defaultFolder();
// Writes the demo files and demo.boneless into `folder` (defaultFolder() when empty), over
// whatever is there, and returns the project's path; empty with *error on failure. So the demo
// always opens as it was generated; the window never saves into it (edits go to Save As and
// the recovery autosave). The project references the demo's correspondence file, unmodified,
// with no fixed alignment.
QString write(const QString& folder = {}, QString* error = nullptr);
// Whether `path` is the project in defaultFolder().
bool isDemo(const QString& path);

}  // namespace DemoProject

}  // namespace boneless::ui
