#pragma once

// What the format checks of precheckForOpenMesh() share: reading the file, splitting it into
// lines and words, and refusing words that are not the numbers a format wants (with the line).

#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "OpenMeshPrecheck.h"

namespace boneless::detail::precheck {

std::string readAll(const std::string& path);
std::vector<std::string> tokens(const std::string& line);
bool isInteger(std::string_view t);
std::string at(int line);  // "line 12", for messages
// Checks a word, or the words of a line, that must be finite numbers; `what` names the element
// for messages.
void requireNumber(const std::string& path, std::string_view t, int line, const std::string& what);
void requireNumbers(const std::string& path, const std::vector<std::string>& toks, int line,
                    const std::string& what);
// Whether the text starts with a UTF-8 byte-order mark (EF BB BF), and the message refusing it.
bool startsWithByteOrderMark(const std::string& text);
std::string byteOrderMarkRefused(const std::string& format);
// Refuses, naming the format and the extension to give the file, a file whose first bytes say it
// is another format than `format` (its extension's: "OBJ", "PLY", "OFF" or "STL"). Read by the
// wrong parser, such a file said "no faces" or "not a PLY file", which hid the simple fix.
void refuseOtherFormat(const std::string& path, const std::string& data, const std::string& format);
// Content lines (comments and blank lines removed) with their 1-based line numbers.
std::vector<std::pair<int, std::string>> contentLines(const std::string& text, char comment);

Precheck checkPly(const std::string& path);  // PlyPrecheck.cpp

}  // namespace boneless::detail::precheck
