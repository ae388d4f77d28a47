#include "MtlReader.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <optional>
#include <sstream>

#include "PrecheckText.h"
#include "boneless/MaterialFiles.h"

namespace boneless::detail {

std::filesystem::path resolvedPath(const std::filesystem::path& path) {
    std::error_code error;
    const std::filesystem::path full = std::filesystem::absolute(path, error);
    if (error || !full.has_filename()) return full.lexically_normal();
    const std::filesystem::path folder =
        std::filesystem::weakly_canonical(full.parent_path(), error);
    return error ? full.lexically_normal() : folder / full.filename();
}

namespace {

// The arguments each map option takes before the file name (the .mtl format of Wavefront's
// documentation); -o, -s and -t take one to three numbers.
int optionArguments(const std::string& option) {
    if (option == "-o" || option == "-s" || option == "-t") return -3;
    if (option == "-mm") return 2;
    if (option == "-blendu" || option == "-blendv" || option == "-bm" || option == "-boost" ||
        option == "-cc" || option == "-clamp" || option == "-imfchan" || option == "-texres" ||
        option == "-type")
        return 1;
    return 0;
}

// The word as a number, if all of it is one.
std::optional<double> asNumber(const std::string& word) {
    std::istringstream in(word);
    double x = 0;
    if (in >> x && in.peek() == EOF) return x;
    return std::nullopt;
}

std::string trimmed(const std::string& s) {
    const size_t first = s.find_first_not_of(" \t\r");
    if (first == std::string::npos) return {};
    return s.substr(first, s.find_last_not_of(" \t\r") - first + 1);
}

// A map statement's file (what follows its options, spaces and all) and its -bm strength.
struct MapStatement {
    std::string file;
    double bumpScale = 1;
    TextureTransform transform;
};

MapStatement mapStatement(std::string rest) {
    MapStatement out;
    for (;;) {
        rest = trimmed(rest);
        if (rest.empty() || rest[0] != '-') {
            out.file = rest;
            return out;
        }
        const size_t end = rest.find_first_of(" \t");
        const std::string option = rest.substr(0, end);
        rest = end == std::string::npos ? "" : rest.substr(end);
        const int arguments = optionArguments(option);
        for (int k = 0; k < std::abs(arguments); ++k) {
            std::istringstream in(rest);
            std::string word;
            if (!(in >> word) || (arguments < 0 && k > 0 && !asNumber(word))) break;
            const auto x = asNumber(word);
            if (option == "-bm" && x) out.bumpScale = *x;
            // The third number (w) moves a 3-D texture, which glTF has not.
            if (option == "-o" && x && k < 2) out.transform.offset[k] = *x;
            if (option == "-s" && x && k < 2) out.transform.scale[k] = *x;
            rest = rest.substr(rest.find(word) + word.size());
        }
    }
}

// Where a map statement's file is: named relative to the library's folder, '\\' as '/'.
std::filesystem::path texturePath(const std::filesystem::path& folder, std::string name) {
    std::replace(name.begin(), name.end(), '\\', '/');
    return resolvedPath(folder / name);
}

bool glTFImage(const std::filesystem::path& file) {
    std::ifstream in(file, std::ios::binary);
    std::string head(8, '\0');
    in.read(head.data(), 8);
    head.resize(static_cast<size_t>(in.gcount()));
    return !imageMimeType(head).empty();
}

// At most this many notes a library, then how many more: a broken file is one problem.
constexpr int kNotesPerLibrary = 5;

void readLibrary(const std::string& path, std::vector<ObjMaterial>& materials,
                 std::vector<std::string>& warnings, std::vector<std::string>* textures) {
    // A regular file only: a library named /dev/zero or a pipe must not hang the reader.
    std::error_code error;
    std::ifstream in;
    if (std::filesystem::is_regular_file(path, error)) in.open(path);
    if (!in.is_open()) {
        warnings.push_back(path +
                           ": material library cannot be read; its materials keep only "
                           "their names");
        return;
    }
    const std::filesystem::path folder = std::filesystem::path(path).parent_path();
    int notes = 0;
    bool roughnessGiven = false;  // the current material's Ns
    std::string line;
    for (int number = 1; std::getline(in, line); ++number) {
        // A UTF-8 byte-order mark (.NET's writers put one) hid the first newmtl.
        if (number == 1 && precheck::startsWithByteOrderMark(line)) line.erase(0, 3);
        std::istringstream words(line);
        std::string key;
        words >> key;
        const std::string where = path + " line " + std::to_string(number) + ": ";
        auto note = [&](const std::string& what) {
            if (notes++ < kNotesPerLibrary) warnings.push_back(where + what);
        };
        if (key == "newmtl") {
            std::string rest;
            std::getline(words, rest);
            materials.emplace_back();
            materials.back().name = trimmed(rest);
            roughnessGiven = false;
        } else if (key == "Kd" || key == "d" || key == "Tr" || key == "Ns" || key == "illum" ||
                   key == "map_Kd" || key == "map_Bump" || key == "map_bump" || key == "bump") {
            if (materials.empty()) {
                note(key + " before any newmtl, ignored");
                continue;
            }
            ObjMaterial& m = materials.back();
            if (key == "Kd") {
                // "Kd r g b", or "Kd r" for a grey.
                std::vector<double> c;
                for (std::string word; words >> word;) {
                    const std::optional<double> x = asNumber(word);
                    if (!x) {
                        c.clear();
                        break;
                    }
                    c.push_back(*x);
                }
                if (c.size() == 1) c.assign(3, c[0]);
                if (c.size() == 3)
                    m.colour = {c[0], c[1], c[2]};
                else
                    note("Kd needs one or three numbers");
            } else if (key == "map_Kd" || key == "map_Bump" || key == "map_bump" || key == "bump") {
                std::string rest;
                std::getline(words, rest);
                const MapStatement map = mapStatement(rest);
                const std::string& name = map.file;
                const std::filesystem::path file = texturePath(folder, name);
                if (textures && !name.empty()) textures->push_back(file.string());
                if (name.empty())
                    note(key + " names no file");
                else if (std::error_code e; !std::filesystem::is_regular_file(file, e))
                    note("texture " + file.string() + " not found");
                else if (!glTFImage(file))
                    note("texture " + file.string() +
                         " is neither PNG nor JPEG, the image formats glTF carries: a .glb export "
                         "leaves it out");
                else if (key == "map_Kd") {
                    m.texture = file.string();
                    m.textureTransform = map.transform;
                } else {
                    m.normalTexture = file.string();
                    m.normalScale = map.bumpScale;
                    m.normalTransform = map.transform;
                }
            } else if (key == "Ns" || key == "illum") {
                std::string word;
                words >> word;
                const std::optional<double> x = asNumber(word);
                if (!x)
                    note(key + " needs a number");
                else if (key == "Ns") {
                    m.roughness = 1 - std::sqrt(std::clamp(*x, 0.0, 1000.0) / 1000);
                    roughnessGiven = true;
                } else if (*x == 2 && !roughnessGiven)
                    m.roughness = 0;  // Blender 3.4 reads "illum 2" without Ns as smooth
            } else {
                std::string word;
                words >> word;
                if (key == "d" && word == "-halo") words >> word;  // halo: ignored
                if (const std::optional<double> x = asNumber(word))
                    m.opacity = std::clamp(key == "d" ? *x : 1 - *x, 0.0, 1.0);
                else
                    note(key + " needs a number");
            }
        }
    }
    if (notes > kNotesPerLibrary)
        warnings.push_back(path + ": " + std::to_string(notes - kNotesPerLibrary) + " more " +
                           (notes - kNotesPerLibrary == 1 ? "line" : "lines") + " like these");
}

}  // namespace

std::vector<ObjMaterial> readMaterialLibraries(const std::vector<std::string>& paths,
                                               std::vector<std::string>& warnings,
                                               std::vector<std::string>* textures) {
    std::vector<ObjMaterial> materials;
    for (size_t k = 0; k < paths.size(); ++k)
        if (std::find(paths.begin(), paths.begin() + k, paths[k]) == paths.begin() + k)
            readLibrary(paths[k], materials, warnings, textures);
    return materials;
}

std::string relocatedLibrary(const std::string& path,
                             const std::function<std::string(const std::string&)>& name) {
    std::ifstream in(path, std::ios::binary);
    const std::filesystem::path folder = std::filesystem::path(path).parent_path();
    std::string text, line;
    // Written with LF alone and no byte-order mark, which after the copy's own first line would
    // hide the first newmtl from every reader.
    for (bool first = true; std::getline(in, line); first = false) {
        if (first && precheck::startsWithByteOrderMark(line)) line.erase(0, 3);
        if (!line.empty() && line.back() == '\r') line.pop_back();
        std::istringstream words(line);
        std::string key;
        words >> key;
        const bool map = key.rfind("map_", 0) == 0 || key == "bump" || key == "disp" ||
                         key == "decal" || key == "refl" || key == "norm";
        const size_t keyEnd = line.find(key) + key.size();
        const std::string rest = map ? line.substr(keyEnd) : std::string();
        const std::string file = map ? mapStatement(rest).file : std::string();
        if (file.empty()) {
            text += line + "\n";
            continue;
        }
        // The options are kept as they were; the file is the end of the line.
        const std::string options = rest.substr(0, rest.rfind(file));
        text += line.substr(0, keyEnd) + options + name(texturePath(folder, file).string()) + "\n";
    }
    return text;
}

std::string imageMimeType(const std::string& head) {
    const auto byte = [&](size_t i) { return static_cast<unsigned char>(head[i]); };
    if (head.size() >= 8 && head.compare(0, 8, "\x89PNG\r\n\x1a\n") == 0) return "image/png";
    if (head.size() >= 3 && byte(0) == 0xFF && byte(1) == 0xD8 && byte(2) == 0xFF)
        return "image/jpeg";
    return {};
}

}  // namespace boneless::detail

namespace boneless {

std::vector<std::string> materialFiles(const SourceFaces& faces) {
    std::vector<std::string> files, warnings;
    detail::readMaterialLibraries(faces.materialLibraries, warnings, &files);
    files.insert(files.begin(), faces.materialLibraries.begin(), faces.materialLibraries.end());
    std::vector<std::string> once;
    for (const std::string& f : files)
        if (std::find(once.begin(), once.end(), f) == once.end()) once.push_back(f);
    return once;
}

}  // namespace boneless
