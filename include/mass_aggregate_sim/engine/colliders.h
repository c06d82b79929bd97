#pragma once

#include <Eigen/Geometry>
#include <cstdint>
#include <vector>

#include "mass_aggregate_sim/engine/types.h"

namespace mass_aggregate_sim {
namespace engine {

// Names one static collider; never reused within a world.
using ColliderId = std::uint32_t;

// Restitution e in [0, 1] (v_sep' = -e v_sep) and Coulomb friction mu >= 0 (|j_t| <= mu |j_n|).
struct Material {
  Real restitution = 0.5;
  Real friction = 0.0;
};

// A half-space: solid where normal.x < offset. The ground is {normal = up, offset = 0}.
struct PlaneCollider {
  Vec3 normal = Vec3::UnitZ();
  Real offset = 0.0;
  Material material;
  ColliderId id = 0;
};

struct SphereCollider {
  Vec3 center = Vec3::Zero();
  Real radius = 1.0;
  Material material;
  ColliderId id = 0;
};

// An oriented box; the identity orientation (an axis-aligned box) takes a faster path.
struct BoxCollider {
  Vec3 center = Vec3::Zero();
  Vec3 half_extents = Vec3::Ones();
  Eigen::Quaterniond orientation = Eigen::Quaterniond::Identity();
  Material material;
  ColliderId id = 0;
};

// All points within radius of the segment from a to b.
struct CapsuleCollider {
  Vec3 a = Vec3::Zero();
  Vec3 b = Vec3::UnitZ();
  Real radius = 0.5;
  Material material;
  ColliderId id = 0;
};

// Every static collider of a world, one array per shape.
struct Colliders {
  std::vector<PlaneCollider> planes;
  std::vector<SphereCollider> spheres;
  std::vector<BoxCollider> boxes;
  std::vector<CapsuleCollider> capsules;

  bool empty() const {
    return planes.empty() && spheres.empty() && boxes.empty() && capsules.empty();
  }
  std::size_t size() const {
    return planes.size() + spheres.size() + boxes.size() + capsules.size();
  }
  void clear() { *this = Colliders{}; }
};

}  // namespace engine
}  // namespace mass_aggregate_sim
