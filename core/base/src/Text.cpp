#include "boneless/Text.h"

#include <algorithm>
#include <charconv>
#include <limits>

namespace boneless {

// Numbers are written and read by std::to_chars and std::from_chars, which follow no locale:
// printf's and strtod's decimal point is LC_NUMERIC's, a comma in German once a program (the
// application's QApplication) calls setlocale(LC_ALL, "").

std::string shortNumber(double x, int significant) {
    char text[64];
    const auto [end, ec] =
        std::to_chars(text, text + sizeof text, x, std::chars_format::general, significant);
    return ec == std::errc() ? std::string(text, end) : std::string("?");
}

std::string fixedNumber(double x, int decimals) {
    char text[400];  // the largest double in full: 309 digits and the decimals
    const auto [end, ec] =
        std::to_chars(text, text + sizeof text, x, std::chars_format::fixed, decimals);
    return ec == std::errc() ? std::string(text, end) : shortNumber(x);
}

std::string lengthText(double mm) {
    // A take read in the wrong units spans kilometres: "1.54 km", not "1.54e+03 m".
    if (mm >= 1e9) return fixedNumber(mm / 1e6, 0) + " km";
    if (mm >= 1e6) return shortNumber(mm / 1e6, 3) + " km";
    return mm >= 1000.0 ? shortNumber(mm / 1000.0, 3) + " m" : shortNumber(mm, 3) + " mm";
}

namespace {

// Whether the decimal `text`, which a double cannot hold, is too close to 0 (rather than too
// far from it): its first significant digit's place and its exponent say which.
bool belowOne(std::string_view text) {
    const std::size_t e = text.find_first_of("eE");
    const std::string_view mantissa = text.substr(0, e);
    long long exponent = 0;
    if (e != std::string_view::npos) {
        std::string_view digits = text.substr(e + 1);
        const bool negative = !digits.empty() && digits[0] == '-';
        if (!digits.empty() && (digits[0] == '-' || digits[0] == '+')) digits.remove_prefix(1);
        const auto [end, ec] =
            std::from_chars(digits.data(), digits.data() + digits.size(), exponent);
        if (ec == std::errc::result_out_of_range) return negative;
        if (negative) exponent = -exponent;
    }
    const std::size_t point = std::min(mantissa.find('.'), mantissa.size());
    const std::size_t first = mantissa.find_first_of("123456789");
    if (first == std::string_view::npos) return true;
    const long long place = first < point ? static_cast<long long>(point - first) - 1
                                          : -static_cast<long long>(first - point);
    return place + exponent < 0;
}

}  // namespace

Decimal readDecimal(const std::string& text, double& x) {
    const std::size_t digits = !text.empty() && (text[0] == '-' || text[0] == '+') ? 1 : 0;
    if (text.find_first_of("xX") != std::string::npos) return Decimal::NotANumber;  // hexadecimal
    if (text.size() > digits + 1 && text[digits] == '0' && isAsciiDigit(text[digits + 1]))
        return Decimal::NotANumber;  // a leading zero: octal to some
    if (text.size() == digits || (digits == 1 && (text[1] == '-' || text[1] == '+')))
        return Decimal::NotANumber;  // from_chars would take the second sign of "+-1"
    const char* first = text.data() + (text[0] == '+');  // from_chars takes no '+'
    const char* last = text.data() + text.size();
    const auto [end, ec] = std::from_chars(first, last, x);
    if (end != last || ec == std::errc::invalid_argument) return Decimal::NotANumber;
    if (ec == std::errc::result_out_of_range) {
        if (belowOne(std::string_view(text).substr(digits))) return Decimal::Underflow;
        x = text[0] == '-' ? -std::numeric_limits<double>::infinity()
                           : std::numeric_limits<double>::infinity();
    }
    return Decimal::Number;
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
