#pragma once

namespace boneless::ui {

// Must run before the QApplication exists: VTK's OpenGL2 backend needs a 3.2 core profile with
// depth and alpha, and the view paces itself (swap interval 0).
void setDefaultSurfaceFormat();

}  // namespace boneless::ui
