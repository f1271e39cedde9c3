#pragma once
// A bounded FIFO between two pipeline threads (METHOD.md §1). push() blocks
// while the queue is full (offline mode: nothing is ever lost, so the result
// does not depend on thread timing); tryPush() refuses instead (real-time
// mode: the producer drops the item and counts it). close() ends the stream:
// pop() returns nullopt once the queue is closed and empty, and a producer
// learns from push() or closedBy() that nobody takes its items any more.
#include <chrono>
#include <condition_variable>
#include <deque>
#include <mutex>
#include <optional>

namespace edgevio::pipeline {

template <class T>
class BoundedQueue {
 public:
  explicit BoundedQueue(std::size_t capacity) : capacity_(capacity < 1 ? 1 : capacity) {}

  /// Blocks while full; false (the item dropped) when the queue is or gets closed.
  bool push(T item) {
    std::unique_lock<std::mutex> lock(mutex_);
    not_full_.wait(lock, [&] { return items_.size() < capacity_ || closed_; });
    if (closed_) return false;
    items_.push_back(std::move(item));
    not_empty_.notify_one();
    return true;
  }
  bool tryPush(T item) {
    std::lock_guard<std::mutex> lock(mutex_);
    if (closed_ || items_.size() >= capacity_) return false;
    items_.push_back(std::move(item));
    not_empty_.notify_one();
    return true;
  }
  std::optional<T> pop() {
    std::unique_lock<std::mutex> lock(mutex_);
    not_empty_.wait(lock, [&] { return !items_.empty() || closed_; });
    if (items_.empty()) return std::nullopt;
    T item = std::move(items_.front());
    items_.pop_front();
    not_full_.notify_one();
    return item;
  }
  /// Waits until `deadline` or the queue's closing, whichever comes first; true when closed.
  template <class Clock, class Duration>
  bool closedBy(const std::chrono::time_point<Clock, Duration>& deadline) {
    std::unique_lock<std::mutex> lock(mutex_);
    return closed_wait_.wait_until(lock, deadline, [&] { return closed_; });
  }
  void close() {
    std::lock_guard<std::mutex> lock(mutex_);
    closed_ = true;
    not_empty_.notify_all();
    not_full_.notify_all();
    closed_wait_.notify_all();
  }

 private:
  std::size_t capacity_;
  std::deque<T> items_;
  bool closed_ = false;
  std::mutex mutex_;
  std::condition_variable not_empty_, not_full_, closed_wait_;
};

}  // namespace edgevio::pipeline
