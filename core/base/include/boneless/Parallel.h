#pragma once

#include <algorithm>
#include <functional>
#include <thread>

namespace boneless {

// How many threads the solver's loops use: the machine's cores, at most a handful (the loops are
// memory-bound, more threads stop paying).
inline int solverThreadCount() {
    static const int count =
        std::clamp(static_cast<int>(std::thread::hardware_concurrency()), 1, 4);
    return count;
}

// Runs task(0 .. count−1) at once: task 0 on the calling thread, the others on the process's
// worker threads, which start once and then wait for work. Starting threads per call cost tens
// of microseconds, as much as a whole loop over a coarse level's few thousand vertices; waking
// a waiting worker costs a few. A call made from inside a task offers its tasks to the pool's
// threads that have finished theirs and runs what none of them takes: the local/global method
// prepares two levels of unequal cost as two tasks, and the longer one's loops get the core the
// shorter one leaves. A call while another thread's call is running, or from inside a task while
// another such call's tasks are on offer, or with more tasks than solverThreadCount(), runs its
// tasks one after the other on the calling thread.
void runOnWorkers(int count, const std::function<void(int)>& task);

// While one exists on a thread, the loops that thread calls run on it alone: for callers that
// keep every core busy with work of their own (frames solved side by side), where the pool's
// threads would only compete with them.
class RunSerially {
  public:
    RunSerially();
    ~RunSerially();
    RunSerially(const RunSerially&) = delete;
    RunSerially& operator=(const RunSerially&) = delete;
};

// Runs body(begin, end, thread) over [0, n) split into one contiguous chunk per thread (at most
// solverThreadCount()). Plain threads rather than OpenMP so that the core needs no compiler flag.
// Loops shorter than two chunks of minimumPerThread stay on the calling thread.
template <class Body>
void parallelFor(int n, Body&& body, int minimumPerThread = 512) {
    const int threads = std::min(solverThreadCount(), std::max(1, n / minimumPerThread));
    if (threads <= 1) {
        body(0, n, 0);
        return;
    }
    runOnWorkers(threads, [&](int t) {
        body(static_cast<int>(static_cast<long>(n) * t / threads),
             static_cast<int>(static_cast<long>(n) * (t + 1) / threads), t);
    });
}

}  // namespace boneless
