#pragma once

#include <QString>

namespace boneless::ui {

// The generated demo (creature mesh, take, map; see boneless/DemoFiles.h) as a project the
// application opens when started without arguments.
namespace DemoProject {

// The per-user folder the demo is written to (QStandardPaths::AppDataLocation + "/demo").
QString defaultFolder();
// Writes the demo files and demo.boneless into `folder` (defaultFolder() when empty) unless
// they are already there, and returns the project's path; empty with *error on failure.
// The project references the demo's correspondence file, unmodified, with no fixed alignment.
QString ensure(const QString& folder = {}, QString* error = nullptr);

}  // namespace DemoProject

}  // namespace boneless::ui
