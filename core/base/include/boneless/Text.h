#pragma once

#include <string>
#include <string_view>
#include <vector>

namespace boneless {

// "a, b, c": how messages list labels, files and choices.
inline std::string joined(const std::vector<std::string>& items,
                          std::string_view separator = ", ") {
    std::string out;
    for (const std::string& item : items) {
        if (!out.empty()) out += separator;
        out += item;
    }
    return out;
}

}  // namespace boneless
