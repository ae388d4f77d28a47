// Text in a C3D file has no declared encoding. Old tools wrote Latin-1 (or a Windows code page
// close to it), newer ones UTF-8; the take holds UTF-8 and remembers which one the file used.

#include "C3dDetail.h"
#include "boneless/Text.h"

namespace boneless::c3d_detail {

std::string textFromC3d(std::string_view raw, bool& wasLatin1) {
    if (isUtf8(raw)) return std::string(raw);
    wasLatin1 = true;
    std::string out;
    out.reserve(raw.size() * 2);
    for (char ch : raw) {
        const unsigned char c = static_cast<unsigned char>(ch);
        if (c < 0x80) {
            out.push_back(ch);
        } else {
            out.push_back(static_cast<char>(0xC0 | (c >> 6)));
            out.push_back(static_cast<char>(0x80 | (c & 0x3F)));
        }
    }
    return out;
}

std::string textToC3d(std::string_view utf8, C3dTextEncoding encoding) {
    if (encoding == C3dTextEncoding::Utf8) return std::string(utf8);
    std::string out;
    out.reserve(utf8.size());
    for (std::size_t i = 0; i < utf8.size();) {
        const std::size_t n = utf8SequenceAt(utf8, i);
        const auto c = static_cast<unsigned char>(utf8[i]);
        if (n == 1) {
            out.push_back(utf8[i]);
        } else if (n == 2 && c <= 0xC3) {  // U+0080..U+00FF
            const auto c2 = static_cast<unsigned char>(utf8[i + 1]);
            out.push_back(static_cast<char>(((c & 0x03) << 6) | (c2 & 0x3F)));
        } else {
            out.push_back('?');  // not representable in Latin-1 (or not UTF-8 at all)
        }
        i += n ? n : 1;
    }
    return out;
}

}  // namespace boneless::c3d_detail
