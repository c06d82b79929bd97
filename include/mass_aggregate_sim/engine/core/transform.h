#pragma once

#include <Eigen/Geometry>

#include "mass_aggregate_sim/engine/core/types.h"

namespace mass_aggregate_sim {
namespace engine {

using Quat = Eigen::Quaterniond;
using Mat3 = Eigen::Matrix3d;

// A rigid transform: x_world = rotation * x_local + position. The rotation is a unit quaternion.
struct Transform {
  Vec3 position = Vec3::Zero();
  Quat rotation = Quat::Identity();

  Vec3 apply(const Vec3& local) const { return rotation * local + position; }
  Vec3 applyInverse(const Vec3& world) const { return rotation.conjugate() * (world - position); }
  // this * other: other's local frame expressed in this transform's parent frame.
  Transform operator*(const Transform& other) const {
    return Transform{rotation * other.position + position, rotation * other.rotation};
  }
  Transform inverse() const {
    const Quat inverse_rotation = rotation.conjugate();
    return Transform{inverse_rotation * (-position), inverse_rotation};
  }
};

// A transform with its rotation as a matrix, for code that applies it many times (narrowphase).
struct Frame {
  Vec3 position = Vec3::Zero();
  Mat3 rotation = Mat3::Identity();

  Frame() = default;
  explicit Frame(const Transform& t)
      : position(t.position), rotation(t.rotation.toRotationMatrix()) {}
  Frame(const Vec3& p, const Mat3& r) : position(p), rotation(r) {}
  Vec3 apply(const Vec3& local) const { return rotation * local + position; }
  Vec3 applyInverse(const Vec3& world) const { return rotation.transpose() * (world - position); }
};

// An axis-aligned box.
struct Aabb {
  Vec3 lower = Vec3::Zero();
  Vec3 upper = Vec3::Zero();

  bool overlaps(const Aabb& other) const {
    return (lower.array() <= other.upper.array()).all() &&
           (other.lower.array() <= upper.array()).all();
  }
  bool contains(const Aabb& other) const {
    return (lower.array() <= other.lower.array()).all() &&
           (other.upper.array() <= upper.array()).all();
  }
  Aabb merged(const Aabb& other) const {
    return Aabb{lower.cwiseMin(other.lower), upper.cwiseMax(other.upper)};
  }
  Aabb grown(const Real margin) const {
    return Aabb{lower - Vec3::Constant(margin), upper + Vec3::Constant(margin)};
  }
  // Half the surface area (the tree's cost metric).
  Real perimeter() const {
    const Vec3 d = upper - lower;
    return d.x() * d.y() + d.y() * d.z() + d.z() * d.x();
  }
  Vec3 center() const { return 0.5 * (lower + upper); }
};

}  // namespace engine
}  // namespace mass_aggregate_sim
