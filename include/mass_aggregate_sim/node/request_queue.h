#pragma once

#include <chrono>
#include <condition_variable>
#include <deque>
#include <functional>
#include <future>
#include <memory>
#include <mutex>

namespace mass_aggregate_sim {
namespace node {

// Hands work from the service threads to the one thread that owns the world. A caller blocks in
// run() until the owner has applied its job at a step boundary (drain()), or the owner has
// stopped; every queued job either runs exactly once or is cancelled, never dropped.
class RequestQueue {
 public:
  // Returns false when the owner stopped before (or instead of) running the job.
  bool run(std::function<void()> job);
  // Queues the job without waiting for it; false when the owner has stopped.
  bool post(std::function<void()> job);
  // Runs every job queued so far, in arrival order; called by the owner only.
  void drain();
  // Blocks the owner until a job is queued, the queue stops, or `deadline` passes: the owner
  // sleeps between its steps here, so a request is applied at once instead of at the next tick.
  // True when jobs are waiting.
  bool waitUntil(std::chrono::steady_clock::time_point deadline);
  // Cancels what is queued and refuses whatever comes later.
  void stop();

 private:
  struct Job {
    std::function<void()> apply;
    std::promise<bool> done;
  };
  std::mutex mutex_;
  std::condition_variable queued_;
  std::deque<std::shared_ptr<Job>> jobs_;
  bool stopped_ = false;
};

}  // namespace node
}  // namespace mass_aggregate_sim
