#include <gtest/gtest.h>

#include <fstream>

#include "SolveMemory.h"
#include "boneless/Error.h"

using namespace boneless;

namespace {

// The koala's size (docs/benchmarks.md, "Large meshes").
constexpr int kFaces = 99994, kVertices = 50000;

// Whether the koala's solve is refused under `budget`, and the message when it is.
bool refused(const MemoryBudget& budget, std::string* message = nullptr) {
    try {
        checkSolveFits(kVertices, kFaces, "koala.obj", SolverOptions::Method::LocalGlobal, budget);
        return false;
    } catch (const Error& e) {
        if (message) *message = e.what();
        return true;
    }
}

}  // namespace

// Each limit was judged by an estimate of its own: under ulimit -v the whole run's address
// space, under physical memory or a cgroup 4 KB a face against 80 % of it. A cgroup between the
// two let the koala start and run out of memory half a minute in, where ulimit -v refused it.
TEST(SolveMemory, ALimitBetweenTheOldResidentAndAddressSpaceFiguresIsJudgedAlikeByEachCheck) {
    const SolveMemory memory =
        estimateSolveMemory(kVertices, kFaces, SolverOptions::Method::LocalGlobal, {});
    const std::uint64_t resident = std::uint64_t(4096.0 * kFaces / 0.8);
    ASSERT_LT(resident, memory.firstRun);
    const std::uint64_t limit = (resident + memory.firstRun) / 2;

    const std::string cgroupFile = BONELESS_TEST_WORK_DIR + "/memory.max";
    std::ofstream(cgroupFile) << limit << "\n";
    ASSERT_EQ(cgroupMemoryMax(cgroupFile), limit);

    const MemoryBudget physical = lowestBudget(limit, 0, 0);
    const MemoryBudget addressSpace = lowestBudget(0, limit, 0);
    const MemoryBudget cgroup = lowestBudget(0, 0, cgroupMemoryMax(cgroupFile));
    const MemoryBudget test = lowestBudget(0, 0, 0, limit);
    for (const MemoryBudget& budget : {physical, addressSpace, cgroup, test}) {
        std::string message;
        EXPECT_TRUE(refused(budget, &message)) << budget.from;
        EXPECT_NE(message.find(budget.from), std::string::npos) << message;
    }
    // Room for the whole run passes each.
    for (const MemoryBudget& budget :
         {lowestBudget(memory.firstRun, 0, 0), lowestBudget(0, memory.firstRun, 0),
          lowestBudget(0, 0, memory.firstRun), lowestBudget(0, 0, 0, memory.firstRun)})
        EXPECT_FALSE(refused(budget)) << budget.from;
}

TEST(SolveMemory, TheLowestLimitSetsTheBudgetAndACgroupOfMaxSetsNone) {
    const std::string cgroupFile = BONELESS_TEST_WORK_DIR + "/memory.max";
    std::ofstream(cgroupFile) << "max\n";
    EXPECT_EQ(cgroupMemoryMax(cgroupFile), 0u);
    EXPECT_EQ(cgroupMemoryMax(BONELESS_TEST_WORK_DIR + "/none"), 0u);

    const MemoryBudget budget = lowestBudget(8000, 0, 3000, 5000);
    EXPECT_EQ(budget.bytes, 3000u);
    EXPECT_EQ(budget.from, "the cgroup's memory.max");
    EXPECT_EQ(lowestBudget(0, 0, 0).bytes, 0u);
    EXPECT_FALSE(refused(lowestBudget(0, 0, 0)));
}
