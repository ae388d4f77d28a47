// PLY before OpenMesh reads it: the header walked word by word as OpenMesh's reader walks it, then
// the body (ascii or binary) checked against what the header announces.
#include <algorithm>
#include <charconv>
#include <cstdint>
#include <cstdio>
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

// Bytes of a PLY value type, 0 for a type OpenMesh does not know.
int plyTypeBytes(const std::string& type) {
    static const std::pair<const char*, int> sizes[] = {
        {"char", 1},  {"uchar", 1},   {"int8", 1},   {"uint8", 1},  {"short", 2}, {"ushort", 2},
        {"int16", 2}, {"uint16", 2},  {"int", 4},    {"uint", 4},   {"int32", 4}, {"uint32", 4},
        {"float", 4}, {"float32", 4}, {"double", 8}, {"float64", 8}};
    for (const auto& [name, bytes] : sizes)
        if (type == name) return bytes;
    return 0;
}

struct PlyProperty {
    int countBytes = 0;  // 0: a single value; else a list whose length takes this many bytes
    int valueBytes = 0;
    bool integer = false;  // ascii: OpenMesh reads the value with >> into an integer
};
struct PlyElement {
    std::string name;
    long long count = 0;
    std::vector<PlyProperty> properties;
};

// The header as OpenMesh's PLY reader walks it, word by word up to the word "end_header". That
// reader never stops on a number it cannot read or a missing end_header: it loops for ever.
struct PlyHeader {
    std::string format;  // ascii, binary_little_endian, binary_big_endian
    std::vector<PlyElement> elements;
    std::vector<std::string> objInfoWords;
};
PlyHeader readPlyHeader(const std::string& path, const std::string& text) {
    size_t at = text.find('\n');
    const auto word = [&] {
        const size_t b = text.find_first_not_of(" \t\r\n\v\f", at);
        if (b == std::string::npos) throw MeshError(path, "PLY header has no end_header");
        at = std::min(text.find_first_of(" \t\r\n\v\f", b), text.size());
        return text.substr(b, at - b);
    };
    const auto bytesOf = [&](const std::string& type) {
        const int bytes = plyTypeBytes(type);
        if (!bytes) throw MeshError(path, "PLY header: unknown type '" + type + "'");
        return bytes;
    };
    PlyHeader header;
    if (word() != "format") throw MeshError(path, "PLY header: no format line after 'ply'");
    header.format = word();
    // OpenMesh reads the version with >> into a float; one that fails (".", or out of a float's
    // range) leaves its stream failed and loops it for ever. Read it the same way.
    const std::string version = word();
    std::istringstream versionStream(version);
    float versionNumber = 0;
    if (version.find_first_not_of("0123456789.") != std::string::npos ||
        !(versionStream >> versionNumber) || versionStream.peek() != EOF)
        throw MeshError(path, "PLY header: version '" + version + "' is not a number");
    std::vector<PlyElement>& elements = header.elements;
    for (std::string w = word(); w != "end_header"; w = word()) {
        if (w == "comment") {
            at = std::min(text.find('\n', at), text.size());
        } else if (w == "obj_info") {
            // Walked on word by word, as OpenMesh does; its words noted to keep it quiet on them.
            header.objInfoWords.push_back(w);
            for (const std::string& t : tokens(text.substr(at, text.find('\n', at) - at)))
                header.objInfoWords.push_back(t);
        } else if (w == "element") {
            const std::string name = word(), count = word();
            if (!isCount(count))
                throw MeshError(path,
                                "PLY header: element " + name + " has no count ('" + count + "')");
            elements.push_back({name, std::stoll(count), {}});
        } else if (w == "property") {
            if (elements.empty())
                throw MeshError(path, "PLY header: a property before any element");
            PlyProperty property;
            std::string type = word();
            if (type == "list") property.countBytes = bytesOf(word()), type = word();
            // OpenMesh takes "name type" as well as "type name" for a single value.
            const std::string name = word();
            const std::string& valueType = plyTypeBytes(type) ? type : name;
            property.valueBytes = bytesOf(valueType);
            property.integer =
                valueType.find("float") == std::string::npos && valueType != "double";
            elements.back().properties.push_back(property);
        }
    }
    return header;
}

// A list's length from the binary body, in the file's byte order.
uint64_t plyListLength(const std::string& data, size_t at, int bytes, bool bigEndian) {
    uint64_t n = 0;
    for (int k = 0; k < bytes; ++k)
        n |= uint64_t(uint8_t(data[at + (bigEndian ? bytes - 1 - k : k)])) << (8 * k);
    if (bytes == 4 && (n & 0x80000000u)) n = ~uint64_t(0);  // a negative int: never enough bytes
    return n;
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

// Ascii PLY as OpenMesh reads it: word after word with >>, whatever the lines. A word that does
// not parse leaves its stream failed and its loops running on stale counts.
void checkPlyAscii(const std::string& path, const std::string& text, size_t bodyStart,
                   const std::vector<PlyElement>& elements) {
    std::vector<std::pair<std::string, int>> words;  // with their line numbers
    int line = static_cast<int>(std::count(text.begin(), text.begin() + bodyStart, '\n'));
    for (const auto& [n, content] : contentLines(text.substr(bodyStart), 0))
        for (const std::string& w : tokens(content)) words.emplace_back(w, line + n);
    size_t k = 0;
    // At an element's first item: a wrong word there most likely belongs to the element before,
    // whose count in the header is too small.
    std::string hint;
    const auto next = [&](const std::string& what, bool integer) {
        if (k >= words.size())
            throw MeshError(path, "file ends in " + what + " (the header announces " +
                                      announced(elements) + ")");
        const auto& [w, n] = words[k++];
        requireNumbers(path, {w}, n, what);
        if (integer && !isInteger(w))
            throw MeshError(path, what + ": '" + w + "' is not an integer" + hint, at(n));
        return w;
    };
    for (size_t ei = 0; ei < elements.size(); ++ei)
        for (long long i = 0; i < elements[ei].count; ++i) {
            const PlyElement& e = elements[ei];
            const std::string what = e.name + " " + std::to_string(i);
            hint = i == 0 && ei > 0
                       ? ": is the header's count of " + elements[ei - 1].name + " elements (" +
                             std::to_string(elements[ei - 1].count) + ") too small?"
                       : "";
            for (const PlyProperty& p : e.properties) {
                long long values = 1;
                if (p.countBytes) {
                    const std::string length = next(what, true);
                    values = std::stoll(length);
                    if (values < 0 || uint64_t(values) > words.size() - k)
                        throw MeshError(
                            path,
                            what + ": list length '" + length + "' is more than the file holds",
                            at(words[k - 1].second));
                }
                for (long long v = 0; v < values; ++v) next(what, p.integer);
            }
        }
    // OpenMesh stops after the announced elements: more after them (a header counting one face
    // too few) would be dropped silently. Comment lines at the end are no data.
    while (k < words.size()) {
        const auto& [w, n] = words[k];
        const bool lineStart = k == 0 || words[k - 1].second != n;
        if (!(lineStart && (w == "comment" || w[0] == '#')))
            throw MeshError(path,
                            "more data than the header announces (" + announced(elements) + "): '" +
                                w + "' follows the last element",
                            at(n));
        while (k < words.size() && words[k].second == n) ++k;
    }
}

// Binary PLY: OpenMesh reads a list length the file cannot hold as that many stale values
// (billions for a 32-bit length), so each element is walked here first.
void checkPlyBinary(const std::string& path, const std::string& text, size_t bodyStart,
                    const std::vector<PlyElement>& elements, bool bigEndian) {
    size_t pos = bodyStart;
    for (const PlyElement& e : elements)
        for (long long i = 0; i < e.count; ++i) {
            const std::string what = e.name + " " + std::to_string(i);
            for (const PlyProperty& p : e.properties) {
                uint64_t values = 1;
                if (p.countBytes) {
                    if (text.size() - pos < size_t(p.countBytes))
                        throw MeshError(path, "file ends in " + what);
                    values = plyListLength(text, pos, p.countBytes, bigEndian);
                    pos += p.countBytes;
                }
                if (values > (text.size() - pos) / p.valueBytes)
                    throw MeshError(path, what + " lists more values than the file holds");
                pos += values * p.valueBytes;
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
    const size_t headerEnd = text.find("end_header");
    if (text.compare(0, 3, "ply") != 0 || headerEnd == std::string::npos)
        throw MeshError(path, "not a PLY file (no 'ply' ... 'end_header' header)");
    const PlyHeader header = readPlyHeader(path, text);
    const std::vector<PlyElement>& elements = header.elements;
    Precheck p;
    p.objInfoWords = header.objInfoWords;
    for (const PlyElement& e : elements) {
        if (e.name == "vertex") p.declaredVertices = e.count;
        if (e.name == "face") p.declaredFaces = e.count;
    }
    // Every element takes at least one byte (binary) or one line (ascii); more than that is a
    // broken header, on which OpenMesh would try to reserve absurd amounts of memory.
    const size_t bodySize = text.size() - headerEnd;
    for (const PlyElement& e : elements)
        if (static_cast<unsigned long long>(e.count) > bodySize)
            throw MeshError(path, "header announces " + std::to_string(e.count) + " " + e.name +
                                      " elements, more than the file holds");
    const size_t newline = text.find('\n', headerEnd);
    const size_t bodyStart = newline == std::string::npos ? text.size() : newline + 1;
    if (header.format == "ascii")
        checkPlyAscii(path, text, bodyStart, elements);
    else
        checkPlyBinary(path, text, bodyStart, elements, header.format == "binary_big_endian");
    return p;
}

}  // namespace boneless::detail::precheck
