#include "OpenMeshPrecheck.h"

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <regex>
#include <sstream>
#include <vector>

#include "boneless/Error.h"

namespace boneless::detail {

namespace {

std::string readAll(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    if (!in) throw MeshError(path, std::string("cannot open file: ") + std::strerror(errno));
    std::ostringstream s;
    s << in.rdbuf();
    if (in.bad()) throw MeshError(path, "cannot read file");
    return s.str();
}

std::vector<std::string> tokens(const std::string& line) {
    std::vector<std::string> out;
    std::istringstream in(line);
    for (std::string t; in >> t;) out.push_back(t);
    return out;
}

enum class Number { Finite, NonFinite, Invalid };

Number classify(const std::string& t) {
    double v;
    const char* b = t.data() + (!t.empty() && t[0] == '+');
    const auto [end, ec] = std::from_chars(b, t.data() + t.size(), v);
    if (ec != std::errc() || end != t.data() + t.size()) return Number::Invalid;
    return std::isfinite(v) ? Number::Finite : Number::NonFinite;
}

// A token classify() found finite.
double number(const std::string& t) {
    double v = 0;
    std::from_chars(t.data() + (t[0] == '+'), t.data() + t.size(), v);
    return v;
}

bool isInteger(const std::string& t) {
    long long v;
    const auto [end, ec] = std::from_chars(t.data(), t.data() + t.size(), v);
    return ec == std::errc() && end == t.data() + t.size();
}

std::string at(int line) {
    return "line " + std::to_string(line);
}

// Checks the tokens of a line that must all be numbers; `what` names the element for messages.
void requireNumbers(const std::string& path, const std::vector<std::string>& toks, int line,
                    const std::string& what) {
    for (const auto& t : toks) {
        const Number n = classify(t);
        if (n == Number::NonFinite)
            throw MeshError(path, what + " has a non-finite coordinate '" + t + "'", at(line));
        if (n == Number::Invalid)
            throw MeshError(path, what + ": '" + t + "' is not a number", at(line));
    }
}

// Content lines (comments and blank lines removed) with their 1-based line numbers.
std::vector<std::pair<int, std::string>> contentLines(const std::string& text, char comment) {
    std::vector<std::pair<int, std::string>> out;
    std::istringstream in(text);
    int n = 0;
    for (std::string line; std::getline(in, line);) {
        ++n;
        if (comment) line = line.substr(0, line.find(comment));
        // The whitespace tokens() splits on: a line of these alone has no word.
        if (line.find_first_not_of(" \t\r\v\f") != std::string::npos) out.emplace_back(n, line);
    }
    return out;
}

// Binary OFF as OpenMesh reads it: after the keyword line, 32-bit little-endian vertex, face and
// edge counts; per vertex its floats (position, then normal, colour, texture coordinates when the
// keyword's [ST][C][N] prefix says so); per face a corner count and the indices. OpenMesh reads a
// count the file cannot hold as billions of stale corners, so such a count is refused here.
Precheck checkBinaryOff(const std::string& path, const std::string& data,
                        const std::string& keyword) {
    const size_t newline = data.find('\n');
    size_t at = newline == std::string::npos ? data.size() : newline + 1;
    const auto word = [&](const std::string& where) {
        if (data.size() - at < 4) throw MeshError(path, "binary OFF file ends in " + where);
        uint32_t v;
        std::memcpy(&v, data.data() + at, 4);
        at += 4;
        return v;
    };
    Precheck p;
    p.declaredVertices = word("the counts");
    p.declaredFaces = word("the counts");
    word("the counts");
    const std::string prefix = keyword.substr(0, keyword.size() - 3);
    const size_t vertexBytes = 12 + (prefix.compare(0, 2, "ST") == 0 ? 8 : 0) +
                               (prefix.find('C') != std::string::npos ? 12 : 0) +
                               (prefix.find('N') != std::string::npos ? 12 : 0);
    if (uint64_t(p.declaredVertices) > (data.size() - at) / vertexBytes)
        throw MeshError(path, "header announces " + std::to_string(p.declaredVertices) +
                                  " vertices, more than the file holds");
    at += p.declaredVertices * vertexBytes;
    for (long long f = 0; f < p.declaredFaces; ++f) {
        const uint32_t corners = word("face " + std::to_string(f));
        if (corners > (data.size() - at) / 4)
            throw MeshError(path, "face " + std::to_string(f) + " announces " +
                                      std::to_string(corners) +
                                      " corners, more than the file holds");
        at += 4 * size_t(corners);
    }
    return p;
}

Precheck checkOff(const std::string& path) {
    const std::string data = readAll(path);
    const auto lines = contentLines(data, '#');
    if (lines.empty()) throw MeshError(path, "empty OFF file");
    auto head = tokens(lines[0].second);
    const std::string keyword = head[0];
    // [ST][C][N][4][n]OFF, the form OpenMesh parses (found by fuzzing: it read "OFF4OFF" as OFF).
    static const std::regex form("(ST)?C?N?4?n?OFF");
    if (!std::regex_match(keyword, form))
        throw MeshError(path, "not an OFF file: first word is '" + keyword + "'",
                        at(lines[0].first));
    // OpenMesh refuses the dimension-prefixed variants by itself.
    if (keyword.find_first_of("4n") != std::string::npos) return {};
    if (head.size() > 1 && head[1] == "BINARY") return checkBinaryOff(path, data, keyword);
    size_t next = 1;
    std::vector<std::string> counts(head.begin() + 1, head.end());
    if (counts.empty()) {
        if (lines.size() < 2) throw MeshError(path, "OFF header lacks the vertex and face counts");
        counts = tokens(lines[next++].second);
    }
    if (counts.size() < 2 || !isInteger(counts[0]) || !isInteger(counts[1]))
        throw MeshError(path, "OFF header lacks the vertex and face counts",
                        at(lines[next - 1].first));
    Precheck p;
    p.declaredVertices = std::stoll(counts[0]);
    p.declaredFaces = std::stoll(counts[1]);
    PolygonSoup& soup = p.offSoup.emplace();
    for (long long v = 0; v < p.declaredVertices; ++v, ++next) {
        if (next >= lines.size())
            throw MeshError(path, "file ends after " + std::to_string(v) + " of " +
                                      std::to_string(p.declaredVertices) + " vertices");
        const auto toks = tokens(lines[next].second);
        const std::string what = "vertex " + std::to_string(v);
        if (toks.size() < 3)
            throw MeshError(path, what + " has fewer than 3 coordinates", at(lines[next].first));
        requireNumbers(path, toks, lines[next].first, what);
        for (int k = 0; k < 3; ++k) soup.xyz.push_back(number(toks[k]));  // rest: colour, normal
        soup.vertexLine.push_back(lines[next].first);
    }
    for (long long f = 0; f < p.declaredFaces; ++f, ++next) {
        if (next >= lines.size())
            throw MeshError(path, "file ends after " + std::to_string(f) + " of " +
                                      std::to_string(p.declaredFaces) + " faces");
        const auto toks = tokens(lines[next].second);
        const std::string what = "face " + std::to_string(f);
        const int line = lines[next].first;
        if (!isInteger(toks[0]))
            throw MeshError(path, what + ": bad corner count '" + toks[0] + "'", at(line));
        const long long k = std::stoll(toks[0]);
        if (k < 3 || static_cast<long long>(toks.size()) < k + 1)
            throw MeshError(path, what + " lists fewer than 3 corners or fewer than announced",
                            at(line));
        for (long long i = 1; i <= k; ++i) {
            int index;
            const auto [end, ec] =
                std::from_chars(toks[i].data(), toks[i].data() + toks[i].size(), index);
            if (ec != std::errc() || end != toks[i].data() + toks[i].size())
                throw MeshError(path, what + ": '" + toks[i] + "' is not a vertex index", at(line));
            soup.faceIndex.push_back(index);  // range-checked by the mesh reader
        }
        soup.endFace();  // what follows the corners (a colour) is not kept
        soup.faceLine.push_back(line);
    }
    return p;
}

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

// Ascii PLY as OpenMesh reads it: word after word with >>, whatever the lines. A word that does
// not parse leaves its stream failed and its loops running on stale counts.
void checkPlyAscii(const std::string& path, const std::string& text, size_t bodyStart,
                   const std::vector<PlyElement>& elements) {
    std::vector<std::pair<std::string, int>> words;  // with their line numbers
    int line = static_cast<int>(std::count(text.begin(), text.begin() + bodyStart, '\n'));
    for (const auto& [n, content] : contentLines(text.substr(bodyStart), 0))
        for (const std::string& w : tokens(content)) words.emplace_back(w, line + n);
    size_t k = 0;
    const auto next = [&](const std::string& what, bool integer) {
        if (k >= words.size()) throw MeshError(path, "file ends in " + what);
        const auto& [w, n] = words[k++];
        requireNumbers(path, {w}, n, what);
        if (integer && !isInteger(w))
            throw MeshError(path, what + ": '" + w + "' is not an integer", at(n));
        return w;
    };
    for (const PlyElement& e : elements)
        for (long long i = 0; i < e.count; ++i) {
            const std::string what = e.name + " " + std::to_string(i);
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
}

Precheck checkPly(const std::string& path) {
    const std::string text = readAll(path);
    const size_t headerEnd = text.find("end_header");
    if (text.compare(0, 3, "ply") != 0 || headerEnd == std::string::npos)
        throw MeshError(path, "not a PLY file (no 'ply' ... 'end_header' header)");
    const PlyHeader header = readPlyHeader(path, text);
    const std::vector<PlyElement>& elements = header.elements;
    Precheck p;
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

bool isBinaryStl(const std::string& path, const std::string& data) {
    const std::string ext = lowerExtension(path);
    if (ext == "stlb") return true;
    if (ext == "stla" || data.size() < 84) return false;
    uint32_t n;
    std::memcpy(&n, data.data() + 80, 4);  // little-endian, as on every platform we build for
    return data.size() == 84 + 50 * uint64_t(n);  // the rule OpenMesh applies
}

Precheck checkStl(const std::string& path) {
    const std::string data = readAll(path);
    Precheck p;
    p.stl = true;
    if (isBinaryStl(path, data)) {
        uint32_t n = 0;
        if (data.size() >= 84) std::memcpy(&n, data.data() + 80, 4);
        if (data.size() < 84 + 50 * uint64_t(n))
            throw MeshError(path, "binary STL file is truncated");
        for (uint32_t t = 0; t < n; ++t) {
            float xyz[9];
            std::memcpy(xyz, data.data() + 84 + 50 * size_t(t) + 12, sizeof xyz);
            for (float c : xyz)
                if (!std::isfinite(c))
                    throw MeshError(path, "non-finite coordinate", "triangle " + std::to_string(t));
        }
        p.triangles = n;
        return p;
    }
    const auto lines = contentLines(data, 0);
    p.triangles = 0;
    for (size_t i = 0; i < lines.size(); ++i) {
        const auto t = tokens(lines[i].second);
        if (t[0] != "outer" && t[0] != "OUTER") continue;
        const std::string what = "triangle " + std::to_string(p.triangles);
        for (size_t k = 1; k <= 3; ++k) {
            const auto v =
                i + k < lines.size() ? tokens(lines[i + k].second) : std::vector<std::string>{};
            const int line = i + k < lines.size() ? lines[i + k].first : lines[i].first;
            if (v.size() != 4 || (v[0] != "vertex" && v[0] != "VERTEX"))
                throw MeshError(path, what + ": expected 'vertex x y z'", at(line));
            requireNumbers(path, {v.begin() + 1, v.end()}, line, what);
        }
        ++p.triangles;
    }
    return p;
}

}  // namespace

std::string lowerExtension(const std::string& path) {
    const size_t slash = path.find_last_of("/\\");
    const size_t dot = path.find_last_of('.');
    if (dot == std::string::npos || (slash != std::string::npos && dot < slash)) return {};
    std::string ext = path.substr(dot + 1);
    std::transform(ext.begin(), ext.end(), ext.begin(),
                   [](unsigned char c) { return std::tolower(c); });
    return ext;
}

Precheck precheckForOpenMesh(const std::string& path) {
    const std::string ext = lowerExtension(path);
    if (ext == "off") return checkOff(path);
    if (ext == "ply") return checkPly(path);
    if (ext == "stl" || ext == "stla" || ext == "stlb") return checkStl(path);
    throw MeshError(path, "unknown mesh file extension '" + ext + "'",
                    "supported: .obj, .ply, .off, .stl");
}

}  // namespace boneless::detail
