#include "track/frame_prefetcher.hpp"

#include <ctime>

#include "track/frame_cache.hpp"

namespace vobench {

OwnedFrame::OwnedFrame(const vobench_frame& f) {
    const auto* c = static_cast<const uint8_t*>(f.color->data);
    const auto* d = static_cast<const uint8_t*>(f.depth->data);
    color.assign(c, c + static_cast<std::size_t>(f.color->stride_bytes) * static_cast<std::size_t>(f.color->height));
    depth.assign(d, d + static_cast<std::size_t>(f.depth->stride_bytes) * static_cast<std::size_t>(f.depth->height));
    color_image = *f.color;
    color_image.data = color.data();
    depth_image = *f.depth;
    depth_image.data = depth.data();
    frame = f;
    frame.color = &color_image;
    frame.depth = &depth_image;
}

FramePrefetcher::FramePrefetcher(DatasetInstance& dataset, uint64_t count, std::size_t depth, const FrameCache* cache)
    : dataset_(dataset), cache_(cache), count_(count), depth_(depth) {
    if (depth_ > 0) thread_ = std::thread([this] { run(); });
}

FramePrefetcher::~FramePrefetcher() {
    {
        std::lock_guard<std::mutex> lock(mutex_);
        stop_ = true;
    }
    changed_.notify_all();
    if (thread_.joinable()) thread_.join();
}

std::unique_ptr<OwnedFrame> FramePrefetcher::read(uint64_t i, bool from_cache) {
    if (from_cache) return cache_->load(i);
    auto frame = std::make_unique<OwnedFrame>(dataset_.read(i));
    if (cache_) cache_->store(i, frame->frame);
    return frame;
}

void FramePrefetcher::run() {
    const bool from_cache = cache_ != nullptr && cache_->complete();
    for (uint64_t i = 0; i < count_; ++i) {
        {
            std::unique_lock<std::mutex> lock(mutex_);
            changed_.wait(lock, [this] { return stop_ || queue_.size() < depth_; });
            if (stop_) return;
        }
        std::unique_ptr<OwnedFrame> frame;
        try {
            frame = read(i, from_cache);
            timespec cpu{};
            if (::clock_gettime(CLOCK_THREAD_CPUTIME_ID, &cpu) == 0) reader_cpu_ns_ = int64_t{cpu.tv_sec} * 1000000000 + cpu.tv_nsec;
        } catch (...) {
            std::lock_guard<std::mutex> lock(mutex_);
            error_ = std::current_exception();
            done_ = true;
            changed_.notify_all();
            return;
        }
        std::lock_guard<std::mutex> lock(mutex_);
        queue_.push_back(std::move(frame));
        changed_.notify_all();
    }
    // The whole sequence went through: the cache is complete (a partial run never marks it).
    if (cache_ && !from_cache && count_ == dataset_.info().frame_count) cache_->mark_complete(count_);
    std::lock_guard<std::mutex> lock(mutex_);
    done_ = true;
    changed_.notify_all();
}

std::unique_ptr<OwnedFrame> FramePrefetcher::next() {
    if (depth_ == 0) {
        const bool from_cache = cache_ != nullptr && cache_->complete();
        if (next_index_ < count_) return read(next_index_++, from_cache);
        if (cache_ && !from_cache && count_ == dataset_.info().frame_count && next_index_ == count_) {
            cache_->mark_complete(count_);
            ++next_index_;
        }
        return nullptr;
    }
    std::unique_lock<std::mutex> lock(mutex_);
    changed_.wait(lock, [this] { return !queue_.empty() || done_; });
    if (!queue_.empty()) {
        auto frame = std::move(queue_.front());
        queue_.pop_front();
        changed_.notify_all();
        return frame;
    }
    if (error_) std::rethrow_exception(error_);
    return nullptr;
}

}  // namespace vobench
