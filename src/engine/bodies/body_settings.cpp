#include "mass_aggregate_sim/engine/bodies/body_settings.h"

#include <cmath>
#include <string>
#include <tuple>

namespace mass_aggregate_sim {
namespace engine {
namespace {

Status positive(const Real value, const char* name) {
  if (std::isfinite(value) && value > 0.0) return Status::ok();
  return Status::error(std::string(name) + " must be finite and > 0");
}

}  // namespace

namespace {

auto fields(const BodySettings& s) {
  return std::tie(s.substeps, s.iterations, s.relax_iterations, s.guess_loads, s.shock_propagation,
                  s.contact_hertz, s.contact_damping_ratio, s.joint_hertz, s.joint_damping_ratio,
                  s.max_push_speed, s.speculative_distance, s.linear_slop, s.min_twist_lever,
                  s.restitution_threshold, s.sleep, s.sleep_speed, s.time_to_sleep, s.continuous,
                  s.gyroscopic, s.runaway_speed);
}
// A field added to BodySettings changes its size: add it to fields() too, then restate the size.
static_assert(sizeof(BodySettings) == 128, "BodySettings changed: list its fields in fields()");

}  // namespace

bool operator==(const BodySettings& a, const BodySettings& b) { return fields(a) == fields(b); }

Status validateBodySettings(const BodySettings& s) {
  if (s.substeps < 1 || s.substeps > 64) return Status::error("substeps must be in [1, 64]");
  if (s.iterations < 1 || s.iterations > 64) return Status::error("iterations must be in [1, 64]");
  if (s.relax_iterations < 0 || s.relax_iterations > 64) {
    return Status::error("relax_iterations must be in [0, 64]");
  }
  for (const auto& [value, name] : {std::pair<Real, const char*>{s.contact_hertz, "contact_hertz"},
                                    {s.joint_hertz, "joint_hertz"},
                                    {s.max_push_speed, "max_push_speed"},
                                    {s.speculative_distance, "speculative_distance"},
                                    {s.restitution_threshold, "restitution_threshold"},
                                    {s.sleep_speed, "sleep_speed"},
                                    {s.time_to_sleep, "time_to_sleep"},
                                    {s.runaway_speed, "runaway_speed"}}) {
    const Status valid = positive(value, name);
    if (!valid) return valid;
  }
  for (const auto& [value, name] :
       {std::pair<Real, const char*>{s.contact_damping_ratio, "contact_damping_ratio"},
        {s.joint_damping_ratio, "joint_damping_ratio"},
        {s.linear_slop, "linear_slop"},
        {s.min_twist_lever, "min_twist_lever"}}) {
    if (!std::isfinite(value) || value < 0.0) {
      return Status::error(std::string(name) + " must be finite and >= 0");
    }
  }
  return Status::ok();
}

}  // namespace engine
}  // namespace mass_aggregate_sim
