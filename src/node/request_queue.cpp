#include "mass_aggregate_sim/node/request_queue.h"

namespace mass_aggregate_sim {
namespace node {

bool RequestQueue::run(std::function<void()> job) {
  auto queued = std::make_shared<Job>();
  queued->apply = std::move(job);
  std::future<bool> done = queued->done.get_future();
  {
    const std::lock_guard<std::mutex> lock(mutex_);
    if (stopped_) return false;
    jobs_.push_back(queued);
  }
  queued_.notify_one();
  return done.get();
}

bool RequestQueue::post(std::function<void()> job) {
  auto queued = std::make_shared<Job>();
  queued->apply = std::move(job);
  {
    const std::lock_guard<std::mutex> lock(mutex_);
    if (stopped_) return false;
    jobs_.push_back(queued);
  }
  queued_.notify_one();
  return true;
}

bool RequestQueue::waitUntil(const std::chrono::steady_clock::time_point deadline) {
  std::unique_lock<std::mutex> lock(mutex_);
  queued_.wait_until(lock, deadline, [this] { return !jobs_.empty() || stopped_; });
  return !jobs_.empty();
}

void RequestQueue::drain() {
  std::deque<std::shared_ptr<Job>> jobs;
  {
    const std::lock_guard<std::mutex> lock(mutex_);
    jobs.swap(jobs_);
  }
  for (auto& job : jobs) {
    job->apply();
    job->done.set_value(true);
  }
}

void RequestQueue::stop() {
  std::deque<std::shared_ptr<Job>> jobs;
  {
    const std::lock_guard<std::mutex> lock(mutex_);
    stopped_ = true;
    jobs.swap(jobs_);
  }
  queued_.notify_all();
  for (auto& job : jobs) job->done.set_value(false);
}

}  // namespace node
}  // namespace mass_aggregate_sim
