#include "OpenMeshPrecheck.h"

#include <algorithm>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <regex>
#include <sstream>
#include <vector>

#include "PrecheckText.h"
#include "boneless/Error.h"
#include "boneless/Text.h"

namespace boneless::detail {

namespace precheck {

namespace {

enum class Number { Finite, NonFinite, Invalid };

Number classify(std::string_view t) {
    double v;
    const char* b = t.data() + (!t.empty() && t[0] == '+');
    const auto [end, ec] = std::from_chars(b, t.data() + t.size(), v);
    if (ec != std::errc() || end != t.data() + t.size()) return Number::Invalid;
    return std::isfinite(v) ? Number::Finite : Number::NonFinite;
}

}  // namespace

std::string readAll(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    if (!in)
        throw MeshError(path,
                        std::string("cannot open the mesh file (") + std::strerror(errno) + ")");
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

bool isInteger(std::string_view t) {
    long long v;
    const auto [end, ec] = std::from_chars(t.data(), t.data() + t.size(), v);
    return ec == std::errc() && end == t.data() + t.size();
}

std::string at(int line) {
    return "line " + std::to_string(line);
}

void requireNumber(const std::string& path, std::string_view t, int line, const std::string& what) {
    const Number n = classify(t);
    if (n == Number::NonFinite)
        throw MeshError(path, what + " has a non-finite coordinate '" + std::string(t) + "'",
                        at(line));
    if (n == Number::Invalid)
        throw MeshError(path, what + ": '" + std::string(t) + "' is not a number", at(line));
}

void requireNumbers(const std::string& path, const std::vector<std::string>& toks, int line,
                    const std::string& what) {
    for (const auto& t : toks) requireNumber(path, t, line, what);
}

bool startsWithByteOrderMark(const std::string& text) {
    return text.compare(0, 3, "\xEF\xBB\xBF") == 0;
}

std::string byteOrderMarkRefused(const std::string& format) {
    return "starts with a UTF-8 byte-order mark (bytes EF BB BF, invisible in most editors), "
           "which " +
           format + " does not allow: save the file without it";
}

namespace {

// A binary STL's size as OpenMesh decides it: 84 bytes and 50 per triangle its header announces.
bool hasBinaryStlSize(const std::string& data) {
    if (data.size() < 84) return false;
    uint32_t n;
    std::memcpy(&n, data.data() + 80, 4);  // little-endian, as on every platform we build for
    return data.size() == 84 + 50 * uint64_t(n);
}

// The format the first bytes show and why, as "an OFF file (it starts with 'OFF')"; format empty
// when they show none. Only the start is read: it decides, and a large file costs nothing more.
struct Sniffed {
    std::string format, looks;
};

Sniffed sniff(const std::string& data) {
    const size_t start = startsWithByteOrderMark(data) ? 3 : 0;
    if (data.compare(start, 4, "ply\n") == 0 || data.compare(start, 5, "ply\r\n") == 0)
        return {"PLY", "a PLY file (it starts with 'ply')"};
    // The text before a binary part (a binary OFF's counts, a binary STL's triangle count).
    const std::string head = data.substr(start, std::min(data.find('\0', start), start + 4096));
    std::vector<std::string> firstWords;
    for (const auto& [n, line] : contentLines(head, '#')) firstWords.push_back(tokens(line)[0]);
    const auto has = [&](const char* word) {
        return std::find(firstWords.begin(), firstWords.end(), word) != firstWords.end();
    };
    if (!firstWords.empty()) {
        const std::string& first = firstWords[0];
        static const std::regex off("(ST)?C?N?4?n?OFF");
        if (std::regex_match(first, off))
            return {"OFF", "an OFF file (it starts with '" + first + "')"};
        if ((first == "solid" || first == "SOLID") && (has("facet") || has("FACET")))
            return {"STL", "an ASCII STL file ('solid' then 'facet normal' lines)"};
        static const std::vector<std::string> objKeys = {"v", "vt", "vn",     "f",     "g",
                                                         "o", "s",  "mtllib", "usemtl"};
        if (std::find(objKeys.begin(), objKeys.end(), first) != objKeys.end() && has("v"))
            return {"OBJ", "an OBJ file ('v' lines)"};
    }
    if (hasBinaryStlSize(data) && data.size() > 84) {
        uint32_t n;
        std::memcpy(&n, data.data() + 80, 4);
        return {"STL", "a binary STL file (84 + 50 x " + std::to_string(n) + " bytes)"};
    }
    return {};
}

}  // namespace

void refuseOtherFormat(const std::string& path, const std::string& data,
                       const std::string& format) {
    // A binary STL's 80-byte header is free text, which may read as any format's start.
    if (format == "STL" && hasBinaryStlSize(data)) return;
    const Sniffed s = sniff(data);
    if (s.format.empty() || s.format == format) return;
    const std::string extension = asciiLower(s.format);
    throw MeshError(path,
                    "looks like " + s.looks + ", not " + format + ": rename it ." + extension);
}

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

}  // namespace precheck

namespace {

using namespace precheck;

// A token classify() found finite.
double number(const std::string& t) {
    double v = 0;
    std::from_chars(t.data() + (t[0] == '+'), t.data() + t.size(), v);
    return v;
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
    // OpenMesh stops after the announced faces: more after them would be dropped silently.
    if (data.find_first_not_of(" \t\r\n\v\f", at) != std::string::npos)
        throw MeshError(path, std::to_string(data.size() - at) + " bytes follow the " +
                                  std::to_string(p.declaredFaces) +
                                  " faces the header announces: does it count too few?");
    return p;
}

Precheck checkOff(const std::string& path) {
    // Text OFF is read here in full, so a byte-order mark (Windows editors write one) is skipped.
    std::string data = readAll(path);
    refuseOtherFormat(path, data, "OFF");
    const bool byteOrderMark = startsWithByteOrderMark(data);
    if (byteOrderMark) data.erase(0, 3);
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
    // OpenMesh reads binary only when "BINARY" follows the keyword after one character on the
    // file's first line, and parses anything else as text; decided its way, or a file this pass
    // took for binary would reach OpenMesh's unchecked text parser (found by fuzzing).
    const size_t k = keyword.size();
    if (data.compare(0, k, keyword) == 0 && data.size() >= k + 7 && data[k] != '\n' &&
        data.compare(k + 1, 6, "BINARY") == 0) {
        if (byteOrderMark) throw MeshError(path, byteOrderMarkRefused("binary OFF"));
        return checkBinaryOff(path, data, keyword);
    }
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
    for (const auto& [count, what] :
         {std::pair{p.declaredVertices, "vertex"}, {p.declaredFaces, "face"}})
        if (count < 0)
            throw MeshError(path,
                            "OFF header: the " + std::string(what) + " count " +
                                std::to_string(count) + " is negative",
                            at(lines[next - 1].first));
    PolygonSoup& soup = p.soup.emplace();
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
        // A bad first face is most likely one more vertex than the header counts.
        const std::string hint = f == 0 ? ": is the header's vertex count (" +
                                              std::to_string(p.declaredVertices) + ") too small?"
                                        : "";
        if (!isInteger(toks[0]))
            throw MeshError(path, what + ": bad corner count '" + toks[0] + "'" + hint, at(line));
        const long long k = std::stoll(toks[0]);
        if (k < 3 || static_cast<long long>(toks.size()) < k + 1)
            throw MeshError(path,
                            what + " lists fewer than 3 corners or fewer than announced" + hint,
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
    if (next < lines.size())
        throw MeshError(path,
                        "more lines than the header announces (" +
                            std::to_string(p.declaredVertices) + " vertices, " +
                            std::to_string(p.declaredFaces) + " faces): '" +
                            tokens(lines[next].second)[0] + "' follows the last face",
                        at(lines[next].first));
    return p;
}

// No NUL and no control character but whitespace: an ASCII STL. A binary one has zeros in its
// triangle count (below 2^24 triangles) and its floats.
bool isText(const std::string& data) {
    return std::none_of(data.begin(), data.end(), [](char c) {
        const auto u = static_cast<unsigned char>(c);
        return (u < 0x20 && !(c >= '\t' && c <= '\r')) || u == 0x7f;  // \t \n \v \f \r
    });
}

bool isBinaryStl(const std::string& path, const std::string& data) {
    const std::string ext = lowerExtension(path);
    if (ext == "stlb") return true;
    if (ext == "stla" || data.size() < 84) return false;
    if (hasBinaryStlSize(data)) return true;  // the rule OpenMesh applies
    // OpenMesh would parse a cut or padded binary file as text and find no faces; not text, it is
    // binary, and checkStl reports it truncated or its extra bytes.
    return !isText(data);
}

Precheck checkStl(const std::string& path) {
    const std::string data = readAll(path);
    refuseOtherFormat(path, data, "STL");
    Precheck p;
    p.stl = true;
    if (isBinaryStl(path, data)) {
        if (data.size() < 84)
            throw MeshError(path, "binary STL file is truncated: " + std::to_string(data.size()) +
                                      " bytes, shorter than the 84-byte header");
        uint32_t n;
        std::memcpy(&n, data.data() + 80, 4);
        if (data.size() < 84 + 50 * uint64_t(n))
            throw MeshError(path, "binary STL file is truncated: the header announces " +
                                      std::to_string(n) + " triangles, the file holds " +
                                      std::to_string((data.size() - 84) / 50));
        // OpenMesh reads a binary file only when its size is exactly this.
        if (data.size() > 84 + 50 * uint64_t(n))
            throw MeshError(
                path,
                "binary STL file has " +
                    plural(static_cast<long long>(data.size() - 84 - 50 * uint64_t(n)), "byte") +
                    " more than the " + std::to_string(n) +
                    " triangles its header announces (84 + 50 x " + std::to_string(n) + " = " +
                    std::to_string(84 + 50 * uint64_t(n)) + " bytes)");
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
    // A file cut inside a facet read as the triangles before the cut, and a map made on that
    // fragment animated it. One that ends after a whole facet without endsolid is let through:
    // some writers leave it out, and nothing tells a cut there from one.
    const auto ends = [&](const char* word) {
        const auto t = lines.empty() ? std::vector<std::string>{} : tokens(lines.back().second);
        return !t.empty() && asciiLower(t[0]) == word;
    };
    if (!ends("endsolid") && !ends("endfacet"))
        throw MeshError(path,
                        "ascii STL file ends without 'endsolid', and not at the end of a facet: "
                        "it looks cut short",
                        lines.empty() ? "" : at(lines.back().first));
    return p;
}

}  // namespace

std::string lowerExtension(const std::string& path) {
    const size_t slash = path.find_last_of("/\\");
    const size_t dot = path.find_last_of('.');
    if (dot == std::string::npos || (slash != std::string::npos && dot < slash)) return {};
    return asciiLower(std::string_view(path).substr(dot + 1));
}

Precheck precheckForOpenMesh(const std::string& path) {
    const std::string ext = lowerExtension(path);
    if (ext == "off") return checkOff(path);
    if (ext == "ply") return precheck::checkPly(path);
    if (ext == "stl" || ext == "stla" || ext == "stlb") return checkStl(path);
    throw MeshError(path, "unknown mesh file extension '" + ext + "'",
                    "supported: .obj, .ply, .off, .stl");
}

}  // namespace boneless::detail
