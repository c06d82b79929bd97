#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "mass_aggregate_sim/engine/world/world.h"
#include "mass_aggregate_sim/node/body_requests.h"
#include "mass_aggregate_sim/node/joint_requests.h"

namespace mass_aggregate_sim {
namespace node {

// A body shape as drawn: its geometry and its pose in the world.
struct ShapeView {
  std::size_t body = 0;     // index into BodySnapshot's arrays
  std::uint32_t index = 0;  // the shape's index within its body
  engine::AnyBodyShape geometry;
  engine::Transform pose;
};

// A joint as drawn: where it holds its two ends, and the centres of mass of its body ends.
struct JointView {
  engine::Vec3 anchor_a = engine::Vec3::Zero();
  engine::Vec3 anchor_b = engine::Vec3::Zero();
  bool body_a = false;
  bool body_b = false;
  engine::Vec3 centre_a = engine::Vec3::Zero();
  engine::Vec3 centre_b = engine::Vec3::Zero();
};

// A hinge for ~joint_states: its angle (rad), b's angular velocity relative to a about the axis
// (rad/s) and the torque about the axis that held b in the last substep (N m).
struct HingeState {
  std::string name;
  double position = 0.0;
  double velocity = 0.0;
  double effort = 0.0;
};

// The bodies and joints of the world, copied by the world thread for the publishing thread.
struct BodySnapshot {
  std::vector<std::uint64_t> ids;
  std::vector<std::string> names;
  std::vector<engine::BodyType> types;
  std::vector<engine::Transform> poses;  // each body's own frame
  std::vector<Twist> twists;             // of the frame's origin, world axes
  std::vector<std::uint8_t> sleeping;
  std::vector<double> masses;
  std::vector<ShapeView> shapes;
  std::vector<JointView> joints;
  std::vector<HingeState> hinges;
  // Filled only when asked for (someone listens to ~contacts or contact markers are on).
  std::vector<engine::BodyContactReport> contacts;
  double substep = 0.0;  // s, the last step's substep: force = impulse / substep
  std::size_t named = 0;
  std::size_t joint_count = 0;
  std::size_t islands = 0;  // World::bodyIslandCount()
  std::size_t sleeping_count = 0;
  std::size_t contact_count = 0;  // body contacts with a point in the last step
};

// Fills `out` from the world (reusing its buffers); joints named by `names` (else joint_<id>).
void takeBodySnapshot(const engine::World& world, const JointNames& names, bool contacts,
                      BodySnapshot& out);

}  // namespace node
}  // namespace mass_aggregate_sim
