#pragma once

// The mesh readers take a path: each input goes to a file of its own in a per-process folder
// (fuzzing jobs run side by side), named with the extension that selects the reader. The folder
// goes when the process exits normally (the end of -max_total_time or -runs), so that CI runs and
// campaigns leave nothing in /tmp; a crash keeps it, with the input that crashed.

#include <unistd.h>

#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>
#include <system_error>

struct FuzzFolder {
    std::filesystem::path path =
        std::filesystem::temp_directory_path() / ("boneless-fuzz-" + std::to_string(::getpid()));
    FuzzFolder() { std::filesystem::create_directories(path); }
    ~FuzzFolder() {
        std::error_code ignored;  // nothing to report to at exit
        std::filesystem::remove_all(path, ignored);
    }
};

inline std::string fuzzInputFile(const std::uint8_t* data, std::size_t size, const char* ext) {
    static const FuzzFolder dir;  // destroyed by exit()
    const std::string path = (dir.path / (std::string("input.") + ext)).string();
    std::ofstream out(path, std::ios::binary | std::ios::trunc);
    out.write(reinterpret_cast<const char*>(data), std::streamsize(size));
    out.close();
    if (!out) std::abort();  // the harness, not the reader, failed
    return path;
}
