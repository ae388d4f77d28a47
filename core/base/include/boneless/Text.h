#pragma once

#include <cstddef>
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

// "1 frame", "2 frames": a count and its noun as messages give them; `words` for an irregular
// plural ("vertices").
inline std::string plural(long long n, const std::string& word, const std::string& words = {}) {
    return std::to_string(n) + " " + (n == 1 ? word : words.empty() ? word + "s" : words);
}

// ASCII's classes and case, whatever the process's locale: C's isalpha and tolower follow
// setlocale, which QApplication calls with the user's, and in Turkish tolower('I') is 'I' (its
// lower case is a dotless i), which made a take's units "IN" no unit at all.
constexpr bool isAsciiDigit(char c) {
    return c >= '0' && c <= '9';
}
constexpr bool isAsciiUpper(char c) {
    return c >= 'A' && c <= 'Z';
}
constexpr bool isAsciiLower(char c) {
    return c >= 'a' && c <= 'z';
}
constexpr bool isAsciiAlpha(char c) {
    return isAsciiUpper(c) || isAsciiLower(c);
}
constexpr bool isAsciiSpace(char c) {
    return c == ' ' || c == '\t' || c == '\n' || c == '\r' || c == '\f' || c == '\v';
}
constexpr char asciiLower(char c) {
    return isAsciiUpper(c) ? char(c - 'A' + 'a') : c;
}
constexpr char asciiUpper(char c) {
    return isAsciiLower(c) ? char(c - 'a' + 'A') : c;
}
inline std::string asciiLower(std::string_view text) {
    std::string out(text);
    for (char& c : out) c = asciiLower(c);
    return out;
}

// `x` as messages give a number: printf's %g, six significant digits, an exponent for the tiny
// and the huge ("3", "0.1", "1e-07", "1e+20", "nan", "inf"). The mesh reader, the take options and
// the C3D reader each had their own copy. With a decimal point in every locale, as JSON and
// the CLI write it (setlocale made it "12,5" in German): this, fixedNumber and readDecimal are
// how core writes and reads a number.
std::string shortNumber(double x, int significant = 6);

// `x` with `decimals` digits after the point, printf's %.*f in the "C" locale: "2.5 GB".
std::string fixedNumber(double x, int decimals);

// A length in millimetres as messages give it, three significant digits: "1.54 mm", "1.8 m",
// "1.54 km"; never an exponent.
std::string lengthText(double mm);

// `text` as a number the way a command line gives one: decimal, as in JSON. NotANumber for
// anything else, "0x10" (which strtod reads as 16) and "010" (octal 8 to C, 10 to strtod)
// included; "nan" and "inf" are numbers, for a range to refuse by name. Underflow for a number
// too close to 0 for a double ("1e-400"), which is no 0 either: a message says kUnderflowNote.
enum class Decimal { Number, NotANumber, Underflow };
Decimal readDecimal(const std::string& text, double& x);
inline constexpr const char* kUnderflowNote =
    "too close to 0 to be held (it underflows): give 0 or at least 1e-307";

// Length of the well-formed UTF-8 sequence at text[i] (RFC 3629: no overlongs, no surrogates,
// nothing past U+10FFFF), 0 when there is none.
std::size_t utf8SequenceAt(std::string_view text, std::size_t i);

bool isUtf8(std::string_view text);

// `text` as UTF-8, which JSON holds and nothing else: its UTF-8 as it is, every other byte read as
// Latin-1. A file name from a Latin-1 system ("caf\xe9.c3d") is recorded as "café.c3d" where a
// JSON writer would have thrown.
std::string validUtf8(std::string_view text);

}  // namespace boneless
