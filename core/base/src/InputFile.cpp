#include "boneless/InputFile.h"

#include <filesystem>
#include <system_error>

namespace boneless {

std::string notARegularFile(const std::string& path, const std::string& kind) {
    namespace fs = std::filesystem;
    std::error_code ec;
    const fs::file_type type = fs::status(path, ec).type();
    if (ec || type == fs::file_type::regular) return {};
    if (type == fs::file_type::directory) return "is a directory, not a " + kind + " file";
    return "is not a regular file";
}

}  // namespace boneless
