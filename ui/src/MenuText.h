#pragma once

#include <QString>

namespace boneless::ui {

// `text` as written where an "&" marks a mnemonic (a menu's action, a buddy label).
inline QString asWritten(QString text) {
    return text.replace('&', "&&");
}

}  // namespace boneless::ui
