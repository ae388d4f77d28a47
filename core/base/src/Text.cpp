#include "boneless/Text.h"

#include <cerrno>
#include <cstdio>
#include <cstdlib>

namespace boneless {

std::string shortNumber(double x) {
    char text[32];  // "%g" of a double takes at most 13 characters ("-1.79769e+308")
    std::snprintf(text, sizeof text, "%g", x);
    return text;
}

std::string lengthText(double mm) {
    char text[48];
    if (mm >= 1000.0)
        std::snprintf(text, sizeof text, "%.3g m", mm / 1000.0);
    else
        std::snprintf(text, sizeof text, "%.3g mm", mm);
    return text;
}

Decimal readDecimal(const std::string& text, double& x) {
    const std::size_t digits = !text.empty() && (text[0] == '-' || text[0] == '+') ? 1 : 0;
    if (text.find_first_of("xX") != std::string::npos) return Decimal::NotANumber;  // hexadecimal
    if (text.size() > digits + 1 && text[digits] == '0' && isAsciiDigit(text[digits + 1]))
        return Decimal::NotANumber;  // a leading zero: octal to some
    if (text.empty() || isAsciiSpace(text[0])) return Decimal::NotANumber;
    char* end = nullptr;
    errno = 0;
    x = std::strtod(text.c_str(), &end);
    if (end != text.c_str() + text.size()) return Decimal::NotANumber;
    return errno == ERANGE && x == 0 ? Decimal::Underflow : Decimal::Number;
}

std::size_t utf8SequenceAt(std::string_view s, std::size_t i) {
    const auto at = [&](std::size_t k) { return static_cast<unsigned char>(s[k]); };
    const unsigned char c = at(i);
    if (c < 0x80) return 1;
    std::size_t n;
    unsigned char lo = 0x80, hi = 0xBF;
    if (c >= 0xC2 && c <= 0xDF) {
        n = 2;
    } else if (c >= 0xE0 && c <= 0xEF) {
        n = 3;
        if (c == 0xE0) lo = 0xA0;
        if (c == 0xED) hi = 0x9F;
    } else if (c >= 0xF0 && c <= 0xF4) {
        n = 4;
        if (c == 0xF0) lo = 0x90;
        if (c == 0xF4) hi = 0x8F;
    } else {
        return 0;
    }
    if (i + n > s.size()) return 0;
    if (at(i + 1) < lo || at(i + 1) > hi) return 0;
    for (std::size_t k = 2; k < n; ++k)
        if (at(i + k) < 0x80 || at(i + k) > 0xBF) return 0;
    return n;
}

bool isUtf8(std::string_view s) {
    for (std::size_t i = 0; i < s.size();) {
        const std::size_t n = utf8SequenceAt(s, i);
        if (n == 0) return false;
        i += n;
    }
    return true;
}

std::string validUtf8(std::string_view s) {
    std::string out;
    out.reserve(s.size());
    for (std::size_t i = 0; i < s.size();) {
        if (const std::size_t n = utf8SequenceAt(s, i)) {
            out.append(s.substr(i, n));
            i += n;
        } else {
            const auto c = static_cast<unsigned char>(s[i++]);  // U+0080..U+00FF
            out.push_back(static_cast<char>(0xC0 | (c >> 6)));
            out.push_back(static_cast<char>(0x80 | (c & 0x3F)));
        }
    }
    return out;
}

}  // namespace boneless
