#pragma once

#include <cstddef>
#include <list>
#include <memory>
#include <unordered_map>

#include "boneless/ui/FrameSolver.h"

namespace boneless::ui {

// Solved frames by frame number, least recently used out first once their bytes pass a cap.
// Not thread-safe: FrameSolver guards it with its mutex.
class FrameCache {
  public:
    explicit FrameCache(std::size_t limitBytes = 0) : limit_(limitBytes) {}

    // Evicts least recently used frames until the cache fits (all of them if need be).
    void setLimit(std::size_t bytes);
    std::size_t limit() const { return limit_; }
    std::size_t bytes() const { return bytes_; }
    int size() const { return int(entries_.size()); }
    bool contains(int frame) const { return entries_.count(frame) > 0; }
    // The frame's result, marked as the most recently used; null when absent.
    std::shared_ptr<const FrameResult> use(int frame);
    // Replaces any result of the same frame. The newest is kept even when it alone is over the
    // cap, so that the frame on screen can always be served again.
    void insert(std::shared_ptr<const FrameResult> result);
    void clear();
    // The size of the last frame inserted (0 before any): how many more would fit.
    std::size_t lastFrameBytes() const { return lastFrameBytes_; }

  private:
    void evictOne();

    std::list<int> order_;  // most recently used first
    std::unordered_map<int, std::pair<std::shared_ptr<const FrameResult>, std::list<int>::iterator>>
        entries_;
    std::size_t bytes_ = 0, limit_ = 0, lastFrameBytes_ = 0;
};

}  // namespace boneless::ui
