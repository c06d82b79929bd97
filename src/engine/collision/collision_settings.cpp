#include "mass_aggregate_sim/engine/collision/collision_settings.h"

#include <array>
#include <cmath>
#include <utility>

namespace mass_aggregate_sim {
namespace engine {
namespace {

constexpr std::array<std::pair<Broadphase, const char*>, 2> kNames{{
    {Broadphase::kSortAndSweep, "sort_and_sweep"},
    {Broadphase::kUniformGrid, "uniform_grid"},
}};

}  // namespace

const char* broadphaseName(const Broadphase broadphase) {
  for (const auto& [kind, name] : kNames) {
    if (kind == broadphase) return name;
  }
  return "unknown";
}

std::optional<Broadphase> parseBroadphase(const std::string& name) {
  for (const auto& [kind, known] : kNames) {
    if (name == known) return kind;
  }
  return std::nullopt;
}

std::string broadphaseNames() {
  std::string names;
  for (const auto& entry : kNames) {
    if (!names.empty()) names += ", ";
    names += entry.second;
  }
  return names;
}

Status validateCollisionSettings(const CollisionSettings& settings) {
  if (!std::isfinite(settings.particle_restitution) || settings.particle_restitution < 0.0 ||
      settings.particle_restitution > 1.0) {
    return Status::error("particle_restitution must be in [0, 1]");
  }
  if (!std::isfinite(settings.particle_friction) || settings.particle_friction < 0.0) {
    return Status::error("particle_friction must be finite and >= 0");
  }
  if (settings.max_iterations < 1 || settings.max_iterations > 10000) {
    return Status::error("max_iterations must be in [1, 10000]");
  }
  if (!std::isfinite(settings.penetration_slop) || settings.penetration_slop < 0.0) {
    return Status::error("penetration_slop must be finite and >= 0");
  }
  if (!std::isfinite(settings.rod_tolerance) || settings.rod_tolerance <= 0.0) {
    return Status::error("rod_tolerance must be finite and > 0");
  }
  if (!std::isfinite(settings.velocity_tolerance) || settings.velocity_tolerance <= 0.0) {
    return Status::error("velocity_tolerance must be finite and > 0");
  }
  if (!std::isfinite(settings.runaway_speed) || settings.runaway_speed <= 0.0) {
    return Status::error("runaway_speed must be finite and > 0");
  }
  if (broadphaseName(settings.broadphase) == std::string("unknown")) {
    return Status::error("broadphase must be one of: " + broadphaseNames());
  }
  return Status::ok();
}

}  // namespace engine
}  // namespace mass_aggregate_sim
