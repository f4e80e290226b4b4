// The movie's helper queue (render/batch_worker.hpp): nothing is processed while it is shut,
// a batch is processed in order once it is opened, a waiting push is bounded only while it is
// open, and an error in the helper reaches the producer.
#include <gtest/gtest.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <stdexcept>
#include <thread>
#include <vector>

#include "runout/render/batch_worker.hpp"

namespace runout::render {
namespace {

// What a movie's helper_cores does between steps: ask until the worker is idle.
template <class Worker>
void until_idle(Worker& worker) {
  while (!worker.idle()) std::this_thread::sleep_for(std::chrono::milliseconds(1));
}

TEST(BatchWorker, ProcessesNothingWhileShutThenTheBatchInOrder) {
  std::vector<int> done;
  BatchWorker<int> worker(/*open=*/false, [&](int& item) { done.push_back(item); });
  for (int k = 0; k < 5; ++k) worker.push(k);
  std::this_thread::sleep_for(std::chrono::milliseconds(50));
  EXPECT_TRUE(done.empty());  // read without a lock: the helper has not touched it
  EXPECT_EQ(worker.queued(), 5u);
  worker.set_open(true);
  until_idle(worker);
  EXPECT_EQ(done, (std::vector<int>{0, 1, 2, 3, 4}));
  worker.set_open(false);
  worker.push(5);
  worker.finish();  // finishing processes what is queued, shut or not
  EXPECT_EQ(done.back(), 5);
}

// A movie two batches behind: every physics thread waits for room at once (recorders.cpp).
TEST(BatchWorker, WaitingForRoomOnSeveralThreadsAtOnce) {
  std::atomic<int> processed{0};
  BatchWorker<int> worker(false, [&](int&) {
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
    ++processed;
  });
  for (int k = 0; k < 8; ++k) worker.push(k);
  worker.set_open(true);
  std::vector<std::thread> waiters;
  std::atomic<int> left_at_return{0}, done_at_return{8};
  for (int t = 0; t < 3; ++t)
    waiters.emplace_back([&] {
      worker.wait_for_room(3);
      left_at_return += static_cast<int>(worker.queued());
      done_at_return = std::min(done_at_return.load(), processed.load());
    });
  for (auto& w : waiters) w.join();
  EXPECT_LE(left_at_return.load(), 3 * 2);  // each returned with fewer than 3 queued
  EXPECT_GE(done_at_return.load(), 5);      // so at least 5 of 8 (one may be in process) were done
  worker.finish();
  EXPECT_EQ(processed.load(), 8);
}

TEST(BatchWorker, PushWaitsForRoomOnlyWhileOpen) {
  std::atomic<int> processed{0};
  BatchWorker<int> shut(false, [&](int&) { ++processed; });
  for (int k = 0; k < 20; ++k) shut.push(k, /*limit=*/2);  // shut: never waits
  EXPECT_EQ(shut.queued(), 20u);
  shut.finish();
  EXPECT_EQ(processed.load(), 20);
}

TEST(BatchWorker, AnErrorInTheHelperReachesTheProducer) {
  BatchWorker<int> worker(true, [](int& item) {
    if (item == 2) throw std::runtime_error("encoder failed");
  });
  worker.push(1);
  worker.push(2);
  until_idle(worker);  // idle once the helper has stopped
  EXPECT_THROW(worker.push(3), std::runtime_error);
  EXPECT_THROW(worker.finish(), std::runtime_error);
}

}  // namespace
}  // namespace runout::render
