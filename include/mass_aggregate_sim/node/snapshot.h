#pragma once

#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <mutex>
#include <string>
#include <utility>
#include <vector>

#include "mass_aggregate_sim/engine/world/world.h"
#include "mass_aggregate_sim/node/body_snapshot.h"

namespace mass_aggregate_sim {
namespace node {

// A link as drawn: its two ends and its tension (N, negative when compressed).
struct LinkSegment {
  engine::Vec3 a;
  engine::Vec3 b;
  engine::Real tension = 0.0;
};

// The part of the world a publisher needs, copied by the world thread so that messages are built
// on another thread. Filling one reuses its buffers: after the first, a copy is a memcpy of the
// particle arrays plus one pass over the links.
struct WorldSnapshot {
  std::uint64_t step = 0;
  engine::Real time = 0.0;  // s, since the scene was (re)loaded
  std::vector<std::uint64_t> ids;
  std::vector<std::string> names;
  engine::Vec3Array positions;
  engine::Vec3Array velocities;
  engine::ScalarArray inverse_masses;
  engine::ScalarArray radii;
  // Springs and bungees with k (l - L) (0 for a slack bungee), then cables and rods with the
  // force their constraint applied in the last substep.
  std::vector<LinkSegment> links;
  std::size_t named = 0;  // particles with a name
  BodySnapshot bodies;
};

// Joints named by `joint_names` (else joint_<id>); body contacts copied when `contacts` is true.
void takeSnapshot(const engine::World& world, WorldSnapshot& out,
                  const JointNames& joint_names = {}, bool contacts = false);

// Hands frames from one producer thread to one consumer thread without copying under the lock:
// the producer fills back(), publish() swaps it with the ready slot; the consumer's take() swaps
// the ready slot with front(). Three buffers, so neither side ever waits for the other's copy.
template <typename Frame>
class FrameExchange {
 public:
  Frame& back() { return buffers_[back_]; }
  void publish() {
    {
      const std::lock_guard<std::mutex> lock(mutex_);
      std::swap(back_, ready_);
      fresh_ = true;
    }
    wake_.notify_one();
  }
  // Waits up to `timeout` for a frame published since the last take (true: front() is it), or
  // until wake() or stop().
  template <typename Duration>
  bool take(const Duration timeout) {
    std::unique_lock<std::mutex> lock(mutex_);
    wake_.wait_for(lock, timeout, [this] { return fresh_ || woken_ || stopped_; });
    woken_ = false;
    if (!fresh_) return false;
    std::swap(front_, ready_);
    fresh_ = false;
    return true;
  }
  const Frame& front() const { return buffers_[front_]; }
  void wake() {
    {
      const std::lock_guard<std::mutex> lock(mutex_);
      woken_ = true;
    }
    wake_.notify_one();
  }
  void stop() {
    {
      const std::lock_guard<std::mutex> lock(mutex_);
      stopped_ = true;
    }
    wake_.notify_one();
  }
  bool stopped() {
    const std::lock_guard<std::mutex> lock(mutex_);
    return stopped_;
  }

 private:
  Frame buffers_[3];
  int back_ = 0;
  int ready_ = 1;
  int front_ = 2;
  bool fresh_ = false;
  bool woken_ = false;
  bool stopped_ = false;
  std::mutex mutex_;
  std::condition_variable wake_;
};

}  // namespace node
}  // namespace mass_aggregate_sim
