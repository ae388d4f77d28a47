#pragma once

// What solving a take needs in memory, estimated up front from the mesh's size, against what the
// process may use: a mesh too large is refused before any work, and no more frames are solved at
// once than fit (each worker holds a solver of its own). Figures: docs/benchmarks.md, "Large
// meshes".

#include <cstdint>
#include <string>

#include "boneless/Reconstruction.h"

namespace boneless {

struct SolveMemory {
    std::uint64_t perSolver = 0;  // bytes one solver of the take holds (method, calibration)
    // Address space the process maps to solve with one solver: the program and its libraries,
    // the mesh, the take and the solver, what an address-space limit (ulimit -v) must hold.
    std::uint64_t addressSpace = 0;
    std::uint64_t budget = 0;  // bytes the process may use
    std::string budgetFrom;    // what sets the budget, for messages ("physical memory", ...)
    bool budgetIsAddressSpace = false;  // the budget is ulimit -v's: addressSpace must fit it
};

// The estimate for a mesh of this size and method, and the budget from the machine: physical
// memory, or less under an address-space limit (ulimit -v) or a cgroup's memory.max (the
// lowest wins; checkSolveFits() in boneless/SolveFits.h refuses what does not fit).
SolveMemory estimateSolveMemory(int vertices, int faces, SolverOptions::Method method);

// Tests only: a budget below the machine's, as a small ulimit -v would set, for a process that
// cannot run under one (the app's window needs far more address space than a small mesh's
// solve). 0 gives the machine's budget back.
void limitSolveMemoryForTests(std::uint64_t bytes);

// How many solvers may run at once: at most `wanted`, at least one, all of them within half the
// budget (the rest is the user's other work, and the outputs' buffers).
int solversThatFit(const SolveMemory& memory, int wanted);

}  // namespace boneless
