#include "TestFiles.h"

#include <filesystem>
#include <fstream>
#include <sstream>

#include "boneless/Error.h"

namespace boneless::testing {

std::string writeTestFile(const std::string& name, const std::string& text) {
    const std::filesystem::path dir(freshTestDir("file-" + name));
    const std::string path = (dir / name).string();
    std::ofstream(path) << text;
    return path;
}

std::string errorOf(const std::function<void()>& f) {
    try {
        f();
    } catch (const Error& e) {
        return e.what();
    }
    return "";
}

std::string twoByTwoPng() {
    static const unsigned char bytes[] = {
        0x89, 0x50, 0x4e, 0x47, 0x0d, 0x0a, 0x1a, 0x0a, 0x00, 0x00, 0x00, 0x0d, 0x49, 0x48, 0x44,
        0x52, 0x00, 0x00, 0x00, 0x02, 0x00, 0x00, 0x00, 0x02, 0x08, 0x02, 0x00, 0x00, 0x00, 0xfd,
        0xd4, 0x9a, 0x73, 0x00, 0x00, 0x00, 0x12, 0x49, 0x44, 0x41, 0x54, 0x78, 0x9c, 0x63, 0xf8,
        0xcf, 0xc0, 0xc0, 0x00, 0xc2, 0x0c, 0xff, 0x81, 0x00, 0x00, 0x1f, 0xee, 0x05, 0xfb, 0x0b,
        0xd9, 0x68, 0x8b, 0x00, 0x00, 0x00, 0x00, 0x49, 0x45, 0x4e, 0x44, 0xae, 0x42, 0x60, 0x82};
    return std::string(reinterpret_cast<const char*>(bytes), sizeof bytes);
}

void addTextureCoordinatesAndMaterial(const std::string& objPath, const std::string& library,
                                      const std::string& material) {
    std::ifstream in(objPath);
    std::string text = "mtllib " + library + "\n", line, faces = "usemtl " + material + "\n";
    int corners = 0;
    while (std::getline(in, line)) {
        if (line.rfind("f ", 0) != 0) {
            text += line + "\n";
            continue;
        }
        std::istringstream corner(line.substr(2));
        faces += "f";
        for (std::string v; corner >> v;) {
            text += "vt " + std::to_string(++corners % 97 / 97.0) + " 0.5\n";
            faces += " " + v + "/" + std::to_string(corners);
        }
        faces += "\n";
    }
    in.close();
    std::ofstream(objPath) << text << faces;
}

}  // namespace boneless::testing
