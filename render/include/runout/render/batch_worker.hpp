// A queue of items processed in order by one helper thread, only while its producer lets it
// (open): a movie's frames are drawn and encoded a batch at a time, on a core the physics
// leaves them meanwhile (Observer::helper_cores), and after the run.
// The helper runs at normal priority, so other processes cannot starve it: the SCHED_IDLE
// helpers it replaces got no CPU while other programs kept every core busy (the 5 s quick
// movie took 200 s; docs/performance_log.md, issue 12). The first error it raises is rethrown to
// the producer.
#pragma once

#include <condition_variable>
#include <cstddef>
#include <deque>
#include <exception>
#include <functional>
#include <mutex>
#include <thread>

namespace runout::render {

template <class Item>
class BatchWorker {
 public:
  // `process` runs on the helper for each item, in order; `on_finish` runs on it after the
  // last item when finish() is called (not when the worker is abandoned).
  BatchWorker(bool open, std::function<void(Item&)> process, std::function<void()> on_finish = {})
      : open_(open), process_(std::move(process)), on_finish_(std::move(on_finish)), thread_([this] { run(); }) {}

  ~BatchWorker() {  // abandoned: queued items are dropped
    {
      std::lock_guard lock(mutex_);
      queue_.clear();
      closing_ = abandoned_ = true;
    }
    changed_.notify_all();
    if (thread_.joinable()) thread_.join();
  }
  BatchWorker(const BatchWorker&) = delete;
  BatchWorker& operator=(const BatchWorker&) = delete;

  // Queues an item; waits only while the worker is open with `limit` items queued (0: never).
  void push(Item item, std::size_t limit = 0) {
    std::unique_lock lock(mutex_);
    changed_.wait(lock, [&] { return limit == 0 || !open_ || queue_.size() < limit || done_; });
    if (error_) std::rethrow_exception(error_);
    queue_.push_back(std::move(item));
    lock.unlock();
    changed_.notify_all();
  }
  // Until a push with this limit would not wait; any number of threads may wait at once.
  void wait_for_room(std::size_t limit) {
    std::unique_lock lock(mutex_);
    changed_.wait(lock, [&] { return !open_ || queue_.size() < limit || done_; });
  }
  std::size_t queued() {
    std::lock_guard lock(mutex_);
    return queue_.size();
  }
  // Nothing queued or in process (or stopped on an error); cheap enough to ask every step.
  // Rethrows nothing: the next push or finish does.
  bool idle() {
    std::lock_guard lock(mutex_);
    return (queue_.empty() && !busy_) || done_;
  }
  void set_open(bool open) {
    {
      std::lock_guard lock(mutex_);
      open_ = open;
    }
    changed_.notify_all();
  }
  void finish() {
    {
      std::lock_guard lock(mutex_);
      closing_ = true;
    }
    changed_.notify_all();
    if (thread_.joinable()) thread_.join();
    if (error_) std::rethrow_exception(error_);
  }

 private:
  void run() {
    try {
      for (;;) {
        Item item;
        {
          std::unique_lock lock(mutex_);
          changed_.wait(lock, [&] { return (open_ && !queue_.empty()) || closing_; });
          if (queue_.empty()) break;  // closing
          item = std::move(queue_.front());
          queue_.pop_front();
          busy_ = true;
        }
        changed_.notify_all();
        process_(item);
        {
          std::lock_guard lock(mutex_);
          busy_ = false;
        }
        changed_.notify_all();
      }
      bool abandoned;
      {
        std::lock_guard lock(mutex_);
        abandoned = abandoned_;
      }
      if (!abandoned && on_finish_) on_finish_();
    } catch (...) {
      std::lock_guard lock(mutex_);
      error_ = std::current_exception();
      queue_.clear();
    }
    std::lock_guard lock(mutex_);
    done_ = true;
    busy_ = false;
    changed_.notify_all();
  }

  bool open_;
  std::function<void(Item&)> process_;
  std::function<void()> on_finish_;
  std::mutex mutex_;
  std::condition_variable changed_;
  std::deque<Item> queue_;
  bool busy_ = false, closing_ = false, abandoned_ = false, done_ = false;
  std::exception_ptr error_;
  std::thread thread_;  // last: starts after the members it uses exist
};

}  // namespace runout::render
