#pragma once
// One way to run a job beside the caller's own work (the right image of a stereo pair, the
// homography of the two-view initializer): in a thread of its own, or, in sequential mode
// (System.sequential), in the caller's thread when its result is asked for. Either way the
// caller collects the result, or the job's exception, with get() on the returned future.
#include <future>
#include <type_traits>
#include <utility>

namespace lumaslam::core {

// threaded: std::async in a new thread, started now. Not threaded: nothing starts; `job`
// runs in the thread that calls get(), during that call (std::launch::deferred).
template <typename Job>
std::future<std::invoke_result_t<std::decay_t<Job>>> startSideJob(bool threaded, Job&& job) {
  const auto policy = threaded ? std::launch::async : std::launch::deferred;
  return std::async(policy, std::forward<Job>(job));
}

}  // namespace lumaslam::core
