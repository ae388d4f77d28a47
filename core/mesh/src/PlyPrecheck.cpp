// PLY, read here in full: the header walked word by word (as OpenMesh's reader walked it, whose
// quirks the fuzzing found), then every element of the body, ascii or binary, in the header's
// types and byte order. OpenMesh misread valid files: integer coordinates in binary, a face's
// properties besides its vertex indices (MeshLab's per-face texture coordinates).
#include <algorithm>
#include <charconv>
#include <climits>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <sstream>
#include <vector>

#include "PrecheckText.h"
#include "boneless/Error.h"

namespace boneless::detail::precheck {

namespace {

bool isCount(const std::string& t) {
    unsigned int v;
    const auto [end, ec] = std::from_chars(t.data(), t.data() + t.size(), v);
    return ec == std::errc() && end == t.data() + t.size();
}

enum class Kind { Signed, Unsigned, Float };

struct PlyType {
    int bytes = 0;  // 0: no PLY type
    Kind kind = Kind::Signed;
};

PlyType plyType(const std::string& type) {
    static const std::pair<const char*, PlyType> types[] = {
        {"char", {1, Kind::Signed}},  {"uchar", {1, Kind::Unsigned}},
        {"int8", {1, Kind::Signed}},  {"uint8", {1, Kind::Unsigned}},
        {"short", {2, Kind::Signed}}, {"ushort", {2, Kind::Unsigned}},
        {"int16", {2, Kind::Signed}}, {"uint16", {2, Kind::Unsigned}},
        {"int", {4, Kind::Signed}},   {"uint", {4, Kind::Unsigned}},
        {"int32", {4, Kind::Signed}}, {"uint32", {4, Kind::Unsigned}},
        {"float", {4, Kind::Float}},  {"float32", {4, Kind::Float}},
        {"double", {8, Kind::Float}}, {"float64", {8, Kind::Float}}};
    for (const auto& [name, t] : types)
        if (type == name) return t;
    return {};
}

struct PlyProperty {
    std::string name;
    int countBytes = 0;  // 0: a single value; else a list whose length takes this many bytes
    Kind countKind = Kind::Unsigned;
    PlyType value;
    std::string valueType;  // as the header names it, for messages
};
struct PlyElement {
    std::string name;
    long long count = 0;
    std::vector<PlyProperty> properties;
};

// The header, walked word by word up to the word "end_header" (OpenMesh's reader, which this
// replaced, looped for ever on a number it could not read or a missing end_header).
struct PlyHeader {
    std::string format;  // ascii, binary_little_endian, binary_big_endian
    std::vector<PlyElement> elements;
    size_t end = 0;                     // just after the word end_header
    std::vector<std::string> warnings;  // header lines not understood, skipped
};
PlyHeader readPlyHeader(const std::string& path, const std::string& text) {
    size_t at = text.find('\n');
    const auto word = [&] {
        const size_t b = text.find_first_not_of(" \t\r\n\v\f", at);
        if (b == std::string::npos) throw MeshError(path, "PLY header has no end_header");
        at = std::min(text.find_first_of(" \t\r\n\v\f", b), text.size());
        return text.substr(b, at - b);
    };
    const auto skipLine = [&] { at = std::min(text.find('\n', at), text.size()); };
    const auto typeOf = [&](const std::string& type) {
        const PlyType t = plyType(type);
        if (!t.bytes) throw MeshError(path, "PLY header: unknown type '" + type + "'");
        return t;
    };
    PlyHeader header;
    if (word() != "format") throw MeshError(path, "PLY header: no format line after 'ply'");
    header.format = word();
    if (header.format != "ascii" && header.format != "binary_little_endian" &&
        header.format != "binary_big_endian")
        throw MeshError(path, "PLY header: format '" + header.format +
                                  "' is none of ascii, binary_little_endian, binary_big_endian");
    const std::string version = word();
    std::istringstream versionStream(version);
    float versionNumber = 0;
    if (version.find_first_not_of("0123456789.") != std::string::npos ||
        !(versionStream >> versionNumber) || versionStream.peek() != EOF)
        throw MeshError(path, "PLY header: version '" + version + "' is not a number");
    std::vector<PlyElement>& elements = header.elements;
    for (std::string w = word(); w != "end_header"; w = word()) {
        if (w == "comment" || w == "obj_info") {
            skipLine();
        } else if (w == "element") {
            const std::string name = word(), count = word();
            if (!isCount(count))
                throw MeshError(path,
                                "PLY header: element " + name + " has no count ('" + count + "')");
            // A second vertex or face element would be dropped: which one is the mesh?
            for (const PlyElement& e : elements)
                if (e.name == name && (name == "vertex" || name == "face"))
                    throw MeshError(path, "PLY header: a second element " + name);
            elements.push_back({name, std::stoll(count), {}});
        } else if (w == "property") {
            if (elements.empty())
                throw MeshError(path, "PLY header: a property before any element");
            PlyProperty property;
            std::string type = word();
            if (type == "list") {
                const PlyType count = typeOf(word());
                if (count.kind == Kind::Float)
                    throw MeshError(path, "PLY header: a list's length of type float");
                property.countBytes = count.bytes;
                property.countKind = count.kind;
                type = word();
            }
            property.valueType = type;
            property.value = typeOf(type);
            property.name = word();
            skipLine();  // no more to a property than its type and name
            for (const PlyProperty& p : elements.back().properties)
                if (p.name == property.name)
                    throw MeshError(path, "PLY header: element " + elements.back().name +
                                              " has two properties " + property.name);
            elements.back().properties.push_back(property);
        } else {
            header.warnings.push_back("PLY header: '" + w +
                                      "' is no PLY keyword; its line skipped");
            skipLine();
        }
    }
    header.end = at;
    return header;
}

// The value of `bytes` bytes at `at` in the file's byte order, as its kind reads it.
double plyBinaryValue(const std::string& data, size_t at, PlyType type, bool bigEndian) {
    uint64_t bits = 0;
    for (int k = 0; k < type.bytes; ++k)
        bits |= uint64_t(uint8_t(data[at + (bigEndian ? type.bytes - 1 - k : k)])) << (8 * k);
    if (type.kind == Kind::Float) {
        if (type.bytes == 4) {
            const uint32_t b = uint32_t(bits);
            float f;
            std::memcpy(&f, &b, 4);
            return f;
        }
        double d;
        std::memcpy(&d, &bits, 8);
        return d;
    }
    if (type.kind == Kind::Signed && (bits >> (8 * type.bytes - 1)) & 1)
        return double(int64_t(bits | (~uint64_t(0) << (8 * type.bytes))));
    return double(bits);
}

// "3426 vertex, 6847 face": what the header announces, for messages.
std::string announced(const std::vector<PlyElement>& elements) {
    std::string s;
    for (const PlyElement& e : elements)
        s += (s.empty() ? "" : ", ") + std::to_string(e.count) + " " + e.name;
    return s.empty() ? "no elements" : s;
}

// Bytes no writer means as data: a newline or spaces after the last element.
bool onlyWhitespace(const std::string& text, size_t from) {
    return text.find_first_not_of(" \t\r\n\v\f", from) == std::string::npos;
}

// What the soup takes of each element: a vertex's x, y and z, a face's vertex indices; every
// other element and property is walked over.
struct PlyLayout {
    int vertexElement = -1, faceElement = -1;
    int xyz[3] = {-1, -1, -1};
    int indices = -1;
};
PlyLayout layoutOf(const std::string& path, const std::vector<PlyElement>& elements) {
    PlyLayout l;
    for (size_t e = 0; e < elements.size(); ++e) {
        const PlyElement& element = elements[e];
        if (element.name == "vertex" && l.vertexElement < 0) {
            l.vertexElement = int(e);
            for (size_t p = 0; p < element.properties.size(); ++p)
                for (int k = 0; k < 3; ++k)
                    if (element.properties[p].name == std::string(1, char('x' + k)) &&
                        !element.properties[p].countBytes)
                        l.xyz[k] = int(p);
            if (element.count > 0 && (l.xyz[0] < 0 || l.xyz[1] < 0 || l.xyz[2] < 0))
                throw MeshError(path, "PLY header: element vertex lacks an x, y or z property");
        } else if (element.name == "face" && l.faceElement < 0) {
            l.faceElement = int(e);
            // vertex_indices, the standard's name, before vertex_index, some writers' name.
            for (const char* name : {"vertex_index", "vertex_indices"})
                for (size_t p = 0; p < element.properties.size(); ++p)
                    if (element.properties[p].countBytes && element.properties[p].name == name)
                        l.indices = int(p);
            if (element.count > 0 && l.indices < 0)
                throw MeshError(path, "PLY header: element face has no vertex_indices list");
            if (l.indices >= 0 && element.properties[l.indices].value.kind == Kind::Float)
                throw MeshError(path, "PLY header: face vertex indices of type '" +
                                          element.properties[l.indices].valueType +
                                          "', not integers");
        }
    }
    return l;
}

// A face's corner as the soup holds it; a value past int's range is refused here, a value in it
// by the mesh reader, which knows the vertex count.
int cornerIndex(const std::string& path, double value, const std::string& what) {
    if (value < double(INT_MIN) || value > double(INT_MAX))
        throw MeshError(
            path, what + ": vertex index " + std::to_string((long long)value) + " is out of range");
    return int(value);
}

// The words of a text from `pos` on, each with its 1-based line, read in place: a scan's ascii
// body holds tens of millions of words, and a copy of each took 6-8 times the file's size.
class Words {
  public:
    Words(const std::string& text, size_t pos)
        : text_(text),
          pos_(pos),
          line_(1 + int(std::count(text.begin(), text.begin() + pos, '\n'))) {}
    // The next word and its line; false at the end of the text.
    bool next(std::string_view& word, int& line) {
        while (pos_ < text_.size() && isSpace(text_[pos_])) line_ += text_[pos_++] == '\n';
        if (pos_ == text_.size()) return false;
        const size_t begin = pos_;
        while (pos_ < text_.size() && !isSpace(text_[pos_])) ++pos_;
        word = std::string_view(text_).substr(begin, pos_ - begin);
        line = line_;
        return true;
    }
    void skipLine() {
        while (pos_ < text_.size() && text_[pos_] != '\n') ++pos_;
    }
    // At least two bytes a word (its characters, a separator) but the last.
    size_t mostWordsLeft() const { return (text_.size() - pos_ + 1) / 2; }

  private:
    // The whitespace of `>>`, as the header's words are split.
    static bool isSpace(char c) { return c == ' ' || (c >= '\t' && c <= '\r'); }
    const std::string& text_;
    size_t pos_;
    int line_;
};

// Ascii PLY: word after word, whatever the lines, as writers put them.
void readPlyAscii(const std::string& path, const std::string& text, size_t bodyStart,
                  const std::vector<PlyElement>& elements, const PlyLayout& layout,
                  PolygonSoup& soup) {
    Words words(text, bodyStart);
    std::string_view w;  // the word last read, and its line
    int n = 0;
    // At an element's first item: a wrong word there most likely belongs to the element before,
    // whose count in the header is too small.
    std::string hint;
    // Within a list, its length and line: the file ending there is that length's doing.
    std::string_view listLength;
    int listLine = 0;
    // The next word's value. A coordinate must be finite; another property (a normal) may be nan,
    // as in binary files.
    const auto next = [&](const std::string& what, bool integer, bool coordinate = false) {
        if (!words.next(w, n)) {
            if (!listLength.empty())
                throw MeshError(path,
                                what + ": list length '" + std::string(listLength) +
                                    "' is more than the file holds",
                                at(listLine));
            throw MeshError(path, "file ends in " + what + " (the header announces " +
                                      announced(elements) + ")");
        }
        if (coordinate || integer) requireNumber(path, w, n, what);
        double v;
        const char* b = w.data() + (w[0] == '+');
        const auto [end, ec] = std::from_chars(b, w.data() + w.size(), v);
        if (ec != std::errc() || end != w.data() + w.size())
            throw MeshError(path, what + ": '" + std::string(w) + "' is not a number" + hint,
                            at(n));
        if (integer && !isInteger(w))
            throw MeshError(path, what + ": '" + std::string(w) + "' is not an integer" + hint,
                            at(n));
        return v;
    };
    for (size_t ei = 0; ei < elements.size(); ++ei)
        for (long long i = 0; i < elements[ei].count && !elements[ei].properties.empty(); ++i) {
            const PlyElement& e = elements[ei];
            const std::string what = e.name + " " + std::to_string(i);
            hint = i == 0 && ei > 0
                       ? ": is the header's count of " + elements[ei - 1].name + " elements (" +
                             std::to_string(elements[ei - 1].count) + ") too small?"
                       : "";
            const bool isVertex = int(ei) == layout.vertexElement;
            const bool isFace = int(ei) == layout.faceElement;
            double xyz[3] = {0, 0, 0};
            for (size_t pi = 0; pi < e.properties.size(); ++pi) {
                const PlyProperty& p = e.properties[pi];
                const bool integer = p.value.kind != Kind::Float;
                if (!p.countBytes) {
                    int c = 0;
                    while (c < 3 && !(isVertex && layout.xyz[c] == int(pi))) ++c;
                    const double v = next(what, integer, c < 3);
                    if (c < 3) xyz[c] = v;
                    continue;
                }
                const long long values = static_cast<long long>(next(what, true));
                if (values < 0)
                    throw MeshError(
                        path, what + ": list length '" + std::string(w) + "' is negative", at(n));
                if (uint64_t(values) > words.mostWordsLeft())
                    throw MeshError(
                        path,
                        what + ": list length '" + std::string(w) + "' is more than the file holds",
                        at(n));
                const bool corners = isFace && layout.indices == int(pi);
                listLength = w;
                listLine = n;
                for (long long v = 0; v < values; ++v) {
                    const double corner = next(what, integer);
                    if (corners) soup.faceIndex.push_back(cornerIndex(path, corner, what));
                }
                listLength = {};
                if (corners) {
                    soup.endFace();
                    soup.faceLine.push_back(n);
                }
            }
            if (isVertex) {
                soup.xyz.insert(soup.xyz.end(), xyz, xyz + 3);
                soup.vertexLine.push_back(n);
            }
        }
    // More after the announced elements (a header counting one face too few) would be dropped
    // silently. Comment lines at the end are no data.
    for (int last = n; words.next(w, n); last = n) {
        if (n == last || !(w == "comment" || w[0] == '#'))
            throw MeshError(path,
                            "more data than the header announces (" + announced(elements) + "): '" +
                                std::string(w) + "' follows the last element",
                            at(n));
        words.skipLine();
    }
}

// Binary PLY, each value in the header's type and the file's byte order. A list length the file
// cannot hold is refused before its values are read.
void readPlyBinary(const std::string& path, const std::string& text, size_t bodyStart,
                   const std::vector<PlyElement>& elements, const PlyLayout& layout, bool bigEndian,
                   PolygonSoup& soup) {
    size_t pos = bodyStart;
    for (size_t ei = 0; ei < elements.size(); ++ei) {
        const PlyElement& e = elements[ei];
        const bool isVertex = int(ei) == layout.vertexElement;
        const bool isFace = int(ei) == layout.faceElement;
        for (long long i = 0; i < e.count && !e.properties.empty(); ++i) {
            const std::string what = e.name + " " + std::to_string(i);
            double xyz[3] = {0, 0, 0};
            for (size_t pi = 0; pi < e.properties.size(); ++pi) {
                const PlyProperty& p = e.properties[pi];
                uint64_t values = 1;
                if (p.countBytes) {
                    if (text.size() - pos < size_t(p.countBytes))
                        throw MeshError(path, "file ends in " + what + " (the header announces " +
                                                  announced(elements) + ")");
                    const double length =
                        plyBinaryValue(text, pos, {p.countBytes, p.countKind}, bigEndian);
                    pos += p.countBytes;
                    if (length < 0)
                        throw MeshError(path, what + ": list length " +
                                                  std::to_string((long long)length) +
                                                  " is negative");
                    values = uint64_t(length);
                }
                if (!p.countBytes && text.size() - pos < size_t(p.value.bytes))
                    throw MeshError(path, "file ends in " + what + " (the header announces " +
                                              announced(elements) + ")");
                if (values > (text.size() - pos) / p.value.bytes)
                    throw MeshError(path, what +
                                              " lists more values than the file holds (the "
                                              "header announces " +
                                              announced(elements) + ")");
                const bool corners = isFace && layout.indices == int(pi);
                for (uint64_t v = 0; v < values; ++v, pos += p.value.bytes) {
                    if (corners)
                        soup.faceIndex.push_back(
                            cornerIndex(path, plyBinaryValue(text, pos, p.value, bigEndian), what));
                    else if (isVertex && !p.countBytes)
                        for (int c = 0; c < 3; ++c)
                            if (layout.xyz[c] == int(pi))
                                xyz[c] = plyBinaryValue(text, pos, p.value, bigEndian);
                }
                if (corners) soup.endFace();
            }
            if (isVertex) soup.xyz.insert(soup.xyz.end(), xyz, xyz + 3);
        }
    }
    if (!onlyWhitespace(text, pos))
        throw MeshError(path, std::to_string(text.size() - pos) +
                                  " bytes follow the elements the header announces (" +
                                  announced(elements) + "): does it count too few?");
}

}  // namespace

Precheck checkPly(const std::string& path) {
    const std::string text = readAll(path);
    refuseOtherFormat(path, text, "PLY");
    if (startsWithByteOrderMark(text)) throw MeshError(path, byteOrderMarkRefused("PLY"));
    if (text.compare(0, 3, "ply") != 0 || text.find("end_header") == std::string::npos)
        throw MeshError(path, "not a PLY file (no 'ply' ... 'end_header' header)");
    const PlyHeader header = readPlyHeader(path, text);
    const std::vector<PlyElement>& elements = header.elements;
    // An element with a property takes at least one byte (binary) or one word (ascii); more than
    // that is a broken header. One without properties takes nothing and is skipped: walking its
    // count made reading quadratic.
    const size_t bodySize = text.size() - header.end;
    for (const PlyElement& e : elements)
        if (!e.properties.empty() && static_cast<unsigned long long>(e.count) > bodySize)
            throw MeshError(path, "header announces " + std::to_string(e.count) + " " + e.name +
                                      " elements, more than the file holds");
    const PlyLayout layout = layoutOf(path, elements);
    const size_t newline = text.find('\n', header.end);
    const size_t bodyStart = newline == std::string::npos ? text.size() : newline + 1;
    Precheck p;
    PolygonSoup& soup = p.soup.emplace();
    soup.warnings = header.warnings;
    if (header.format == "ascii")
        readPlyAscii(path, text, bodyStart, elements, layout, soup);
    else
        readPlyBinary(path, text, bodyStart, elements, layout, header.format == "binary_big_endian",
                      soup);
    return p;
}

}  // namespace boneless::detail::precheck
