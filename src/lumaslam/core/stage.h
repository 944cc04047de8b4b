#pragma once
// A pipeline stage (Kimera-VIO's PipelineModule): inputs queue up in a core::WorkQueue and are
// processed one at a time, each output handed to the stage's output callback. Threaded, the
// stage processes in a thread of its own, started when the stage is built (so a stage is the
// last member of its owner: the thread may use everything declared before it). Sequential
// (System.sequential), no thread starts and the owner processes the queue in its own thread
// with processOne / processPending. Local mapping, loop closing, the global BA and detection
// are stages (docs/architecture.md).
#include <cstddef>
#include <functional>
#include <type_traits>
#include <utility>

#include "lumaslam/core/work_queue.h"

namespace lumaslam::core {

struct StageParams {
  bool threaded = true;
  std::size_t capacity = 0;  // 0: unbounded
  WhenFull when_full = WhenFull::drop_oldest;
};

template <typename Out>
struct StageOutput {
  using type = std::function<void(Out&&)>;
};
template <>
struct StageOutput<void> {
  using type = std::nullptr_t;
};

template <typename In, typename Out = void>
class Stage {
 public:
  using Process = std::function<Out(In&)>;
  // Called in the thread that processed the input, with its output.
  using Output = typename StageOutput<Out>::type;
  // Hooks called with the queue's lock held, after an input is queued / before one is taken.
  struct Hooks {
    std::function<void()> on_push = {};
    std::function<void()> on_take = {};
  };

  Stage(Process process, Output output, StageParams params,
        Hooks hooks = {}) requires(!std::is_void_v<Out>)
      : queue_(handlerOf(std::move(process), std::move(output)), optionsOf(params, hooks)) {
    if (params.threaded) queue_.startThread();
  }
  Stage(Process process, StageParams params, Hooks hooks = {}) requires std::is_void_v<Out>
      : queue_(handlerOf(std::move(process), nullptr), optionsOf(params, hooks)) {
    if (params.threaded) queue_.startThread();
  }
  ~Stage() { queue_.shutdown(); }
  Stage(const Stage&) = delete;
  Stage& operator=(const Stage&) = delete;

  // Queues an input (WhenFull decides what happens when the queue is full); false once
  // stop() was called.
  bool push(In input) { return queue_.push(std::move(input)); }
  // Sequential mode: process the oldest input / every queued input in the caller's thread.
  bool processOne() { return queue_.processOne(); }
  void processPending() { queue_.processPending(); }
  // Threaded mode: wait until nothing is queued or being processed.
  void waitUntilIdle() { queue_.waitUntilIdle(); }
  template <typename Duration>
  bool waitUntilIdleFor(Duration timeout) {
    return queue_.waitUntilIdleFor(timeout);
  }
  bool idle() const { return queue_.idle(); }
  std::size_t size() const { return queue_.size(); }
  // Processes what is queued, then joins (idempotent).
  void shutdown() { queue_.shutdown(); }
  // Drops what is queued, lets the running input finish, joins (idempotent).
  void stop() { queue_.stop(); }

 private:
  static typename WorkQueue<In>::Options optionsOf(const StageParams& params, Hooks& hooks) {
    return {params.capacity, params.when_full, std::move(hooks.on_push), std::move(hooks.on_take)};
  }
  static std::function<void(In&)> handlerOf(Process process, Output output) {
    if constexpr (std::is_void_v<Out>) {
      return [process = std::move(process)](In& input) { process(input); };
    } else {
      return [process = std::move(process), output = std::move(output)](In& input) {
        Out result = process(input);
        if (output) output(std::move(result));
      };
    }
  }

  WorkQueue<In> queue_;
};

}  // namespace lumaslam::core
