// boneless: the desktop application.
#include <QApplication>

#include "boneless/ui/SurfaceFormat.h"

int main(int argc, char** argv) {
    boneless::ui::setDefaultSurfaceFormat();
    QApplication app(argc, argv);
    QApplication::setApplicationName("Boneless");
    QApplication::setOrganizationName("Boneless");
    return 0;
}
