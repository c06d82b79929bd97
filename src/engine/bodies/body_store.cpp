#include "mass_aggregate_sim/engine/bodies/body_store.h"

#include <algorithm>
#include <type_traits>
#include <utility>
#include <variant>

namespace mass_aggregate_sim {
namespace engine {

BodyId BodyStore::add(const BodySpec& spec, const MassProperties& mass) {
  const BodyId id = slots_.add();
  const bool dynamic = spec.type == BodyType::kDynamic;
  const Transform mass_pose = spec.pose * mass.frame;
  type_.push_back(spec.type);
  name_.push_back(spec.name);
  position_.push_back(mass_pose.position);
  orientation_.push_back(mass_pose.rotation.normalized());
  mass_frame_.push_back(mass.frame);
  const bool moves = spec.type != BodyType::kFixed;
  linear_velocity_.push_back(moves ? spec.linear_velocity : Vec3::Zero());
  angular_velocity_.push_back(moves ? spec.angular_velocity : Vec3::Zero());
  force_.push_back(Vec3::Zero());
  torque_.push_back(Vec3::Zero());
  mass_.push_back(mass.mass);
  inverse_mass_.push_back(dynamic ? 1.0 / mass.mass : 0.0);
  principal_inertia_.push_back(mass.principal_inertia);
  inverse_inertia_.push_back(dynamic ? Vec3(mass.principal_inertia.cwiseInverse()) : Vec3::Zero());
  world_inverse_inertia_.push_back(Mat3::Zero());
  linear_damping_.push_back(spec.linear_damping);
  angular_damping_.push_back(spec.angular_damping);
  awake_.push_back(spec.type == BodyType::kFixed ? 0 : 1);
  can_sleep_.push_back(spec.can_sleep ? 1 : 0);
  sleep_time_.push_back(0.0);
  std::vector<ShapeIndex> own;
  const Transform to_mass_frame = mass.frame.inverse();
  for (const BodyShapeSpec& s : spec.shapes) {
    ShapeIndex index;
    if (!free_shapes_.empty()) {
      index = free_shapes_.back();
      free_shapes_.pop_back();
    } else {
      index = static_cast<ShapeIndex>(shapes_.size());
      shapes_.emplace_back();
    }
    BodyShape& shape = shapes_[index];
    shape.geometry = s.geometry;
    shape.local = to_mass_frame * s.local;
    shape.material = s.material;
    shape.body = id;
    shape.proxy = -1;
    shape.live = true;
    own.push_back(index);
  }
  Real reach = 0.0;
  for (const ShapeIndex index : own) {
    const BodyShape& shape = shapes_[index];
    const Aabb box = std::visit(
        [&](const auto& g) {
          return BodyShapeKind<std::decay_t<decltype(g)>>::aabb(g, Frame(shape.local));
        },
        shape.geometry);
    reach = std::max({reach, box.lower.norm(), box.upper.norm()});
  }
  reach_.push_back(reach);
  shapes_of_.push_back(std::move(own));
  refreshWorldInertia(size() - 1);
  ++layout_version_;
  return id;
}

Status BodyStore::remove(const BodyId id) {
  if (!contains(id)) return Status::error(describeInvalid(id));
  const std::size_t dense = slots_.denseIndexUnchecked(id);
  for (const ShapeIndex s : shapes_of_[dense]) {
    shapes_[s].live = false;
    shapes_[s].proxy = -1;
    free_shapes_.push_back(s);
  }
  const auto move = slots_.remove(id);
  if (move.from != move.to) moveDense(move.from, move.to);
  popDense();
  ++layout_version_;
  return Status::ok();
}

void BodyStore::clear() {
  while (!empty()) remove(idAt(size() - 1));
  shapes_.clear();
  free_shapes_.clear();
}

Status BodyStore::checkReference(const BodyId id, const char* field) const {
  if (contains(id)) return Status::ok();
  return Status::error(std::string(field) + ": " + describeInvalid(id));
}

std::optional<BodyId> BodyStore::findByName(const std::string& name) const {
  if (name.empty()) return std::nullopt;
  for (std::size_t i = 0; i < name_.size(); ++i) {
    if (name_[i] == name) return idAt(i);
  }
  return std::nullopt;
}

Transform BodyStore::pose(const std::size_t i) const {
  return Transform{position_[i], orientation_[i]} * mass_frame_[i].inverse();
}

void BodyStore::refreshWorldInertia(const std::size_t i) {
  const Mat3 r = orientation_[i].toRotationMatrix();
  world_inverse_inertia_[i] = r * inverse_inertia_[i].asDiagonal() * r.transpose();
}

void BodyStore::setAwake(const std::size_t i, const bool awake) {
  awake_[i] = awake && type_[i] != BodyType::kFixed ? 1 : 0;
  if (awake) sleep_time_[i] = 0.0;
}

Transform BodyStore::shapePose(const ShapeIndex s) const {
  const std::size_t i = slots_.denseIndexUnchecked(shapes_[s].body);
  return Transform{position_[i], orientation_[i]} * shapes_[s].local;
}

void BodyStore::moveDense(const std::size_t from, const std::size_t to) {
  type_[to] = type_[from];
  name_[to] = std::move(name_[from]);
  position_[to] = position_[from];
  orientation_[to] = orientation_[from];
  mass_frame_[to] = mass_frame_[from];
  linear_velocity_[to] = linear_velocity_[from];
  angular_velocity_[to] = angular_velocity_[from];
  force_[to] = force_[from];
  torque_[to] = torque_[from];
  mass_[to] = mass_[from];
  inverse_mass_[to] = inverse_mass_[from];
  principal_inertia_[to] = principal_inertia_[from];
  inverse_inertia_[to] = inverse_inertia_[from];
  world_inverse_inertia_[to] = world_inverse_inertia_[from];
  linear_damping_[to] = linear_damping_[from];
  angular_damping_[to] = angular_damping_[from];
  awake_[to] = awake_[from];
  can_sleep_[to] = can_sleep_[from];
  sleep_time_[to] = sleep_time_[from];
  shapes_of_[to] = std::move(shapes_of_[from]);
  reach_[to] = reach_[from];
}

void BodyStore::popDense() {
  type_.pop_back();
  name_.pop_back();
  position_.pop_back();
  orientation_.pop_back();
  mass_frame_.pop_back();
  linear_velocity_.pop_back();
  angular_velocity_.pop_back();
  force_.pop_back();
  torque_.pop_back();
  mass_.pop_back();
  inverse_mass_.pop_back();
  principal_inertia_.pop_back();
  inverse_inertia_.pop_back();
  world_inverse_inertia_.pop_back();
  linear_damping_.pop_back();
  angular_damping_.pop_back();
  awake_.pop_back();
  can_sleep_.pop_back();
  sleep_time_.pop_back();
  shapes_of_.pop_back();
  reach_.pop_back();
}

}  // namespace engine
}  // namespace mass_aggregate_sim
