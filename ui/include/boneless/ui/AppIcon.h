#pragma once

#include <QIcon>

namespace boneless::ui {

// The application's icon (resources/boneless.svg rendered at 16 to 256 pixels), for the windows
// and the About box.
QIcon applicationIcon();

}  // namespace boneless::ui
