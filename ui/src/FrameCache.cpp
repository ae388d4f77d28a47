#include "boneless/ui/FrameCache.h"

namespace boneless::ui {

void FrameCache::setLimit(std::size_t bytes) {
    limit_ = bytes;
    while (bytes_ > limit_ && !order_.empty()) evictOne();
}

std::shared_ptr<const FrameResult> FrameCache::use(int frame) {
    auto it = entries_.find(frame);
    if (it == entries_.end()) return nullptr;
    order_.splice(order_.begin(), order_, it->second.second);
    return it->second.first;
}

void FrameCache::insert(std::shared_ptr<const FrameResult> result) {
    if (auto it = entries_.find(result->frame); it != entries_.end()) {
        bytes_ -= it->second.first->bytes();
        order_.erase(it->second.second);
        entries_.erase(it);
    }
    const int frame = result->frame;
    lastFrameBytes_ = result->bytes();
    bytes_ += lastFrameBytes_;
    order_.push_front(frame);
    entries_[frame] = {std::move(result), order_.begin()};
    while (bytes_ > limit_ && order_.size() > 1) evictOne();
}

void FrameCache::clear() {
    order_.clear();
    entries_.clear();
    bytes_ = 0;
}

void FrameCache::evictOne() {
    auto victim = entries_.find(order_.back());
    bytes_ -= victim->second.first->bytes();
    entries_.erase(victim);
    order_.pop_back();
}

}  // namespace boneless::ui
