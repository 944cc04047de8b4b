// core::Stage, the one stage mechanism (issue 21), and the queue behaviours it adds to
// core::WorkQueue: blocking pushes, stop(), the output callback.
#include "lumaslam/core/stage.h"

#include <atomic>
#include <chrono>
#include <future>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

#include <gtest/gtest.h>

namespace {

using lumaslam::core::Stage;
using lumaslam::core::WhenFull;
using lumaslam::core::WorkQueue;

TEST(CoreStage, OutputReceivesEveryResultInPushOrderSequentially) {
  std::vector<int> outputs;
  const auto caller = std::this_thread::get_id();
  bool other_thread = false;
  Stage<int, int> stage(
      [&](int& input) {
        other_thread = other_thread || std::this_thread::get_id() != caller;
        return input * input;
      },
      [&](int&& output) { outputs.push_back(output); }, {.threaded = false});
  for (int i = 1; i <= 4; ++i) EXPECT_TRUE(stage.push(i));
  EXPECT_TRUE(outputs.empty());  // nothing runs before the owner asks
  EXPECT_TRUE(stage.processOne());
  EXPECT_EQ(outputs, (std::vector<int>{1}));
  stage.processPending();
  EXPECT_EQ(outputs, (std::vector<int>{1, 4, 9, 16}));
  EXPECT_FALSE(stage.processOne());
  EXPECT_FALSE(other_thread);
}

TEST(CoreStage, ThreadedStageProcessesInItsOwnThread) {
  std::atomic<int> sum{0};
  std::atomic<bool> in_caller_thread{false};
  const auto caller = std::this_thread::get_id();
  Stage<int> stage(
      [&](int& input) {
        if (std::this_thread::get_id() == caller) in_caller_thread = true;
        sum += input;
      },
      {.threaded = true});
  for (int i = 1; i <= 100; ++i) stage.push(i);
  stage.waitUntilIdle();
  EXPECT_EQ(sum, 5050);
  EXPECT_FALSE(in_caller_thread);
}

// Detection's queue: a full queue makes the producer wait, and nothing is dropped. The
// queue's hooks log pushes and takes in the order they happen (under its lock), so the check
// holds under any scheduling; no sleep.
TEST(CoreStage, BlockingPushWaitsForRoomAndDropsNothingThreaded) {
  std::promise<void> release;
  std::shared_future<void> released = release.get_future().share();
  std::vector<int> handled;
  std::mutex handled_mutex;
  std::vector<char> log;  // 'p' push, 't' take; written with the queue's lock held
  Stage<int> stage(
      [&](int& input) {
        released.wait();
        std::lock_guard lock(handled_mutex);
        handled.push_back(input);
      },
      {.threaded = true, .capacity = 2, .when_full = WhenFull::block},
      {.on_push = [&] { log.push_back('p'); }, .on_take = [&] { log.push_back('t'); }});
  stage.push(0);  // taken by the thread, which then waits for the release
  while (stage.size() != 0) std::this_thread::yield();
  stage.push(1);
  stage.push(2);  // the queue is full now
  std::promise<void> pushing;
  std::thread producer([&] {
    pushing.set_value();
    stage.push(3);
  });
  pushing.get_future().wait();  // the producer is at its push, most likely ahead of the release
  release.set_value();
  producer.join();
  stage.waitUntilIdle();
  EXPECT_EQ(handled, (std::vector<int>{0, 1, 2, 3}));
  // Never more than 2 queued: the 4th push came after the thread took item 1 (its 2nd take).
  const std::string events(log.begin(), log.end());
  ASSERT_EQ(events.size(), 8U) << events;
  EXPECT_EQ(events.substr(0, 4), "ptpp") << events;
  int queued = 0;
  for (const char event : events) {
    queued += event == 'p' ? 1 : -1;
    EXPECT_LE(queued, 2) << events;
  }
}

// Sequential, nobody else would make room: the push processes the oldest input itself.
TEST(CoreStage, BlockingPushWithoutThreadProcessesTheOldestInputFirst) {
  std::vector<int> handled;
  Stage<int> stage([&](int& input) { handled.push_back(input); },
                   {.threaded = false, .capacity = 2, .when_full = WhenFull::block});
  stage.push(0);
  stage.push(1);
  EXPECT_TRUE(handled.empty());
  stage.push(2);
  EXPECT_EQ(handled, (std::vector<int>{0}));
  EXPECT_EQ(stage.size(), 2U);
  stage.processPending();
  EXPECT_EQ(handled, (std::vector<int>{0, 1, 2}));
}

TEST(CoreStage, DropOldestKeepsTheNewestInputs) {
  std::vector<int> handled;
  Stage<int> stage([&](int& input) { handled.push_back(input); },
                   {.threaded = false, .capacity = 2, .when_full = WhenFull::drop_oldest});
  for (int i = 0; i < 5; ++i) stage.push(i);
  stage.processPending();
  EXPECT_EQ(handled, (std::vector<int>{3, 4}));
}

TEST(CoreStage, StopDropsQueuedInputsFinishesTheRunningOneAndRefusesPushes) {
  std::promise<void> release;
  std::shared_future<void> released = release.get_future().share();
  std::atomic<bool> started{false};
  std::atomic<int> handled{0};
  Stage<int> stage(
      [&](int&) {
        started = true;
        released.wait();
        ++handled;
      },
      {.threaded = true});
  stage.push(0);
  while (!started) std::this_thread::yield();
  for (int i = 1; i < 5; ++i) stage.push(i);
  std::thread stopper([&] { stage.stop(); });
  while (stage.size() != 0) std::this_thread::yield();  // stop() cleared the queue
  release.set_value();
  stopper.join();
  EXPECT_EQ(handled, 1);  // the running input finished, the 4 queued ones were dropped
  EXPECT_FALSE(stage.push(5));
  stage.stop();  // idempotent
  EXPECT_EQ(handled, 1);
}

TEST(CoreStage, StopReleasesAProducerBlockedOnAFullQueue) {
  std::promise<void> release;
  std::shared_future<void> released = release.get_future().share();
  std::atomic<bool> started{false};
  Stage<int> stage(
      [&](int&) {
        started = true;
        released.wait();
      },
      {.threaded = true, .capacity = 1, .when_full = WhenFull::block});
  stage.push(0);
  while (!started) std::this_thread::yield();
  stage.push(1);  // fills the queue
  std::promise<bool> pushed;
  std::promise<void> pushing;
  std::thread producer([&] {
    pushing.set_value();
    pushed.set_value(stage.push(2));
  });
  // The producer is at its push: most likely blocked when stop() comes; if stop() comes
  // first, the push is refused just the same.
  pushing.get_future().wait();
  std::thread stopper([&] { stage.stop(); });
  auto result = pushed.get_future();
  EXPECT_EQ(result.wait_for(std::chrono::seconds(60)), std::future_status::ready);
  EXPECT_FALSE(result.get());  // refused, not queued
  release.set_value();
  producer.join();
  stopper.join();
}

TEST(CoreStage, ShutdownProcessesWhatIsQueuedFirst) {
  std::atomic<int> handled{0};
  Stage<int> stage(
      [&](int&) {
        std::this_thread::sleep_for(std::chrono::microseconds(200));
        ++handled;
      },
      {.threaded = true});
  for (int i = 0; i < 20; ++i) stage.push(i);
  stage.shutdown();
  EXPECT_EQ(handled, 20);
}

}  // namespace
