#pragma once

#include <algorithm>
#include <thread>
#include <vector>

namespace boneless {

// How many threads the solver's loops use: the machine's cores, at most a handful (the loops are
// memory-bound, more threads stop paying).
inline int solverThreadCount() {
    static const int count =
        std::clamp(static_cast<int>(std::thread::hardware_concurrency()), 1, 4);
    return count;
}

// Runs body(begin, end, thread) over [0, n) split into one contiguous chunk per thread. Plain
// threads rather than OpenMP so that the core needs no compiler flag; the loops it serves take
// milliseconds, so starting threads per call (tens of microseconds) is noise. Small loops stay on
// the calling thread.
template <class Body>
void parallelFor(int n, Body&& body, int minimumPerThread = 2048) {
    const int threads = std::min(solverThreadCount(), std::max(1, n / minimumPerThread));
    if (threads <= 1) {
        body(0, n, 0);
        return;
    }
    std::vector<std::thread> pool;
    pool.reserve(threads - 1);
    for (int t = 1; t < threads; ++t)
        pool.emplace_back([&, t] {
            body(static_cast<int>(static_cast<long>(n) * t / threads),
                 static_cast<int>(static_cast<long>(n) * (t + 1) / threads), t);
        });
    body(0, static_cast<int>(static_cast<long>(n) / threads), 0);
    for (auto& th : pool) th.join();
}

}  // namespace boneless
