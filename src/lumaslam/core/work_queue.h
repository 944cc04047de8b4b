#pragma once
// A FIFO of work items handled one at a time by a handler, either in the queue's own thread
// (startThread) or in the owner's thread (processOne / processPending, the Pipeline's
// sequential mode). The one queue type of the pipeline: every core::Stage (stage.h) runs on
// one. The owner starts the thread once the state its handler uses is built, and calls
// shutdown() or stop() before destroying that state.
#include <condition_variable>
#include <cstddef>
#include <deque>
#include <functional>
#include <mutex>
#include <optional>
#include <thread>
#include <utility>

namespace lumaslam::core {

// What push() does when the queue holds `capacity` items.
enum class WhenFull {
  drop_oldest,  // the oldest queued item is dropped (loop closing's keyframes)
  block,        // push waits for room; without a thread it first handles the oldest item itself
};

template <typename T>
class WorkQueue {
 public:
  struct Options {
    std::size_t capacity = 0;  // 0: unbounded
    WhenFull when_full = WhenFull::drop_oldest;
    // Called with the queue's lock held, after an item is queued / before one is handled.
    std::function<void()> on_push = {};
    std::function<void()> on_take = {};
  };

  explicit WorkQueue(std::function<void(T&)> handler, Options options = {})
      : handler_(std::move(handler)), options_(std::move(options)) {}
  ~WorkQueue() { shutdown(); }
  WorkQueue(const WorkQueue&) = delete;
  WorkQueue& operator=(const WorkQueue&) = delete;

  // Threaded mode: items are handled in a thread of the queue from now on.
  void startThread() {
    std::lock_guard lock(mutex_);
    if (!thread_.joinable() && !stopping_) thread_ = std::thread([this] { run(); });
  }

  // Returns false, dropping the item, once stop() was called.
  bool push(T item) {
    {
      std::unique_lock lock(mutex_);
      if (options_.when_full == WhenFull::block) makeRoom(lock);
      if (stopped_) return false;
      items_.push_back(std::move(item));
      while (options_.capacity > 0 && items_.size() > options_.capacity) items_.pop_front();
      if (options_.on_push) options_.on_push();
    }
    changed_.notify_all();
    return true;
  }

  // Sequential mode: handles the oldest queued item now, in the caller's thread; false when
  // there was none.
  bool processOne() {
    auto item = take();
    if (!item) return false;
    handler_(*item);
    return true;
  }
  // Sequential mode: handles every queued item now, in the caller's thread.
  void processPending() {
    while (processOne()) {
    }
  }

  // Threaded mode: blocks until the queue is empty and no item is being handled.
  void waitUntilIdle() {
    std::unique_lock lock(mutex_);
    changed_.wait(lock, [this] { return idleLocked(); });
  }
  // The same, for at most `timeout`; returns whether the queue is idle.
  template <typename Duration>
  bool waitUntilIdleFor(Duration timeout) {
    std::unique_lock lock(mutex_);
    return changed_.wait_for(lock, timeout, [this] { return idleLocked(); });
  }

  // Stops and joins the thread (idempotent); queued items are handled first.
  void shutdown() {
    {
      std::lock_guard lock(mutex_);
      stopping_ = true;
    }
    changed_.notify_all();
    join();
  }

  // Drops the queued items, lets the one being handled finish, joins (idempotent); later
  // pushes are refused.
  void stop() {
    {
      std::lock_guard lock(mutex_);
      stopping_ = true;
      stopped_ = true;
      items_.clear();
    }
    changed_.notify_all();
    join();
  }

  bool idle() const {
    std::lock_guard lock(mutex_);
    return items_.empty() && !busy_;
  }

  std::size_t size() const {
    std::lock_guard lock(mutex_);
    return items_.size();
  }

 private:
  bool idleLocked() const { return (items_.empty() && !busy_) || !thread_.joinable(); }
  bool full() const { return options_.capacity > 0 && items_.size() >= options_.capacity; }

  // Blocking push: waits for the thread to take an item or, without a thread, handles the
  // oldest items in the caller's thread until there is room.
  void makeRoom(std::unique_lock<std::mutex>& lock) {
    if (thread_.joinable()) {
      changed_.wait(lock, [this] { return stopped_ || !full(); });
      return;
    }
    while (!stopped_ && full()) {
      T oldest = popFront();
      lock.unlock();
      handler_(oldest);
      lock.lock();
    }
  }

  void join() {
    if (thread_.joinable() && thread_.get_id() != std::this_thread::get_id()) thread_.join();
  }

  std::optional<T> take() {
    std::lock_guard lock(mutex_);
    if (items_.empty()) return std::nullopt;
    return popFront();
  }

  T popFront() {
    T item = std::move(items_.front());
    items_.pop_front();
    if (options_.on_take) options_.on_take();
    return item;
  }

  void run() {
    while (true) {
      std::optional<T> item;
      {
        std::unique_lock lock(mutex_);
        changed_.wait(lock, [this] { return stopping_ || !items_.empty(); });
        if (items_.empty()) break;  // stopping, nothing left
        item = popFront();
        busy_ = true;
      }
      changed_.notify_all();  // room for a blocked push
      handler_(*item);
      {
        std::lock_guard lock(mutex_);
        busy_ = false;
      }
      changed_.notify_all();
    }
    changed_.notify_all();
  }

  std::function<void(T&)> handler_;
  Options options_;
  mutable std::mutex mutex_;
  std::condition_variable changed_;
  std::deque<T> items_;
  bool busy_ = false;
  bool stopping_ = false;
  bool stopped_ = false;  // stop(): queued items dropped, pushes refused
  std::thread thread_;
};

}  // namespace lumaslam::core
