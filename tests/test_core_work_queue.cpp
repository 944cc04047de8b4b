#include "lumaslam/core/work_queue.h"

#include <atomic>
#include <chrono>
#include <future>
#include <thread>
#include <vector>

#include <gtest/gtest.h>

namespace {

using lumaslam::core::WorkQueue;

TEST(CoreWorkQueue, SequentialModeHandlesItemsInOrderInTheCallersThread) {
  std::vector<int> handled;
  const auto caller = std::this_thread::get_id();
  bool other_thread = false;
  WorkQueue<int> queue([&](int& item) {
    handled.push_back(item);
    other_thread = other_thread || std::this_thread::get_id() != caller;
  });
  for (int i = 0; i < 5; ++i) queue.push(i);
  EXPECT_EQ(queue.size(), 5U);
  EXPECT_FALSE(queue.idle());
  EXPECT_TRUE(handled.empty());  // nothing runs before processPending()
  queue.processPending();
  EXPECT_EQ(handled, (std::vector<int>{0, 1, 2, 3, 4}));
  EXPECT_FALSE(other_thread);
  EXPECT_TRUE(queue.idle());
}

// The Pipeline's bounded wait for a busy mapper (TrackerParams::wait_for_busy_mapper).
TEST(CoreWorkQueue, WaitUntilIdleForReportsWhetherTheQueueGotIdle) {
  std::promise<void> release;
  std::shared_future<void> released = release.get_future().share();
  std::atomic<bool> started{false};
  WorkQueue<int> queue([&](int&) {
    started = true;
    released.wait();
  });
  EXPECT_TRUE(
      queue.waitUntilIdleFor(std::chrono::milliseconds(0)));  // no thread: nothing to wait for
  queue.startThread();
  queue.push(1);
  while (!started) std::this_thread::yield();
  EXPECT_FALSE(queue.waitUntilIdleFor(std::chrono::milliseconds(20)));  // handler blocked
  release.set_value();
  EXPECT_TRUE(queue.waitUntilIdleFor(std::chrono::seconds(60)));
  EXPECT_TRUE(queue.idle());
}

TEST(CoreWorkQueue, CapacityDropsTheOldestItems) {
  std::vector<int> handled;
  WorkQueue<int> queue([&](int& item) { handled.push_back(item); }, {.capacity = 3});
  for (int i = 0; i < 7; ++i) queue.push(i);
  EXPECT_EQ(queue.size(), 3U);
  queue.processPending();
  EXPECT_EQ(handled, (std::vector<int>{4, 5, 6}));
}

TEST(CoreWorkQueue, HooksRunOnPushAndTake) {
  int pushes = 0;
  int takes = 0;
  WorkQueue<int> queue([](int&) {}, {.on_push = [&] { ++pushes; }, .on_take = [&] { ++takes; }});
  queue.push(1);
  queue.push(2);
  EXPECT_EQ(pushes, 2);
  EXPECT_EQ(takes, 0);
  queue.processPending();
  EXPECT_EQ(takes, 2);
}

TEST(CoreWorkQueue, ThreadedModeHandlesEveryItemInItsOwnThread) {
  std::atomic<int> sum{0};
  std::atomic<bool> in_caller_thread{false};
  const auto caller = std::this_thread::get_id();
  WorkQueue<int> queue([&](int& item) {
    if (std::this_thread::get_id() == caller) in_caller_thread = true;
    std::this_thread::sleep_for(std::chrono::microseconds(100));  // let items pile up
    sum += item;
  });
  queue.startThread();
  for (int i = 1; i <= 100; ++i) queue.push(i);
  queue.waitUntilIdle();
  EXPECT_EQ(sum, 5050);
  EXPECT_TRUE(queue.idle());
  EXPECT_FALSE(in_caller_thread);
}

TEST(CoreWorkQueue, ShutdownHandlesQueuedItemsFirstAndIsIdempotent) {
  std::atomic<int> handled{0};
  WorkQueue<int> queue([&](int&) {
    std::this_thread::sleep_for(std::chrono::microseconds(200));
    ++handled;
  });
  queue.startThread();
  for (int i = 0; i < 50; ++i) queue.push(i);
  queue.shutdown();
  EXPECT_EQ(handled, 50);
  queue.shutdown();
  queue.waitUntilIdle();  // returns at once: no thread
}

}  // namespace
