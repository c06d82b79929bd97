#pragma once
// A joint as the body solver sees it during one step: its two solver bodies (kNoBody: a fixed
// body, the world), its anchors from their centres of mass when the step began, where those
// centres were and how the bodies were turned. The joint's kind reads its own data (axes, limits,
// motor) from the joint and keeps its accumulated impulses there (they warm start the next step).

#include <cstdint>
#include <vector>

#include "engine/bodies/softness.h"
#include "engine/bodies/solver_body.h"

namespace mass_aggregate_sim {
namespace engine {

struct JointRow {
  std::int32_t a = kNoBody;
  std::int32_t b = kNoBody;
  Vec3 r_a = Vec3::Zero();  // anchor on a from a's centre of mass (world), at the step's start
  Vec3 r_b = Vec3::Zero();
  Vec3 center_a = Vec3::Zero();  // a's centre of mass (the anchor itself for the world or a
                                 // particle), at the step's start
  Vec3 center_b = Vec3::Zero();
  Quat q_a = Quat::Identity();  // a's mass frame orientation at the step's start
  Quat q_b = Quat::Identity();
  Softness softness;
  std::uint32_t joint = 0;  // index into its kind's array
};

// One array of rows per joint kind, in JointKinds order.
struct JointRows {
  std::vector<std::vector<JointRow>> of_kind;
};

}  // namespace engine
}  // namespace mass_aggregate_sim
