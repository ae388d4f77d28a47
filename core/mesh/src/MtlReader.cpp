#include "MtlReader.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>

namespace boneless::detail {

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

bool isNumber(const std::string& s) {
    std::istringstream in(s);
    double x;
    return static_cast<bool>(in >> x) && in.peek() == EOF;
}

std::string trimmed(const std::string& s) {
    const size_t first = s.find_first_not_of(" \t\r");
    if (first == std::string::npos) return {};
    return s.substr(first, s.find_last_not_of(" \t\r") - first + 1);
}

// The file a map statement names: what follows its options, spaces and all.
std::string mapFile(std::string rest) {
    for (;;) {
        rest = trimmed(rest);
        if (rest.empty() || rest[0] != '-') return rest;
        const size_t end = rest.find_first_of(" \t");
        const std::string option = rest.substr(0, end);
        rest = end == std::string::npos ? "" : rest.substr(end);
        const int arguments = optionArguments(option);
        for (int k = 0; k < std::abs(arguments); ++k) {
            std::istringstream in(rest);
            std::string word;
            if (!(in >> word) || (arguments < 0 && k > 0 && !isNumber(word))) break;
            rest = rest.substr(rest.find(word) + word.size());
        }
    }
}

// PNG and JPEG by their signatures, not their names.
bool glTFImage(const std::filesystem::path& file) {
    std::ifstream in(file, std::ios::binary);
    unsigned char head[8] = {};
    in.read(reinterpret_cast<char*>(head), sizeof head);
    const bool png =
        in.gcount() == 8 && head[0] == 0x89 && head[1] == 'P' && head[2] == 'N' && head[3] == 'G';
    const bool jpeg = in.gcount() >= 3 && head[0] == 0xFF && head[1] == 0xD8 && head[2] == 0xFF;
    return png || jpeg;
}

void readLibrary(const std::string& path, std::vector<ObjMaterial>& materials,
                 std::vector<std::string>& warnings) {
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
    std::string line;
    for (int number = 1; std::getline(in, line); ++number) {
        std::istringstream words(line);
        std::string key;
        words >> key;
        const std::string where = path + " line " + std::to_string(number) + ": ";
        if (key == "newmtl") {
            std::string rest;
            std::getline(words, rest);
            materials.emplace_back();
            materials.back().name = trimmed(rest);
        } else if (key == "Kd" || key == "d" || key == "Tr" || key == "map_Kd") {
            if (materials.empty()) {
                warnings.push_back(where + key + " before any newmtl, ignored");
                continue;
            }
            ObjMaterial& m = materials.back();
            if (key == "Kd") {
                std::array<double, 3> c{};
                if (words >> c[0] >> c[1] >> c[2])
                    m.color = c;
                else
                    warnings.push_back(where + "Kd needs three numbers");
            } else if (key == "map_Kd") {
                std::string rest;
                std::getline(words, rest);
                std::string name = mapFile(rest);
                std::replace(name.begin(), name.end(), '\\', '/');
                const std::filesystem::path file = (folder / name).lexically_normal();
                if (name.empty())
                    warnings.push_back(where + "map_Kd names no file");
                else if (std::error_code e; !std::filesystem::is_regular_file(file, e))
                    warnings.push_back(where + "texture " + file.string() + " not found");
                else if (!glTFImage(file))
                    warnings.push_back(where + "texture " + file.string() +
                                       " is neither PNG nor JPEG, the formats glTF carries; the "
                                       ".glb leaves it out");
                else
                    m.texture = file.string();
            } else {
                double x = 0;
                if (!(words >> x))
                    warnings.push_back(where + key + " needs a number");
                else
                    m.opacity = std::clamp(key == "d" ? x : 1 - x, 0.0, 1.0);
            }
        }
    }
}

}  // namespace

std::vector<ObjMaterial> readMaterialLibraries(const std::vector<std::string>& paths,
                                               std::vector<std::string>& warnings) {
    std::vector<ObjMaterial> materials;
    for (const std::string& path : paths) readLibrary(path, materials, warnings);
    return materials;
}

}  // namespace boneless::detail
