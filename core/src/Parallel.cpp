#include "Parallel.h"

#include <atomic>
#include <chrono>
#include <condition_variable>
#include <exception>
#include <mutex>
#include <vector>

namespace boneless {

namespace {

thread_local bool insideTask = false;

// Workers spin this long for the next task before they sleep: the solver's loops come in quick
// succession (conjugate gradients on a coarse level: a loop every few tens of microseconds), and
// a sleeping worker takes a context switch to wake, which cost more than those loops.
constexpr auto spinTime = std::chrono::microseconds(200);

class WorkerPool {
  public:
    WorkerPool() {
        for (int t = 1; t < solverThreadCount(); ++t) workers_.emplace_back([this, t] { work(t); });
    }
    ~WorkerPool() {
        {
            std::lock_guard<std::mutex> lock(mutex_);
            stopping_ = true;
            generation_.fetch_add(1);
        }
        wake_.notify_all();
        for (auto& w : workers_) w.join();
    }

    // False when another thread's call holds the workers.
    bool tryRun(int count, const std::function<void(int)>& task) {
        std::unique_lock<std::mutex> busy(busy_, std::try_to_lock);
        if (!busy.owns_lock()) return false;
        task_ = &task;
        count_ = count;
        error_ = nullptr;
        pending_.store(count - 1);
        {
            // Under the lock, so that a worker between its check and its sleep sees it.
            std::lock_guard<std::mutex> lock(mutex_);
            generation_.fetch_add(1);
        }
        wake_.notify_all();
        std::exception_ptr mine;
        runTask(task, 0, mine);
        while (pending_.load() != 0) std::this_thread::yield();
        task_ = nullptr;
        if (!mine) mine = error_;
        if (mine) std::rethrow_exception(mine);
        return true;
    }

  private:
    static void runTask(const std::function<void(int)>& task, int t, std::exception_ptr& error) {
        insideTask = true;
        try {
            task(t);
        } catch (...) {
            error = std::current_exception();
        }
        insideTask = false;
    }

    void work(int t) {
        unsigned long seen = 0;
        for (;;) {
            const auto until = std::chrono::steady_clock::now() + spinTime;
            while (generation_.load() == seen && std::chrono::steady_clock::now() < until) {
            }
            if (generation_.load() == seen) {
                std::unique_lock<std::mutex> lock(mutex_);
                wake_.wait(lock, [&] { return generation_.load() != seen; });
            }
            if (stopping_) return;
            seen = generation_.load();
            if (t >= count_) continue;
            std::exception_ptr error;
            runTask(*task_, t, error);
            if (error) {
                std::lock_guard<std::mutex> lock(mutex_);
                if (!error_) error_ = error;
            }
            pending_.fetch_sub(1);
        }
    }

    std::mutex busy_;   // held by the call using the workers
    std::mutex mutex_;  // for sleeping and waking, and error_
    std::condition_variable wake_;
    // Written by the calling thread before generation_ moves on, read by workers after.
    const std::function<void(int)>* task_ = nullptr;
    int count_ = 0;
    bool stopping_ = false;
    std::exception_ptr error_;
    std::atomic<unsigned long> generation_{0};
    std::atomic<int> pending_{0};
    std::vector<std::thread> workers_;
};

}  // namespace

void runOnWorkers(int count, const std::function<void(int)>& task) {
    // More tasks than the pool has threads (one core: none) run one after the other: a task left
    // to a worker that does not exist would never start, and the call would wait for it forever.
    if (count > 1 && count <= solverThreadCount() && !insideTask) {
        static WorkerPool pool;
        if (pool.tryRun(count, task)) return;
    }
    for (int t = 0; t < count; ++t) task(t);
}

}  // namespace boneless
