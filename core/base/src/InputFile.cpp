#include "boneless/InputFile.h"

#include <filesystem>
#include <system_error>

namespace boneless {

std::string notARegularFile(const std::string& path, const std::string& kind) {
    namespace fs = std::filesystem;
    std::error_code ec;
    // Opening a link whose target is gone says "No such file" of the link, which is there.
    if (fs::is_symlink(fs::symlink_status(path, ec)) && !fs::exists(path, ec) && !ec) {
        fs::path target = fs::read_symlink(path, ec);
        if (!ec) {
            if (target.is_relative()) target = (fs::path(path).parent_path() / target);
            return "is a link to " + target.lexically_normal().string() + ", which does not exist";
        }
    }
    ec.clear();
    const fs::file_type type = fs::status(path, ec).type();
    if (ec || type == fs::file_type::regular) return {};
    if (type == fs::file_type::directory) return "is a directory, not a " + kind + " file";
    return "is not a regular file";
}

}  // namespace boneless
