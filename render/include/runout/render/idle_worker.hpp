// A bounded queue drained by one helper thread that runs only on cores the simulation leaves
// idle (Linux SCHED_IDLE): preempting a physics thread mid-phase would stall its partner at
// the next barrier, so a frame would cost twice its CPU time. When every core is stepping,
// items wait; when the queue is full the producer waits and both cores work the queue.
// The first error the worker raises is rethrown to the producer.
#pragma once

#include <pthread.h>
#include <sched.h>

#include <condition_variable>
#include <cstddef>
#include <deque>
#include <exception>
#include <functional>
#include <mutex>
#include <thread>

namespace runout::render {

template <class Item>
class IdleWorker {
 public:
  // `process` runs on the worker for each item, in order; `on_finish` runs on it after the
  // last item when finish() is called (not when the worker is abandoned).
  IdleWorker(std::size_t capacity, std::function<void(Item&)> process, std::function<void()> on_finish = {})
      : capacity_(capacity), process_(std::move(process)), on_finish_(std::move(on_finish)),
        thread_([this] { run(); }) {}

  ~IdleWorker() {  // abandoned: queued items are dropped
    {
      std::lock_guard lock(mutex_);
      queue_.clear();
      closing_ = abandoned_ = true;
    }
    changed_.notify_all();
    if (thread_.joinable()) thread_.join();
  }
  IdleWorker(const IdleWorker&) = delete;
  IdleWorker& operator=(const IdleWorker&) = delete;

  void push(Item item) {
    std::unique_lock lock(mutex_);
    changed_.wait(lock, [&] { return queue_.size() < capacity_ || done_; });
    if (error_) std::rethrow_exception(error_);
    queue_.push_back(std::move(item));
    lock.unlock();
    changed_.notify_all();
  }

  // The queue is full: a push would wait.
  bool full() {
    std::lock_guard lock(mutex_);
    return queue_.size() >= capacity_ && !done_;
  }
  // Waits until a push would not; any number of threads may wait at once.
  void wait_for_room() {
    std::unique_lock lock(mutex_);
    changed_.wait(lock, [&] { return queue_.size() < capacity_ || done_; });
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
    sched_param param{};
    pthread_setschedparam(pthread_self(), SCHED_IDLE, &param);  // best effort
    try {
      for (;;) {
        Item item;
        {
          std::unique_lock lock(mutex_);
          changed_.wait(lock, [&] { return !queue_.empty() || closing_; });
          if (queue_.empty()) break;
          item = std::move(queue_.front());
          queue_.pop_front();
        }
        changed_.notify_all();
        process_(item);
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
    changed_.notify_all();
  }

  std::size_t capacity_;
  std::function<void(Item&)> process_;
  std::function<void()> on_finish_;
  std::mutex mutex_;
  std::condition_variable changed_;
  std::deque<Item> queue_;
  bool closing_ = false, abandoned_ = false, done_ = false;
  std::exception_ptr error_;
  std::thread thread_;  // last: starts after the members it uses exist
};

}  // namespace runout::render
