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
  return done.get();
}

bool RequestQueue::post(std::function<void()> job) {
  auto queued = std::make_shared<Job>();
  queued->apply = std::move(job);
  const std::lock_guard<std::mutex> lock(mutex_);
  if (stopped_) return false;
  jobs_.push_back(queued);
  return true;
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
  for (auto& job : jobs) job->done.set_value(false);
}

}  // namespace node
}  // namespace mass_aggregate_sim
