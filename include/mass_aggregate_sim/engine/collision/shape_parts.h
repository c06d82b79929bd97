#pragma once
// What every shape shares, static collider or body shape: its surface material, how a sphere or a
// ray meets it, and how it is drawn.

#include <Eigen/Geometry>
#include <vector>

#include "mass_aggregate_sim/engine/core/types.h"

namespace mass_aggregate_sim {
namespace engine {

// Restitution e in [0, 1] (v_sep' = -e v_sep) and Coulomb friction mu >= 0 (|j_t| <= mu |j_n|).
struct Material {
  Real restitution = 0.5;
  Real friction = 0.0;
};

// Overlap of a sphere (a particle) with a shape: moving the sphere by penetration along normal
// separates them; a negative penetration is a gap about to close.
struct ShapeContact {
  Vec3 normal;
  Real penetration;
};

// The first crossing of a ray into a shape: distance t along the unit direction, and the shape's
// outward normal there.
struct RayShapeHit {
  Real t;
  Vec3 normal;
};

// How a shape is drawn and where its frame is: its origin and orientation (a tf frame), and the
// parts it is drawn with. `surface` marks an unbounded shape (a plane) drawn as a large slab.
struct ShapePrimitive {
  enum class Type { kBox, kSphere, kCylinder };
  Type type = Type::kBox;
  Vec3 center = Vec3::Zero();
  Eigen::Quaterniond orientation = Eigen::Quaterniond::Identity();
  Vec3 size = Vec3::Ones();  // full extents along the primitive's axes (a cylinder's along z)
};
struct ShapeDescription {
  Vec3 origin = Vec3::Zero();
  Eigen::Quaterniond orientation = Eigen::Quaterniond::Identity();
  std::vector<ShapePrimitive> parts;
  bool surface = false;
};

}  // namespace engine
}  // namespace mass_aggregate_sim
