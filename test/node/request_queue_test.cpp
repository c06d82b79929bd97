#include "mass_aggregate_sim/node/request_queue.h"

#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <thread>
#include <vector>

namespace mass_aggregate_sim {
namespace node {
namespace {

TEST(RequestQueueTest, JobsRunOnTheDrainingThreadInOrder) {
  RequestQueue queue;
  std::vector<int> order;
  const std::thread::id owner = std::this_thread::get_id();
  std::atomic<int> answered{0};
  std::vector<std::thread> callers;
  // Queued one after another, so the arrival order is known.
  for (int i = 0; i < 3; ++i) {
    callers.emplace_back([&, i] {
      const bool ran = queue.run([&, i] {
        EXPECT_EQ(std::this_thread::get_id(), owner);
        order.push_back(i);
      });
      EXPECT_TRUE(ran);
      ++answered;
    });
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  EXPECT_EQ(answered.load(), 0);  // nobody is answered before the owner drains
  queue.drain();
  for (auto& caller : callers) caller.join();
  EXPECT_EQ(answered.load(), 3);
  EXPECT_EQ(order, (std::vector<int>{0, 1, 2}));
}

TEST(RequestQueueTest, StopCancelsQueuedAndLaterJobs) {
  RequestQueue queue;
  bool ran = false;
  bool result = true;
  std::thread caller([&] { result = queue.run([&] { ran = true; }); });
  std::this_thread::sleep_for(std::chrono::milliseconds(20));
  queue.stop();
  caller.join();
  EXPECT_FALSE(result);
  EXPECT_FALSE(queue.run([&] { ran = true; }));
  queue.drain();
  EXPECT_FALSE(ran);
}

}  // namespace
}  // namespace node
}  // namespace mass_aggregate_sim
