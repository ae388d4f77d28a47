#include "TestFiles.h"

#include <filesystem>
#include <fstream>

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

}  // namespace boneless::testing
