#include "SolveMemory.h"

#include <sys/resource.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <thread>
#include <utility>

#include "boneless/Error.h"
#include "boneless/SolveFits.h"
#include "boneless/Text.h"

namespace boneless {

namespace {

// Peak bytes a solver adds per face, measured with boneless-bench-large on the demo creature
// (docs/benchmarks.md) and rounded up; the exact method's 2-ring block system and its factor
// need several times more than the local/global method's levels.
constexpr double kLocalGlobalBytesPerFace = 4.0 * 1024;
constexpr double kExactBytesPerFace = 16.0 * 1024;
// What a first solver's run takes, held against every limit (physical memory, ulimit -v, a
// cgroup): the address space it maps, which ulimit -v caps, the program and its
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
    const double mb = double(bytes) / (1024.0 * 1024);
    return mb >= 1024 ? fixedNumber(mb / 1024, 1) + " GB" : fixedNumber(mb, 0) + " MB";
}

std::string thousands(int n) {
    std::string s = std::to_string(n);
    for (int i = static_cast<int>(s.size()) - 3; i > 0; i -= 3) s.insert(i, ",");
    return s;
}

}  // namespace

std::uint64_t physicalMemory() {
    const long pages = ::sysconf(_SC_PHYS_PAGES), pageSize = ::sysconf(_SC_PAGESIZE);
    return pages > 0 && pageSize > 0 ? std::uint64_t(pages) * std::uint64_t(pageSize) : 0;
}

std::uint64_t addressSpaceLimit() {
    rlimit limit{};
    return ::getrlimit(RLIMIT_AS, &limit) == 0 && limit.rlim_cur != RLIM_INFINITY ? limit.rlim_cur
                                                                                  : 0;
}

std::uint64_t cgroupMemoryMax(const std::string& file) {
    std::uint64_t bytes = 0;
    return std::ifstream(file) >> bytes ? bytes : 0;
}

MemoryBudget lowestBudget(std::uint64_t physical, std::uint64_t addressSpace, std::uint64_t cgroup,
                          std::uint64_t test) {
    MemoryBudget budget;
    for (const auto& [bytes, from] :
         {std::pair{physical, "this machine's physical memory"},
          {addressSpace, "the process's address-space limit (ulimit -v)"},
          {cgroup, "the cgroup's memory.max"},
          {test, "the limit set for tests"}})
        if (bytes > 0 && (budget.bytes == 0 || bytes < budget.bytes)) budget = {bytes, from};
    return budget;
}

MemoryBudget processBudget() {
    return lowestBudget(physicalMemory(), addressSpaceLimit(), cgroupMemoryMax(), testLimit);
}

SolveMemory estimateSolveMemory(int vertices, int faces, SolverOptions::Method method,
                                const MemoryBudget& budget) {
    (void)vertices;  // a closed mesh has twice as many faces as vertices: faces say it all
    SolveMemory m;
    const double perFace =
        method == SolverOptions::Method::Exact ? kExactBytesPerFace : kLocalGlobalBytesPerFace;
    m.perSolver = static_cast<std::uint64_t>(perFace * std::max(faces, 0));
    m.firstRun = static_cast<std::uint64_t>(
        kAddressSpaceBase + kAddressSpacePerBlasThread * (blasThreads() - 1) +
        (kAddressBytesPerFace - kLocalGlobalBytesPerFace + perFace) * std::max(faces, 0));
    m.budget = budget;
    return m;
}

SolveMemory estimateSolveMemory(int vertices, int faces, SolverOptions::Method method) {
    return estimateSolveMemory(vertices, faces, method, processBudget());
}

void limitSolveMemoryForTests(std::uint64_t bytes) {
    testLimit = bytes;
}

void checkSolveFits(int vertices, int faces, const std::string& meshPath,
                    SolverOptions::Method method, const MemoryBudget& budget) {
    const SolveMemory memory = estimateSolveMemory(vertices, faces, method, budget);
    // One figure whatever sets the limit: physical memory and a cgroup took the solver's 4 KB a
    // face against 80 % of themselves, so a cgroup that ulimit -v's check refused passed the
    // koala, which then ran out of memory; the whole run is what each limit must hold.
    const std::uint64_t need = memory.firstRun;
    if (budget.bytes == 0 || need <= budget.bytes) return;
    throw Error(meshPath + ": " + thousands(faces) + " faces (" + thousands(vertices) +
                " vertices) would need about " + megabytes(need) + " to solve, and " + budget.from +
                " is " + megabytes(budget.bytes) +
                "; decimate the mesh (Blender's Decimate modifier, for one) and solve again");
}

void checkSolveFits(const TriMesh& mesh, const std::string& meshPath,
                    SolverOptions::Method method) {
    checkSolveFits(mesh.vertexCount(), mesh.faceCount(), meshPath, method, processBudget());
}

int solversThatFit(const SolveMemory& memory, int wanted) {
    if (memory.budget.bytes == 0 || memory.perSolver == 0) return std::max(1, wanted);
    const auto fit = static_cast<int>(memory.budget.bytes / 2 / memory.perSolver);
    return std::clamp(fit, 1, std::max(1, wanted));
}

}  // namespace boneless
