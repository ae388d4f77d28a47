#include "SolveMemory.h"

#include <sys/resource.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <thread>

#include "boneless/Error.h"
#include "boneless/SolveFits.h"

namespace boneless {

namespace {

// Peak bytes a solver adds per face, measured with boneless-bench-large on the demo creature
// (docs/benchmarks.md) and rounded up; the exact method's 2-ring block system and its factor
// need several times more than the local/global method's levels.
constexpr double kLocalGlobalBytesPerFace = 4.0 * 1024;
constexpr double kExactBytesPerFace = 16.0 * 1024;
// One solver may take at most this share of the budget.
constexpr double kLargestShare = 0.8;
// The address space a first solver's run maps, which ulimit -v caps: the program and its
// libraries, a buffer for each of OpenBLAS's threads, then 4.8 KB a face for the mesh, take,
// calibration and solver. Fitted on 2 cores to the smallest limits that solved 4 frames of CMU
// 85_02 (docs/benchmarks.md): the koala (99,994 faces) needs 650 to 684 MB (558 to 605 MB with
// OPENBLAS_NUM_THREADS=1), MakeHuman's body (26,756) 293 to 342 MB. The exact method adds its
// larger system on top.
constexpr double kAddressSpaceBase = 100.0 * 1024 * 1024;
constexpr double kAddressSpacePerBlasThread = 100.0 * 1024 * 1024;
constexpr double kAddressBytesPerFace = 4.8 * 1024;

// The threads OpenBLAS starts as it loads, each with its buffer: as it reads them, else a core's.
int blasThreads() {
    for (const char* name : {"OPENBLAS_NUM_THREADS", "GOTO_NUM_THREADS", "OMP_NUM_THREADS"})
        if (const char* value = std::getenv(name); value && std::atoi(value) > 0)
            return std::atoi(value);
    return std::max(1, static_cast<int>(std::thread::hardware_concurrency()));
}

// limitSolveMemoryForTests(): 0, none. Atomic: the app's and the export's threads read it.
std::atomic<std::uint64_t> testLimit{0};

std::string megabytes(std::uint64_t bytes) {
    char text[32];
    const double mb = double(bytes) / (1024.0 * 1024);
    if (mb >= 1024)
        std::snprintf(text, sizeof text, "%.1f GB", mb / 1024);
    else
        std::snprintf(text, sizeof text, "%.0f MB", mb);
    return text;
}

std::string thousands(int n) {
    std::string s = std::to_string(n);
    for (int i = static_cast<int>(s.size()) - 3; i > 0; i -= 3) s.insert(i, ",");
    return s;
}

}  // namespace

SolveMemory estimateSolveMemory(int vertices, int faces, SolverOptions::Method method) {
    (void)vertices;  // a closed mesh has twice as many faces as vertices: faces say it all
    SolveMemory m;
    const double perFace =
        method == SolverOptions::Method::Exact ? kExactBytesPerFace : kLocalGlobalBytesPerFace;
    m.perSolver = static_cast<std::uint64_t>(perFace * std::max(faces, 0));
    m.addressSpace = static_cast<std::uint64_t>(
        kAddressSpaceBase + kAddressSpacePerBlasThread * (blasThreads() - 1) +
        (kAddressBytesPerFace - kLocalGlobalBytesPerFace + perFace) * std::max(faces, 0));
    const long pages = ::sysconf(_SC_PHYS_PAGES), pageSize = ::sysconf(_SC_PAGESIZE);
    m.budget = pages > 0 && pageSize > 0 ? std::uint64_t(pages) * std::uint64_t(pageSize) : 0;
    m.budgetFrom = "this machine's physical memory";
    rlimit limit{};
    if (::getrlimit(RLIMIT_AS, &limit) == 0 && limit.rlim_cur != RLIM_INFINITY &&
        (m.budget == 0 || limit.rlim_cur < m.budget)) {
        m.budget = limit.rlim_cur;
        m.budgetFrom = "the process's address-space limit (ulimit -v)";
        m.budgetIsAddressSpace = true;
    }
    std::uint64_t cgroup = 0;
    if (std::ifstream("/sys/fs/cgroup/memory.max") >> cgroup && cgroup > 0 &&
        (m.budget == 0 || cgroup < m.budget)) {
        m.budget = cgroup;
        m.budgetFrom = "the cgroup's memory.max";
        m.budgetIsAddressSpace = false;
    }
    if (const std::uint64_t test = testLimit; test > 0 && (m.budget == 0 || test < m.budget)) {
        m.budget = test;
        m.budgetFrom = "the limit set for tests";
        m.budgetIsAddressSpace = false;
    }
    return m;
}

void limitSolveMemoryForTests(std::uint64_t bytes) {
    testLimit = bytes;
}

void checkSolveFits(const TriMesh& mesh, const std::string& meshPath,
                    SolverOptions::Method method) {
    const int vertices = mesh.vertexCount(), faces = mesh.faceCount();
    const SolveMemory memory = estimateSolveMemory(vertices, faces, method);
    // Under ulimit -v all the address space mapped counts, and nothing else is the user's; the
    // resident figure left out the program and its libraries, so a limit between 400 and 700 MB
    // passed the koala, which then ran out of memory half a minute in.
    const std::uint64_t need = memory.budgetIsAddressSpace ? memory.addressSpace : memory.perSolver;
    const double share = memory.budgetIsAddressSpace ? 1.0 : kLargestShare;
    if (memory.budget == 0 || double(need) <= share * double(memory.budget)) return;
    throw Error(meshPath + ": " + thousands(faces) + " faces (" + thousands(vertices) +
                " vertices) would need about " + megabytes(need) + " to solve, and " +
                memory.budgetFrom + " is " + megabytes(memory.budget) +
                "; decimate the mesh (Blender's Decimate modifier, for one) and solve again");
}

int solversThatFit(const SolveMemory& memory, int wanted) {
    if (memory.budget == 0 || memory.perSolver == 0) return std::max(1, wanted);
    const auto fit = static_cast<int>(memory.budget / 2 / memory.perSolver);
    return std::clamp(fit, 1, std::max(1, wanted));
}

}  // namespace boneless
