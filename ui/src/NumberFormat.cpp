#include "boneless/ui/NumberFormat.h"

#include <QLocale>
#include <clocale>

namespace boneless::ui {

void useOneNumberFormat() {
    // The C library's decimal point, which printf and strtod follow (core, OpenMesh, VTK).
    std::setlocale(LC_NUMERIC, "C");
    // Qt's: spin boxes, counts and QLocale().toString. Dates keep the user's (QLocale::system()).
    QLocale numbers = QLocale::c();
    numbers.setNumberOptions(QLocale::OmitGroupSeparator | QLocale::RejectGroupSeparator);
    QLocale::setDefault(numbers);
}

}  // namespace boneless::ui
