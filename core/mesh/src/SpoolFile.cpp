#include "boneless/SpoolFile.h"

#include <sys/stat.h>
#include <unistd.h>
#include <cerrno>
#include <charconv>
#include <chrono>
#include <cstring>
#include <filesystem>
#include <limits>
#include <mutex>
#include <string_view>
#include <unordered_map>
#include <utility>
#include <vector>

#include "boneless/Error.h"
#include "boneless/Process.h"

namespace boneless {

namespace {

namespace fs = std::filesystem;

// The pid of `<output>.tmp<pid>` (so of `<output>.frames.tmp<pid>` too), with `output` set to the
// name before ".tmp"; 0 for any other name. The pid is written as std::to_string writes it.
pid_t temporaryPid(std::string_view name, std::string_view& output) {
    const std::size_t at = name.rfind(".tmp");
    if (at == 0 || at == std::string_view::npos) return 0;
    const std::string_view digits = name.substr(at + 4);
    long long pid = 0;
    const auto [end, ec] = std::from_chars(digits.data(), digits.data() + digits.size(), pid);
    if (digits.empty() || digits[0] < '1' || digits[0] > '9' || ec != std::errc() ||
        end != digits.data() + digits.size() || pid > std::numeric_limits<pid_t>::max())
        return 0;
    output = name.substr(0, at);
    return static_cast<pid_t>(pid);
}

// The writers' temporaries in one folder, by the name of the output they were for. An OBJ
// sequence writes thousands of files into one folder (listing 10,000 files took 28 ms on the
// shared test machine): listing it for each would make the export's time grow with the square of
// its length, so a listing serves the writes into its folder for a second.
struct Listing {
    std::string folder;
    dev_t device = 0;
    ino_t inode = 0;
    std::chrono::steady_clock::time_point at;
    std::unordered_map<std::string, std::vector<std::pair<std::string, pid_t>>> temporaries;
};

void list(const fs::path& folder, Listing& listing) {
    listing.temporaries.clear();
    std::error_code ec;
    for (fs::directory_iterator it(folder, ec), end; !ec && it != end; it.increment(ec)) {
        const std::string name = it->path().filename().string();
        std::string_view output;
        const pid_t pid = temporaryPid(name, output);
        if (pid == 0) continue;
        listing.temporaries[std::string(output)].emplace_back(name, pid);
        constexpr std::string_view spool = ".frames";
        if (output.size() > spool.size() && output.substr(output.size() - spool.size()) == spool)
            listing.temporaries[std::string(output.substr(0, output.size() - spool.size()))]
                .emplace_back(name, pid);
    }
}

void removeStaleTemporaries(const std::string& path) {
    const fs::path file(path);
    const fs::path folder = file.has_parent_path() ? file.parent_path() : fs::path(".");
    const std::string name = file.filename().string();
    struct stat folderStat {};
    if (name.empty() || ::stat(folder.c_str(), &folderStat) != 0) return;
    static std::mutex mutex;
    static Listing listing;
    std::lock_guard<std::mutex> lock(mutex);
    const auto now = std::chrono::steady_clock::now();
    if (listing.folder != folder.string() || listing.device != folderStat.st_dev ||
        listing.inode != folderStat.st_ino || now - listing.at > std::chrono::seconds(1)) {
        listing.folder = folder.string();
        listing.device = folderStat.st_dev;
        listing.inode = folderStat.st_ino;
        listing.at = now;
        list(folder, listing);
    }
    const auto found = listing.temporaries.find(name);
    if (found == listing.temporaries.end()) return;
    auto& temporaries = found->second;
    for (auto t = temporaries.begin(); t != temporaries.end();) {
        const fs::path stale = folder / t->first;
        std::error_code ec;
        // Only a regular file: a folder or link of that name was never a writer's.
        if (processIsGone(t->second) &&
            fs::symlink_status(stale, ec).type() == fs::file_type::regular) {
            fs::remove(stale, ec);
            t = temporaries.erase(t);
        } else {
            ++t;
        }
    }
}

}  // namespace

void removeStaleTemporariesIn(const std::string& folder,
                              const std::function<bool(const std::string& output)>& ours) {
    std::vector<fs::path> stale;
    std::error_code ec;
    for (fs::directory_iterator it(folder, ec), end; !ec && it != end; it.increment(ec)) {
        const std::string name = it->path().filename().string();
        std::string_view output;
        const pid_t pid = temporaryPid(name, output);
        constexpr std::string_view spool = ".frames";
        if (output.size() > spool.size() && output.substr(output.size() - spool.size()) == spool)
            output.remove_suffix(spool.size());
        std::error_code typeError;
        // Only a regular file: a folder or link of that name was never a writer's.
        if (pid != 0 && ours(std::string(output)) &&
            fs::symlink_status(it->path(), typeError).type() == fs::file_type::regular &&
            processIsGone(pid))
            stale.push_back(it->path());
    }
    for (const fs::path& file : stale) fs::remove(file, ec);
}

std::string temporaryFor(const std::string& path) {
    removeStaleTemporaries(path);
    return path + ".tmp" + std::to_string(::getpid());
}

std::FILE* openSpoolBeside(const std::string& path) {
    removeStaleTemporaries(path);
    // Named only from fopen to unlink; a kill in between leaves what the next writer removes.
    const std::string name = path + ".frames.tmp" + std::to_string(::getpid());
    std::FILE* spool = std::fopen(name.c_str(), "wb+");
    if (!spool || ::unlink(name.c_str()) != 0) {
        const std::string why = std::strerror(errno);
        if (spool) std::fclose(spool);
        throw Error(path + ": cannot be written (" + why + ")");
    }
    return spool;
}

void writeSpooled(const std::string& path, const std::string& head, std::FILE* spool,
                  const std::string& tail) {
    writeSpooled(path, head, spool, [&](std::FILE* out) {
        return std::fwrite(tail.data(), 1, tail.size(), out) == tail.size();
    });
}

void writeSpooled(const std::string& path, const std::string& head, std::FILE* spool,
                  const std::function<bool(std::FILE*)>& writeTail) {
    const std::string temporary = temporaryFor(path);
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
    ok = ok && !std::ferror(spool) && writeTail(out);
    std::string why = ok ? "" : writeFailure();  // before fclose and remove touch errno
    if (out && std::fclose(out) != 0 && ok) {
        ok = false;
        why = writeFailure();
    }
    std::fclose(spool);
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
