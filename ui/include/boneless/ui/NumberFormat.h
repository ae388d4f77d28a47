#pragma once

namespace boneless::ui {

// Must run once the QApplication exists, which set the C locale to the user's (setlocale(LC_ALL,
// "")): numbers are written and read with a decimal point and no group separator in every
// locale, as the CLI, the project files and the maps write them (docs/view.md, "One way of
// writing a number"). In German core's messages said "12,5 Hz", which a project file refuses,
// and the offset box "10,0 mm" beside a residual column of "0.00 mm".
void useOneNumberFormat();

}  // namespace boneless::ui
