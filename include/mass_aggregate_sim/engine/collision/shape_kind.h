#pragma once

#include <Eigen/Geometry>
#include <cstdint>
#include <optional>
#include <vector>

#include "mass_aggregate_sim/engine/core/kind_list.h"
#include "mass_aggregate_sim/engine/core/status.h"
#include "mass_aggregate_sim/engine/core/types.h"

namespace mass_aggregate_sim {
namespace engine {

// Names one static collider; never reused within a world.
using ColliderId = std::uint32_t;

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

// What the engine knows of a collider shape kind K: ShapeKind<K>, specialised in K's own header
// and defined in its own source file (collision/<kind>.cpp). Every stage that handles colliders
// (contacts, swept tests, queries) and the node (scenes, markers, frames) visit ShapeKinds
// (colliders.h) through these, so a kind that lacks one does not compile:
//   kName                          the kind's name in scenes and messages
//   fields(K&, visitor)            every field a scene sets, by name and meaning: the visitor's
//                                  point, direction, coordinate, length, extents, orientation
//   validate(K&)                   refuses bad values (Status says why); normalises
//   contact(k, x, r, margin)       the sphere at x of radius r against the shape; nothing when it
//                                  is farther than margin. A solid shape pushes a sphere whose
//                                  centre is inside it out the nearest way.
//   raycast(k, origin, direction, max_t, inflate)
//                                  the first entry of the ray into the shape grown by inflate (a
//                                  swept sphere's radius); a ray starting inside does not hit
//   describe(k)                    how it is drawn and where its frame is
template <typename Kind>
struct ShapeKind;

}  // namespace engine
}  // namespace mass_aggregate_sim
