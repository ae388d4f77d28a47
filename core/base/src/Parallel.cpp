#include "boneless/Parallel.h"

#include <atomic>
#include <chrono>
#include <condition_variable>
#include <exception>
#include <mutex>
#include <vector>

namespace boneless {

namespace {

thread_local bool insideTask = false;
thread_local int serialScopes = 0;  // RunSerially objects alive on this thread

// Workers spin this long for the next task before they sleep: the solver's loops come in quick
// succession (a coarse level's local steps: a loop every few tens of microseconds), and a
// sleeping worker takes a context switch to wake, which cost more than those loops.
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
            publish(0);
        }
        wake_.notify_all();
        for (auto& w : workers_) w.join();
    }

    // False when another thread's call holds the workers.
    bool tryRun(int count, const std::function<void(int)>& task) {
        std::unique_lock<std::mutex> busy(busy_, std::try_to_lock);
        if (!busy.owns_lock()) return false;
        task_ = &task;
        error_ = nullptr;
        pending_.store(count - 1);
        {
            // Under the lock, so that a worker between its check and its sleep sees it.
            std::lock_guard<std::mutex> lock(mutex_);
            publish(count);
        }
        wake_.notify_all();
        std::exception_ptr mine;
        runTask(task, 0, mine);
        // Done first, this thread takes a share of what the other tasks split up meanwhile.
        while (pending_.load() != 0)
            if (!helpOnce()) std::this_thread::yield();
        task_ = nullptr;
        if (!mine) mine = error_;
        if (mine) std::rethrow_exception(mine);
        return true;
    }

    // A call from inside a task: its tasks are offered to the pool's threads that have finished
    // their own and are waiting, and the calling thread runs whatever nobody else took. False
    // when another such call's tasks are on offer.
    bool tryNested(int count, const std::function<void(int)>& task) {
        Offer offer(task, count);
        {
            std::lock_guard<std::mutex> lock(mutex_);
            if (offer_) return false;
            offer_ = &offer;
            offered_.store(true);
        }
        wake_.notify_all();
        take(offer);
        {
            // Withdrawn, then waited for: a thread that joined may still be running a task.
            std::unique_lock<std::mutex> lock(mutex_);
            offer_ = nullptr;
            offered_.store(false);
            left_.wait(lock, [&] { return offer.helpers == 0; });
        }
        if (offer.error) std::rethrow_exception(offer.error);
        return true;
    }

  private:
    struct Offer {
        Offer(const std::function<void(int)>& t, int c) : task(&t), count(c) {}
        const std::function<void(int)>* task;
        int count;
        std::atomic<int> next{0};  // the next task to take
        int helpers = 0;           // threads inside take(), but the caller (under mutex_)
        std::exception_ptr error;  // the first (under mutex_)
    };

    static void runTask(const std::function<void(int)>& task, int t, std::exception_ptr& error) {
        const bool outer = insideTask;
        insideTask = true;
        try {
            task(t);
        } catch (...) {
            error = std::current_exception();
        }
        insideTask = outer;
    }

    // Runs the offer's tasks that nobody has taken yet; whether it ran any.
    bool take(Offer& offer) {
        bool any = false;
        for (int t; (t = offer.next.fetch_add(1)) < offer.count; any = true) {
            std::exception_ptr error;
            runTask(*offer.task, t, error);
            if (error) {
                std::lock_guard<std::mutex> lock(mutex_);
                if (!offer.error) offer.error = error;
            }
        }
        return any;
    }

    // Joins the tasks on offer, if any; whether it ran one.
    bool helpOnce() {
        if (!offered_.load()) return false;
        Offer* offer;
        {
            std::lock_guard<std::mutex> lock(mutex_);
            offer = offer_;
            if (!offer) return false;
            ++offer->helpers;
        }
        const bool any = take(*offer);
        {
            std::lock_guard<std::mutex> lock(mutex_);
            if (--offer->helpers == 0) left_.notify_all();
        }
        return any;
    }

    void work(int t) {
        unsigned long seen = 0;
        for (;;) {
            const auto until = std::chrono::steady_clock::now() + spinTime;
            while (generation_.load() == seen && !offered_.load() &&
                   std::chrono::steady_clock::now() < until) {
            }
            if (generation_.load() == seen && !offered_.load()) {
                std::unique_lock<std::mutex> lock(mutex_);
                wake_.wait(lock, [&] { return generation_.load() != seen || offer_; });
            }
            if (generation_.load() == seen) {
                if (!helpOnce()) std::this_thread::yield();
                continue;
            }
            if (stopping_) return;
            seen = generation_.load();
            if (t >= static_cast<int>(seen & 0xff)) continue;  // not one of this call's tasks
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
    std::mutex mutex_;  // for sleeping and waking, error_ and offer_
    std::condition_variable wake_;
    std::condition_variable left_;  // an offer's last helper has left
    // Written by the calling thread before generation_ moves on, read by workers after.
    const std::function<void(int)>* task_ = nullptr;
    bool stopping_ = false;
    std::exception_ptr error_;
    // A call's number and, in its low byte, its task count, in one word: a worker that read
    // them apart could take a later call's count for the call it saw, and run a task twice.
    std::atomic<unsigned long> generation_{0};
    void publish(int count) {
        generation_.store((((generation_.load() >> 8) + 1) << 8) | static_cast<unsigned>(count));
    }
    std::atomic<int> pending_{0};
    Offer* offer_ = nullptr;            // a nested call's tasks (under mutex_)
    std::atomic<bool> offered_{false};  // offer_ is set: checked without the lock
    std::vector<std::thread> workers_;
};

WorkerPool& pool() {
    static WorkerPool instance;
    return instance;
}

}  // namespace

RunSerially::RunSerially() {
    ++serialScopes;
}
RunSerially::~RunSerially() {
    --serialScopes;
}

void runOnWorkers(int count, const std::function<void(int)>& task) {
    // More tasks than the pool has threads (one core: none) run one after the other: a task left
    // to a worker that does not exist would never start, and the call would wait for it forever.
    if (count > 1 && count <= solverThreadCount() && serialScopes == 0) {
        if (insideTask ? pool().tryNested(count, task) : pool().tryRun(count, task)) return;
    }
    for (int t = 0; t < count; ++t) task(t);
}

}  // namespace boneless
