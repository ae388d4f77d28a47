#pragma once

// Seed corpora made by the project's writers, so nothing binary is committed. Each fuzzer
// writes its own when run with --write-seeds=DIR (libFuzzer passes "--" flags through):
//   boneless-fuzz-obj --write-seeds=corpus/obj

#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "boneless/TriMesh.h"

namespace fuzzseeds {

// The DIR of --write-seeds=DIR, or empty.
inline std::string seedDir(int* argc, char*** argv) {
    for (int i = 1; i < *argc; ++i)
        if (std::strncmp((*argv)[i], "--write-seeds=", 14) == 0) return (*argv)[i] + 14;
    return {};
}

inline void save(const std::string& dir, const std::string& name, const std::string& bytes) {
    std::filesystem::create_directories(dir);
    std::ofstream(std::filesystem::path(dir) / name, std::ios::binary) << bytes;
}

inline std::string slurp(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    return std::string(std::istreambuf_iterator<char>(in), {});
}

// A closed octahedron and an open square of two triangles: one closed, one with a boundary.
struct SeedMesh {
    boneless::Positions V;
    boneless::Faces F;
};
inline std::vector<SeedMesh> seedMeshes() {
    SeedMesh octa;
    octa.V.resize(6, 3);
    octa.V << 1, 0, 0, -1, 0, 0, 0, 1, 0, 0, -1, 0, 0, 0, 1, 0, 0, -1;
    octa.F.resize(8, 3);
    octa.F << 0, 2, 4, 2, 1, 4, 1, 3, 4, 3, 0, 4, 2, 0, 5, 1, 2, 5, 3, 1, 5, 0, 3, 5;
    SeedMesh square;
    square.V.resize(4, 3);
    square.V << 0, 0, 0, 1, 0, 0, 1, 1, 0.5, 0, 1, 0;
    square.F.resize(2, 3);
    square.F << 0, 1, 2, 0, 2, 3;
    return {octa, square};
}

// Exits the process after writing: a seed run is not a fuzzing run.
[[noreturn]] inline void done(const std::string& dir) {
    std::printf("seeds written to %s\n", dir.c_str());
    std::exit(0);
}

}  // namespace fuzzseeds
