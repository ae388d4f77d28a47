// parallelFor hands chunks to a pool of worker threads that outlive the call (Parallel.cpp): these
// pin down that every index is visited once, that errors reach the caller and that calls from
// inside a task or from two threads at once still finish their work.
#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <stdexcept>
#include <thread>
#include <vector>

#include "boneless/Parallel.h"

using namespace boneless;

namespace {

// Visits [0, n) with parallelFor; each index's count ends up in the result.
std::vector<int> visitCounts(int n, int grain) {
    std::vector<std::atomic<int>> seen(n);
    parallelFor(
        n,
        [&](int begin, int end, int t) {
            EXPECT_GE(t, 0);
            EXPECT_LT(t, solverThreadCount());
            for (int i = begin; i < end; ++i) seen[i].fetch_add(1);
        },
        grain);
    std::vector<int> counts(n);
    for (int i = 0; i < n; ++i) counts[i] = seen[i].load();
    return counts;
}

}  // namespace

TEST(Parallel, EveryIndexIsVisitedExactlyOnce) {
    for (int n : {0, 1, 7, 511, 512, 1023, 1024, 4097, 100000})
        for (int grain : {1, 64, 512})
            EXPECT_EQ(visitCounts(n, grain), std::vector<int>(n, 1)) << n << " by " << grain;
}

TEST(Parallel, AnErrorInAnyChunkReachesTheCallerAndThePoolGoesOn) {
    if (solverThreadCount() < 2) GTEST_SKIP() << "one hardware thread: no workers";
    for (int failing : {0, solverThreadCount() - 1}) {
        EXPECT_THROW(parallelFor(
                         4096,
                         [&](int, int, int t) {
                             if (t == failing) throw std::runtime_error("chunk failed");
                         },
                         1),
                     std::runtime_error);
        EXPECT_EQ(visitCounts(4096, 1), std::vector<int>(4096, 1));
    }
}

TEST(Parallel, ACallFromInsideATaskRunsItsWorkToo) {
    std::atomic<int> total{0};
    parallelFor(
        64,
        [&](int begin, int end, int) {
            for (int i = begin; i < end; ++i)
                parallelFor(
                    100, [&](int b, int e, int) { total.fetch_add(e - b); }, 1);
        },
        1);
    EXPECT_EQ(total.load(), 64 * 100);
}

// The local/global method prepares its two levels as two tasks of unequal length; the longer one's
// own loops then use the thread the shorter one has left.
TEST(Parallel, ACallFromInsideATaskUsesAThreadThatHasFinishedItsTask) {
    if (solverThreadCount() < 2) GTEST_SKIP() << "one hardware thread: no workers";
    std::vector<std::thread::id> ranOn(2);
    runOnWorkers(2, [&](int task) {
        if (task == 0) return;  // done at once: its thread waits for task 1
        std::this_thread::sleep_for(std::chrono::milliseconds(20));
        runOnWorkers(2, [&](int t) {
            ranOn[t] = std::this_thread::get_id();
            std::this_thread::sleep_for(std::chrono::milliseconds(100));
        });
    });
    EXPECT_NE(ranOn[0], ranOn[1]);
}

TEST(Parallel, AnErrorInANestedCallReachesItsCaller) {
    if (solverThreadCount() < 2) GTEST_SKIP() << "one hardware thread: no workers";
    bool caught = false;
    runOnWorkers(2, [&](int task) {
        if (task == 0) return;
        try {
            runOnWorkers(2, [&](int t) {
                std::this_thread::sleep_for(std::chrono::milliseconds(20));
                if (t == 1) throw std::runtime_error("nested");
            });
        } catch (const std::runtime_error&) {
            caught = true;
        }
    });
    EXPECT_TRUE(caught);
    EXPECT_EQ(visitCounts(10000, 1), std::vector<int>(10000, 1));  // the pool goes on
}

TEST(Parallel, TwoThreadsCallingAtOnceBothFinish) {
    std::vector<std::vector<int>> results(2);
    std::vector<std::thread> callers;
    for (int c = 0; c < 2; ++c)
        callers.emplace_back([&, c] {
            for (int round = 0; round < 200 && results[c].empty(); ++round) {
                const auto counts = visitCounts(10000, 1);
                if (counts != std::vector<int>(10000, 1)) results[c] = counts;
            }
            if (results[c].empty()) results[c] = {1};
        });
    for (auto& t : callers) t.join();
    EXPECT_EQ(results[0], std::vector<int>{1});
    EXPECT_EQ(results[1], std::vector<int>{1});
}

// The local/global method prepares two levels as two tasks; on a machine with fewer threads
// than tasks (one core: no worker at all) they run one after the other instead of one of them
// waiting for a worker that does not exist.
TEST(Parallel, MoreTasksThanThreadsAllRun) {
    const int count = solverThreadCount() + 1;
    std::vector<std::atomic<int>> ran(count);
    // Were a task left to a missing worker, this call would never return (ctest's timeout).
    runOnWorkers(count, [&](int t) { ran[t].fetch_add(1); });
    for (int t = 0; t < count; ++t) EXPECT_EQ(ran[t].load(), 1) << "task " << t;
}
