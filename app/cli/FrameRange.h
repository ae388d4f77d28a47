#pragma once

#include <algorithm>
#include <cstdio>
#include <string>
#include <vector>

#include "boneless/Error.h"
#include "boneless/Text.h"

// "--frames A:B": 0-based, B excluded; "A:" and ":B" leave that end at its default. `name` is
// what the error calls it (a manifest's entry says "m.json: takes[2]: \"frames\""); the text is
// quoted as the choice flags quote theirs: got "0-10".
// `text` as a count or index typed on a command line or in a manifest: digits alone, decimal as
// in JSON (readDecimal), so that " 2", "+2" and "02" are refused as --max-iterations refuses them.
inline bool readWholeNumber(const std::string& text, int& value) {
    double x = 0;
    if (text.empty() || text.find_first_not_of("0123456789") != std::string::npos ||
        boneless::readDecimal(text, x) != boneless::Decimal::Number || x > 2147483647.0)
        return false;
    value = static_cast<int>(x);
    return true;
}

struct FrameRange {
    int first = 0;
    int end = -1;  // -1 = to the last frame
};

// A frame number past int's range is past every take's end: read as the largest, so that
// "0:99999999999" is cut to the take as "0:2147483647" is, not refused as malformed.
inline bool readFrameNumber(const std::string& text, int& value) {
    double x = 0;
    if (text.empty() || text.find_first_not_of("0123456789") != std::string::npos ||
        boneless::readDecimal(text, x) != boneless::Decimal::Number)
        return false;
    value = static_cast<int>(std::min(x, 2147483647.0));
    return true;
}

inline FrameRange parseFrameRange(const std::string& text, const std::string& name = "--frames") {
    FrameRange range;
    if (text.empty()) return range;
    const auto colon = text.find(':');
    const bool ok =
        colon != std::string::npos &&
        (colon == 0 || readFrameNumber(text.substr(0, colon), range.first)) &&
        (colon + 1 == text.size() || readFrameNumber(text.substr(colon + 1), range.end));
    if (!ok)
        throw boneless::Error(name + " expects A:B (0-based, not negative, B excluded), got \"" +
                              text + "\"");
    return range;
}

// `range` (parsed from `text`) within the `frames` frames of `source`: refused when it selects no
// frame, cut at the end with a note when it runs past it, in one wording for solve and batch
// ("--frames 2:100 runs past the end of walk.c3d (6 frames): solving 2:6"; `name` is what the
// range is called, a manifest's "frames" for batch): on stderr as "note: ...", or into `notes`
// for a caller that says it under its own line (batch, which said it as a warning before).
inline FrameRange withinFrames(FrameRange range, const std::string& text, int frames,
                               const std::string& source, const char* doing,
                               std::vector<std::string>* notes = nullptr,
                               const std::string& name = "--frames") {
    if (range.first >= (range.end < 0 ? frames : std::min(range.end, frames)))
        throw boneless::Error("frames " + text + " select no frame of " + source + " (" +
                              boneless::plural(frames, "frame") + ")");
    if (range.end > frames) {
        const std::string note = name + " " + text + " runs past the end of " + source + " (" +
                                 boneless::plural(frames, "frame") + "): " + doing + " " +
                                 std::to_string(range.first) + ":" + std::to_string(frames);
        if (notes)
            notes->push_back(note);
        else
            std::fprintf(stderr, "note: %s\n", note.c_str());
        range.end = frames;
    }
    return range;
}
