#pragma once

#include <string>

#include "boneless/Error.h"

// "--frames A:B": 0-based, B excluded; "A:" and ":B" leave that end at its default. `name` is
// what the error calls it (a manifest's entry says "m.json: takes[2]: 'frames'").
struct FrameRange {
    int first = 0;
    int end = -1;  // -1 = to the last frame
};

inline FrameRange parseFrameRange(const std::string& text, const std::string& name = "--frames") {
    FrameRange range;
    if (text.empty()) return range;
    const auto colon = text.find(':');
    try {
        if (colon == std::string::npos) throw std::invalid_argument("no colon");
        // stoi alone would read "0:810:40" as 0:810; every character must belong to a number.
        auto number = [](const std::string& part) {
            std::size_t used = 0;
            const int value = std::stoi(part, &used);
            if (used != part.size()) throw std::invalid_argument("trailing characters");
            if (value < 0) throw std::invalid_argument("negative");
            return value;
        };
        if (colon > 0) range.first = number(text.substr(0, colon));
        if (colon + 1 < text.size()) range.end = number(text.substr(colon + 1));
    } catch (const std::exception&) {
        throw boneless::Error(name + " expects A:B (0-based, not negative, B excluded), got '" +
                              text + "'");
    }
    return range;
}
