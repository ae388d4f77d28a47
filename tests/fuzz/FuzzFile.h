#pragma once

// The mesh readers take a path: each input goes to a file of its own in a per-process folder
// (fuzzing jobs run side by side), named with the extension that selects the reader.

#include <unistd.h>

#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>

inline std::string fuzzInputFile(const std::uint8_t* data, std::size_t size, const char* ext) {
    static const std::filesystem::path dir = [] {
        std::filesystem::path d = std::filesystem::temp_directory_path() /
                                  ("boneless-fuzz-" + std::to_string(::getpid()));
        std::filesystem::create_directories(d);
        return d;
    }();
    const std::string path = (dir / (std::string("input.") + ext)).string();
    std::ofstream out(path, std::ios::binary | std::ios::trunc);
    out.write(reinterpret_cast<const char*>(data), std::streamsize(size));
    out.close();
    if (!out) std::abort();  // the harness, not the reader, failed
    return path;
}
