// Own OBJ parser: OpenMesh's OBJ reader cannot select a group, builds topology while reading
// (duplicating vertices at non-manifold spots) and is slower on large files.

#include <algorithm>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <map>
#include <string_view>
#include <unordered_map>

#include "PolygonSoup.h"
#include "PrecheckText.h"
#include "boneless/Error.h"

namespace boneless::detail {

namespace {

std::string slurp(const std::string& path) {
    std::FILE* f = std::fopen(path.c_str(), "rb");
    if (!f)
        throw MeshError(path,
                        std::string("cannot open the mesh file (") + std::strerror(errno) + ")");
    std::string data;
    char buf[1 << 16];
    size_t n;
    while ((n = std::fread(buf, 1, sizeof buf, f)) > 0) data.append(buf, n);
    const bool failed = std::ferror(f);
    std::fclose(f);
    if (failed) throw MeshError(path, "cannot read file");
    return data;
}

bool isBlank(char c) {
    return c == ' ' || c == '\t' || c == '\r' || c == '\f' || c == '\v';
}

// Walks logical lines: a line ending in '\' continues on the next physical line. Lines end in
// LF, CR LF or a lone CR (old Mac files); a UTF-8 byte-order mark (Windows editors) is skipped.
class LineReader {
  public:
    explicit LineReader(const std::string& data)
        : data_(data), pos_(precheck::startsWithByteOrderMark(data) ? 3 : 0) {}

    bool next(std::string_view& line, int& lineNumber) {
        if (pos_ >= data_.size()) return false;
        lineNumber = ++physical_;
        std::string_view part = physicalLine();
        if (!continues(part)) {
            line = part;
            return true;
        }
        joined_.clear();
        while (continues(part) && pos_ < data_.size()) {
            joined_.append(trimmedRight(part).substr(0, trimmedRight(part).size() - 1));
            joined_.push_back(' ');
            ++physical_;
            part = physicalLine();
        }
        joined_.append(part);
        line = joined_;
        return true;
    }

  private:
    std::string_view physicalLine() {
        size_t end = pos_;
        while (end < data_.size() && data_[end] != '\n' && data_[end] != '\r') ++end;
        std::string_view part(data_.data() + pos_, end - pos_);
        pos_ = end + (data_.compare(end, 2, "\r\n") == 0 ? 2 : 1);
        return part;
    }
    static std::string_view trimmedRight(std::string_view s) {
        while (!s.empty() && isBlank(s.back())) s.remove_suffix(1);
        return s;
    }
    static bool continues(std::string_view s) {
        s = trimmedRight(s);
        return !s.empty() && s.back() == '\\';
    }

    const std::string& data_;
    size_t pos_;
    int physical_ = 0;
    std::string joined_;
};

// A name is the rest of the line, as Blender reads it: "usemtl Material 1" is one material, and
// "o Walker Body" and "o Walker Prop" two objects (cut at the space, they were one).
std::string_view wholeName(std::string_view rest) {
    while (!rest.empty() && isBlank(rest.front())) rest.remove_prefix(1);
    while (!rest.empty() && isBlank(rest.back())) rest.remove_suffix(1);
    return rest;
}

std::string_view nextToken(std::string_view& rest) {
    size_t i = 0;
    while (i < rest.size() && isBlank(rest[i])) ++i;
    size_t j = i;
    while (j < rest.size() && !isBlank(rest[j])) ++j;
    std::string_view token = rest.substr(i, j - i);
    rest.remove_prefix(j);
    if (!token.empty() && token[0] == '#') {  // trailing comment
        rest = {};
        return {};
    }
    return token;
}

// "1#c": a comment straight after a number ends the line there, as one after a space does.
std::string_view beforeComment(std::string_view t, std::string_view& rest) {
    const size_t hash = t.find('#');
    if (hash == std::string_view::npos) return t;
    rest = {};
    return t.substr(0, hash);
}

// Where from_chars may start: after a '+' sign, which it does not take ("+-1" stays refused).
const char* afterPlus(std::string_view t) {
    return t.data() + (t.size() > 1 && t[0] == '+' && t[1] != '-');
}

bool parseDouble(std::string_view t, double& value) {
    t.remove_prefix(size_t(afterPlus(t) - t.data()));
    const auto [end, ec] = std::from_chars(t.data(), t.data() + t.size(), value);
    return ec == std::errc() && end == t.data() + t.size();
}

class ObjParser {
  public:
    ObjParser(std::string path, std::string group)
        : path_(std::move(path)), group_(std::move(group)) {}

    PolygonSoup parse(bool namesOnly) {
        const std::string data = slurp(path_);
        precheck::refuseOtherFormat(path_, data, "OBJ");
        // A NUL byte is in no text file: a binary file (an STL, a .blend) named .obj was read as
        // lines of unknown keywords and said "no faces".
        if (const std::size_t nul = data.find('\0'); nul != std::string::npos)
            throw MeshError(path_,
                            "is not a text OBJ file: byte " + std::to_string(nul) +
                                " is a NUL, which no text holds (a binary file named .obj?)");
        LineReader lines(data);
        std::string_view line;
        while (lines.next(line, line_)) {
            std::string_view rest = line;
            const std::string_view key = nextToken(rest);
            if (key == "v") {
                if (!namesOnly) vertex(rest);
                ++vertexCount_;
            } else if (key == "vt") {
                if (!namesOnly) textureCoordinate(rest);
                ++uvCount_;
            } else if (key == "usemtl") {
                material_ = useMaterial(rest);
            } else if (key == "mtllib") {
                materialLibraries(rest);
            } else if (key == "f") {
                if (namesOnly)
                    countGroupFace(rest);
                else if (selected_)
                    face(rest);
                ++fileFaces_;
            } else if (key == "g") {
                currentG_.clear();
                for (auto t = nextToken(rest); !t.empty(); t = nextToken(rest)) {
                    currentG_.emplace_back(t);
                    addName(currentG_.back());
                }
                updateSelected();
            } else if (key == "o") {
                currentO_ = std::string(wholeName(rest));
                if (!currentO_.empty()) addName(currentO_);
                updateSelected();
            } else if (!key.empty() && !isKnownIgnored(key)) {
                ++unknown_[std::string(key)];
            }
        }
        uvBroken_ = uvBroken_ || std::any_of(soup_.uvOf.begin(), soup_.uvOf.end(),
                                             [&](int t) { return t >= uvCount_; });
        if (uvBroken_) {
            soup_.uv.clear();
            soup_.uvOf.clear();
            soup_.warnings.push_back(
                "texture coordinates ignored: a \"vt\" line or a face's reference to one is "
                "unusable");
        }
        for (const auto& [key, count] : unknown_)
            soup_.warnings.push_back("ignored " + std::to_string(count) +
                                     " OBJ line(s) starting with '" + key + "'");
        if (!group_.empty() && std::find(names_.begin(), names_.end(), group_) == names_.end())
            throw MeshError(path_, "no group named '" + group_ + "'", "groups: " + nameList());
        return std::move(soup_);
    }

    const std::vector<std::string>& names() const { return names_; }

    // Per name, the distinct file vertices its faces use (what readMesh of that group keeps).
    std::vector<int> groupVertexCounts() const {
        std::vector<int> counts(names_.size(), 0), seenBy(size_t(vertexCount_), -1);
        for (size_t g = 0; g < groupCorners_.size(); ++g)
            for (int v : groupCorners_[g])
                if (v >= 0 && v < vertexCount_ && seenBy[size_t(v)] != int(g)) {
                    seenBy[size_t(v)] = int(g);
                    ++counts[g];
                }
        return counts;
    }

  private:
    static bool isKnownIgnored(std::string_view key) {
        return key[0] == '#' || key == "vn" || key == "vp" || key == "s" || key == "l" ||
               key == "p";
    }

    [[noreturn]] void fail(const std::string& what) const {
        throw MeshError(path_, what, "line " + std::to_string(line_));
    }

    void vertex(std::string_view rest) {
        for (int k = 0; k < 3; ++k) {
            const std::string_view t = beforeComment(nextToken(rest), rest);
            double value;
            if (t.empty())
                fail("vertex " + std::to_string(vertexCount_) + " has fewer than 3 coordinates");
            if (!parseDouble(t, value)) fail("invalid coordinate '" + std::string(t) + "'");
            soup_.xyz.push_back(value);
        }
        soup_.vertexLine.push_back(line_);
    }

    // "u [v] [w]": u and v (0 if absent) are kept; one that does not parse keeps no texture
    // coordinates at all (they are only carried to the output, so a bad one must not stop a solve).
    void textureCoordinate(std::string_view rest) {
        for (int k = 0; k < 2; ++k) {
            const std::string_view t = beforeComment(nextToken(rest), rest);
            double value = 0;
            // A nan or inf would reach a glb's TEXCOORD_0, which must be finite.
            if ((k == 0 || !t.empty()) && (!parseDouble(t, value) || !std::isfinite(value)))
                uvBroken_ = true;
            soup_.uv.push_back(value);
        }
    }

    // "mtllib my mat.mtl" as Blender reads it: the rest of the line (quotes around it removed)
    // is one library when it names a file beside the OBJ; otherwise its words are libraries.
    void materialLibraries(std::string_view rest) {
        std::string_view whole = wholeName(rest);
        if (whole.size() > 2 && whole.front() == '"' && whole.back() == '"')
            whole = whole.substr(1, whole.size() - 2);
        std::error_code ec;
        if (!whole.empty() &&
            std::filesystem::is_regular_file(
                std::filesystem::path(path_).parent_path() / std::string(whole), ec)) {
            soup_.materialLibraries.emplace_back(whole);
            return;
        }
        for (auto t = nextToken(rest); !t.empty(); t = nextToken(rest))
            soup_.materialLibraries.emplace_back(t);
    }

    int useMaterial(std::string_view rest) {
        const std::string name(wholeName(rest));
        if (name.empty()) return -1;
        const auto it = std::find(soup_.materialNames.begin(), soup_.materialNames.end(), name);
        if (it != soup_.materialNames.end())
            return static_cast<int>(it - soup_.materialNames.begin());
        soup_.materialNames.push_back(name);
        return static_cast<int>(soup_.materialNames.size()) - 1;
    }

    // The "vt" index after the first '/' of "7/1", "7/1/3" (-1 for "7" and "7//3"), resolved
    // like a position (a forward one is checked at the end); an unusable one drops the file's
    // texture coordinates.
    int uvReference(const char* from, const char* end) {
        if (from == end || *from != '/' || from + 1 == end || from[1] == '/') return -1;
        int index = 0;
        const auto [stop, ec] = std::from_chars(
            afterPlus(std::string_view(from + 1, size_t(end - from - 1))), end, index);
        const int resolved = index > 0 ? index - 1 : uvCount_ + index;
        if (ec != std::errc() || (stop != end && *stop != '/') || index == 0 || resolved < 0)
            uvBroken_ = true;
        return resolved;
    }

    void face(std::string_view rest) {
        const size_t first = soup_.faceIndex.size();
        for (auto t = nextToken(rest); !t.empty(); t = nextToken(rest)) {
            t = beforeComment(t, rest);
            if (t.empty()) break;
            // The position index, then the texture coordinate's: "7", "7/1", "7//3", "7/1/3".
            int index = 0;
            const char* end = t.data() + t.size();
            const auto [stop, ec] = std::from_chars(afterPlus(t), end, index);
            if (ec != std::errc() || (stop != end && *stop != '/'))
                fail("invalid vertex reference '" + std::string(t) + "'");
            soup_.uvOf.push_back(uvReference(stop, end));
            if (index == 0) fail("vertex index 0 (OBJ indices start at 1)");
            // Relative indices count back from the vertices read so far.
            const int resolved = index > 0 ? index - 1 : vertexCount_ + index;
            if (resolved < 0)
                fail("relative index " + std::to_string(index) + " points before the first vertex");
            soup_.faceIndex.push_back(resolved);
        }
        if (soup_.faceIndex.size() - first < 3)
            fail("face with " + std::to_string(soup_.faceIndex.size() - first) +
                 " corner(s); a face needs at least 3");
        soup_.endFace();
        soup_.faceMaterial.push_back(material_);
        soup_.faceLine.push_back(line_);
        if (!group_.empty()) soup_.fileFace.push_back(fileFaces_);
    }

    // Names only: the corners of a face go to every group it belongs to. Bad references are
    // left to readMesh, which names them; here they count nothing.
    void countGroupFace(std::string_view rest) {
        corners_.clear();
        for (auto t = nextToken(rest); !t.empty(); t = nextToken(rest)) {
            t = beforeComment(t, rest);  // as face() cuts "3/1/#1": else the count took a corner
            if (t.empty()) break;
            int index = 0;
            std::from_chars(afterPlus(t), t.data() + t.size(), index);
            if (index != 0) corners_.push_back(index > 0 ? index - 1 : vertexCount_ + index);
        }
        for (size_t g : activeGroups_)
            groupCorners_[g].insert(groupCorners_[g].end(), corners_.begin(), corners_.end());
    }

    void addName(const std::string& name) {
        if (nameIndex_.emplace(name, names_.size()).second) names_.push_back(name);
    }

    void updateSelected() {
        selected_ = group_.empty() || currentO_ == group_ ||
                    std::find(currentG_.begin(), currentG_.end(), group_) != currentG_.end();
        // The same membership by name index, for counting each group's vertices.
        groupCorners_.resize(names_.size());
        activeGroups_.clear();
        for (const std::string& g : currentG_) activeGroups_.push_back(nameIndex_.at(g));
        if (!currentO_.empty()) activeGroups_.push_back(nameIndex_.at(currentO_));
    }

    std::string nameList() const {
        std::string list;
        for (size_t i = 0; i < names_.size() && i < 12; ++i) list += (i ? ", " : "") + names_[i];
        if (names_.size() > 12) list += ", ... (" + std::to_string(names_.size()) + " in all)";
        return names_.empty() ? "none" : list;
    }

    std::string path_, group_;
    PolygonSoup soup_;
    int line_ = 0;
    int vertexCount_ = 0;
    int uvCount_ = 0;
    bool uvBroken_ = false;
    int material_ = -1;
    int fileFaces_ = 0;
    bool selected_ = group_.empty();
    std::vector<std::string> currentG_, names_;
    std::vector<std::vector<int>> groupCorners_;  // names only: per name, its faces' corners
    std::unordered_map<std::string, size_t> nameIndex_;
    std::vector<size_t> activeGroups_;  // indices into names_ of the current g and o
    std::vector<int> corners_;
    std::string currentO_;
    std::map<std::string, int> unknown_;
};

}  // namespace

PolygonSoup readObj(const std::string& path, const std::string& group) {
    return ObjParser(path, group).parse(false);
}

std::vector<ObjGroup> readObjGroups(const std::string& path) {
    ObjParser parser(path, {});
    parser.parse(true);
    const std::vector<int> counts = parser.groupVertexCounts();
    std::vector<ObjGroup> groups;
    for (size_t g = 0; g < parser.names().size(); ++g)
        groups.push_back({parser.names()[g], g < counts.size() ? counts[g] : 0});
    return groups;
}

}  // namespace boneless::detail
