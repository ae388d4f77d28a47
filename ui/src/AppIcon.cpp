#include "boneless/ui/AppIcon.h"

// Q_INIT_RESOURCE must be called at global scope; it also keeps the linker from dropping the
// resources' object file out of the static library.
static void initResources() {
    Q_INIT_RESOURCE(boneless);
}

namespace boneless::ui {

QIcon applicationIcon() {
    initResources();
    QIcon icon;
    for (int size : {16, 32, 48, 64, 128, 256})
        icon.addFile(QString(":/boneless/icons/boneless-%1.png").arg(size), QSize(size, size));
    return icon;
}

}  // namespace boneless::ui
