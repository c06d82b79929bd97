#include "mass_aggregate_sim/node/input_limits.h"

#include <cmath>
#include <sstream>

namespace mass_aggregate_sim {
namespace node {

using engine::Real;
using engine::Status;
using engine::Vec3;

namespace {

std::string number(const Real value) {
  std::ostringstream out;
  out << value;
  return out.str();
}

}  // namespace

Status checkVector(const Vec3& v, const Real limit, const std::string& field, const char* unit) {
  if (!v.allFinite()) return Status::error(field + ": must be finite");
  if ((v.array().abs() > limit).any()) {
    return Status::error(field + ": each component must be within +-" + number(limit) + " " + unit +
                         ", got [" + number(v.x()) + ", " + number(v.y()) + ", " + number(v.z()) +
                         "]");
  }
  return Status::ok();
}

Status checkPosition(const Vec3& position, const std::string& field) {
  return checkVector(position, kMaxCoordinate, field, "m");
}

Status checkVelocity(const Vec3& velocity, const std::string& field) {
  return checkVector(velocity, kMaxSpeed, field, "m/s");
}

Status checkNonNegative(const Real value, const Real limit, const std::string& field,
                        const char* unit) {
  if (!std::isfinite(value)) return Status::error(field + ": must be finite");
  if (value < 0.0 || value > limit) {
    const std::string units = *unit != '\0' ? std::string(" ") + unit : std::string();
    return Status::error(field + ": must be in [0, " + number(limit) + "]" + units + ", got " +
                         number(value));
  }
  return Status::ok();
}

std::string quoteInput(const std::string& text) {
  if (text.size() <= kMaxQuoted) return "'" + text + "'";
  return "'" + text.substr(0, kMaxQuoted) + "'... (" + std::to_string(text.size()) + " characters)";
}

Status checkParticleName(const std::string& name, const std::string& world_frame) {
  if (name.size() > kMaxNameLength) {
    return Status::error("name: at most " + std::to_string(kMaxNameLength) + " characters, got " +
                         std::to_string(name.size()));
  }
  for (const char c : name) {
    if (c <= ' ' || c > '~') {
      return Status::error("name: only printable ASCII characters without spaces");
    }
  }
  if (!name.empty() && name[0] == '/') return Status::error("name: must not start with '/'");
  if (!world_frame.empty() &&
      (name == world_frame || name.rfind(world_frame + "/collider_", 0) == 0)) {
    return Status::error("name: " + quoteInput(name) + " is the world frame or a collider frame");
  }
  return Status::ok();
}

Status checkParticleSpec(const engine::ParticleSpec& spec, const std::string& world_frame) {
  if (!spec.name.empty()) {
    const Status name = checkParticleName(spec.name, world_frame);
    if (!name) return name;
  }
  Status checked = checkPosition(spec.position, "position");
  if (!checked) return checked;
  checked = checkVelocity(spec.velocity, "velocity");
  if (!checked) return checked;
  checked = checkVector(spec.acceleration, kMaxAcceleration, "acceleration", "m/s^2");
  if (!checked) return checked;
  // Finite, >= 0 inverse mass and damping in [0, 1] are the engine's (validateSpec); the node
  // adds only its limits.
  if (spec.inverse_mass > 0.0) {
    // m = 1 / w; compared as w so no division is needed.
    if (spec.inverse_mass > 1.0 / kMinMass || spec.inverse_mass < 1.0 / kMaxMass) {
      return Status::error("mass: must be in [" + number(kMinMass) + ", " + number(kMaxMass) +
                           "] kg, got " + number(1.0 / spec.inverse_mass));
    }
  }
  return checkNonNegative(spec.radius, kMaxRadius, "radius", "m");
}

Status checkParamType(const std::string& name, const XmlRpc::XmlRpcValue& value,
                      const ParamType type) {
  using XmlRpc::XmlRpcValue;
  const auto isNumber = [](const XmlRpcValue& v) {
    return v.getType() == XmlRpcValue::TypeDouble || v.getType() == XmlRpcValue::TypeInt;
  };
  bool ok = false;
  const char* expected = "";
  switch (type) {
    case ParamType::kNumber:
      ok = isNumber(value);
      expected = "a number";
      break;
    case ParamType::kInt:
      ok = value.getType() == XmlRpcValue::TypeInt;
      expected = "an integer";
      break;
    case ParamType::kBool:
      ok = value.getType() == XmlRpcValue::TypeBoolean;
      expected = "true or false";
      break;
    case ParamType::kString:
      ok = value.getType() == XmlRpcValue::TypeString;
      expected = "a string";
      break;
    case ParamType::kVec3:
      ok = value.getType() == XmlRpcValue::TypeArray && value.size() == 3;
      for (int i = 0; ok && i < 3; ++i) ok = isNumber(value[i]);
      expected = "[x, y, z] of numbers";
      break;
  }
  if (ok) return Status::ok();
  return Status::error("~" + name + ": expected " + expected);
}

}  // namespace node
}  // namespace mass_aggregate_sim
