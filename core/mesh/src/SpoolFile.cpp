#include "boneless/SpoolFile.h"

#include <unistd.h>
#include <cerrno>
#include <cstring>
#include <filesystem>
#include <vector>

#include "boneless/Error.h"

namespace boneless {

void writeSpooled(const std::string& path, const std::string& head, std::FILE* spool,
                  const std::string& spoolPath, const std::string& tail) {
    const std::string temporary = path + ".tmp" + std::to_string(::getpid());
    std::FILE* out = std::fopen(temporary.c_str(), "wb");
    const std::string cannotCreate = out ? "" : std::strerror(errno);
    bool ok = out && std::fflush(spool) == 0 && std::fseek(spool, 0, SEEK_SET) == 0 &&
              std::fwrite(head.data(), 1, head.size(), out) == head.size();
    std::vector<char> buffer(1 << 20);
    while (ok) {
        const size_t got = std::fread(buffer.data(), 1, buffer.size(), spool);
        if (got == 0) break;
        ok = std::fwrite(buffer.data(), 1, got, out) == got;
    }
    ok = ok && !std::ferror(spool) && std::fwrite(tail.data(), 1, tail.size(), out) == tail.size();
    std::string why = ok ? "" : writeFailure();  // before fclose and remove touch errno
    if (out && std::fclose(out) != 0 && ok) {
        ok = false;
        why = writeFailure();
    }
    std::fclose(spool);
    if (!spoolPath.empty()) std::remove(spoolPath.c_str());
    std::error_code ec;
    if (ok) std::filesystem::rename(temporary, path, ec);
    if (!ok || ec) {
        std::remove(temporary.c_str());
        throw Error(path + ": cannot be written (" +
                    (!out ? cannotCreate
                     : ec ? ec.message()
                          : why) +
                    ")");
    }
}

}  // namespace boneless
