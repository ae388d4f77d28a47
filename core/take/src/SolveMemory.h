#pragma once

// What solving a take needs in memory, estimated up front from the mesh's size, against what the
// process may use: a mesh too large is refused before any work, and no more frames are solved at
// once than fit (each worker holds a solver of its own). Figures: docs/benchmarks.md, "Large
// meshes".

#include <cstdint>
#include <string>

#include "boneless/Reconstruction.h"

namespace boneless {

// What the process may use, and what sets it: the lowest of the limits below.
struct MemoryBudget {
    std::uint64_t bytes = 0;  // 0: no limit known, nothing is refused
    std::string from;         // what sets it, for messages ("the cgroup's memory.max", ...)
};

// The limits, each 0 when it sets none: the machine's physical memory, the address-space limit
// (ulimit -v), and a cgroup's memory.max as `file` holds it ("max" sets none).
std::uint64_t physicalMemory();
std::uint64_t addressSpaceLimit();
std::uint64_t cgroupMemoryMax(const std::string& file = "/sys/fs/cgroup/memory.max");

// The lowest of these limits (0: none), named; `test` as limitSolveMemoryForTests() sets it.
MemoryBudget lowestBudget(std::uint64_t physical, std::uint64_t addressSpace, std::uint64_t cgroup,
                          std::uint64_t test = 0);
// The lowest of this process's limits, read now.
MemoryBudget processBudget();

struct SolveMemory {
    std::uint64_t perSolver = 0;  // bytes a further worker's solver adds (method, calibration)
    // Bytes the whole run needs with one solver: the program and its libraries, OpenBLAS's
    // threads, the mesh, the take and the solver. One figure whatever sets the budget.
    std::uint64_t firstRun = 0;
    MemoryBudget budget;
};

// The estimate for a mesh of this size and method, against `budget` (the process's by default).
SolveMemory estimateSolveMemory(int vertices, int faces, SolverOptions::Method method,
                                const MemoryBudget& budget);
SolveMemory estimateSolveMemory(int vertices, int faces, SolverOptions::Method method);

// Throws Error naming `meshPath`, its faces and vertices, what its solve would need and the
// budget, when the run with one solver does not fit the budget.
void checkSolveFits(int vertices, int faces, const std::string& meshPath,
                    SolverOptions::Method method, const MemoryBudget& budget);

// Tests only: a budget below the machine's, as a small ulimit -v would set, for a process that
// cannot run under one (the app's window needs far more address space than a small mesh's
// solve). 0 gives the machine's budget back.
void limitSolveMemoryForTests(std::uint64_t bytes);

// How many solvers may run at once: at most `wanted`, at least one, all of them within half the
// budget (the rest is the user's other work, and the outputs' buffers).
int solversThatFit(const SolveMemory& memory, int wanted);

}  // namespace boneless
