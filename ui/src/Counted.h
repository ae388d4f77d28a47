#pragma once

#include <QLocale>
#include <QString>

namespace boneless::ui {

// "1 marker", "3 markers": tr("%n marker(s)", nullptr, n) reads "3 marker(s)" unless a translation
// gives the plural, and the app ships none. Both forms go through tr() where they are written, so
// a translation still replaces them; %n in them is the count.
inline QString counted(int n, const QString& one, const QString& many) {
    return QString(n == 1 ? one : many).replace(QLatin1String("%n"), QLocale().toString(n));
}

}  // namespace boneless::ui
