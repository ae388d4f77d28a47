#pragma once

#include <QLocale>
#include <QString>
#include <QStringList>

namespace boneless::ui {

// "1 marker", "3 markers": tr("%n marker(s)", nullptr, n) reads "3 marker(s)" unless a translation
// gives the plural, and the app ships none. Both forms go through tr() where they are written, so
// a translation still replaces them; %n in them is the count.
inline QString counted(int n, const QString& one, const QString& many) {
    return QString(n == 1 ? one : many).replace(QLatin1String("%n"), QLocale().toString(n));
}

// "LFWT, RFWT, LBWT, …": the first names of a list too long for the status bar, which cuts off
// what does not fit; the whole list goes where there is room (a tooltip, a box's details).
inline QString firstFew(const QStringList& names, int few = 3) {
    if (names.size() <= few + 1) return names.join(", ");  // "…" would hide no more than a name
    return names.mid(0, few).join(", ") + ", …";
}

}  // namespace boneless::ui
