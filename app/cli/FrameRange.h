#pragma once

#include <string>

#include "boneless/Error.h"

// "--frames A:B": 0-based, B excluded; "A:" and ":B" leave that end at its default.
struct FrameRange {
    int first = 0;
    int end = -1;  // -1 = to the last frame
};

inline FrameRange parseFrameRange(const std::string& text) {
    FrameRange range;
    if (text.empty()) return range;
    const auto colon = text.find(':');
    try {
        if (colon == std::string::npos) throw std::invalid_argument("no colon");
        if (colon > 0) range.first = std::stoi(text.substr(0, colon));
        if (colon + 1 < text.size()) range.end = std::stoi(text.substr(colon + 1));
    } catch (const std::exception&) {
        throw boneless::Error("--frames expects A:B (0-based, B excluded), got '" + text + "'");
    }
    return range;
}
