#pragma once
// A blocking multi-producer queue: DDS listeners push, the one worker pops.

#include <chrono>
#include <condition_variable>
#include <deque>
#include <mutex>
#include <optional>
#include <utility>

namespace pena::services {

template <class T>
class WorkQueue {
 public:
  // Adds an item (any thread).
  void Push(T item) {
    {
      const std::lock_guard<std::mutex> lock(mutex_);
      items_.push_back(std::move(item));
    }
    ready_.notify_one();
  }
  // The oldest item, waiting at most `timeout`; nullopt if none came.
  template <class Rep, class Period>
  std::optional<T> PopFor(std::chrono::duration<Rep, Period> timeout) {
    std::unique_lock<std::mutex> lock(mutex_);
    if (!ready_.wait_for(lock, timeout, [this] { return !items_.empty(); })) return std::nullopt;
    T item = std::move(items_.front());
    items_.pop_front();
    return item;
  }
  // The oldest item if there is one, without waiting.
  std::optional<T> TryPop() { return PopFor(std::chrono::seconds(0)); }
  // Items waiting now.
  std::size_t size() const {
    const std::lock_guard<std::mutex> lock(mutex_);
    return items_.size();
  }

 private:
  mutable std::mutex mutex_;
  std::condition_variable ready_;
  std::deque<T> items_;
};

}  // namespace pena::services
