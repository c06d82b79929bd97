#pragma once

#include <xmlrpcpp/XmlRpcValue.h>

#include <cstddef>
#include <string>

#include "mass_aggregate_sim/engine/core/particle_store.h"
#include "mass_aggregate_sim/engine/core/status.h"
#include "mass_aggregate_sim/engine/core/types.h"

namespace mass_aggregate_sim {
namespace node {

// Bounds every number that enters the node keeps (service requests, parameters, scenes); a value
// beyond one is refused with the field and the rule, never clamped. docs/RELIABILITY.md lists
// them. 1e6 m: a double there still resolves 2^-33 m = 1.2e-10 m, and the engine's extreme tests
// (test/engine/extremes_test.cpp) run there.
constexpr engine::Real kMaxCoordinate = 1e6;  // m, |x|, |y|, |z| of a position, anchor, centre
constexpr engine::Real kMaxLength = 4e6;      // m, > the diagonal of the coordinate box
constexpr engine::Real kMaxRadius = 1e3;      // m, particle radius
constexpr engine::Real kMaxSpeed = 1e5;       // m/s, each velocity component, also after an impulse
constexpr engine::Real kMaxAcceleration = 1e6;  // m/s^2, each component of gravity or a particle's
constexpr engine::Real kMinMass = 1e-6;         // kg
constexpr engine::Real kMaxMass = 1e9;          // kg
constexpr engine::Real kMaxForce = 1e9;         // N, each component of a requested force
constexpr engine::Real kMaxStiffness = 1e12;    // N/m
constexpr engine::Real kMaxLinkDamping = 1e9;   // N s/m
constexpr std::size_t kMaxNameLength = 256;     // characters of a particle name

// Finite and every component within [-limit, limit]; the message names `field` and `unit`.
engine::Status checkVector(const engine::Vec3& v, engine::Real limit, const std::string& field,
                           const char* unit);
engine::Status checkPosition(const engine::Vec3& position, const std::string& field);
engine::Status checkVelocity(const engine::Vec3& velocity, const std::string& field);
// Finite and in [0, limit].
engine::Status checkNonNegative(engine::Real value, engine::Real limit, const std::string& field,
                                const char* unit);
// A particle name: at most kMaxNameLength printable non-space ASCII characters, not starting with
// '/', and not the world frame or one of the node's collider frames (names become tf frames).
engine::Status checkParticleName(const std::string& name, const std::string& world_frame);
// Everything about a particle the engine does not check itself: the bounds above, mass in
// [kMinMass, kMaxMass] unless immovable, and the name (when not empty).
engine::Status checkParticleSpec(const engine::ParticleSpec& spec, const std::string& world_frame);

// A piece of a request (a name, a frame, a type) as a refusal quotes it: in single quotes, cut to
// its first kMaxQuoted characters with the total length after them when longer, so a 100 kB name
// does not come back in the answer.
constexpr std::size_t kMaxQuoted = 100;
std::string quoteInput(const std::string& text);

// Upper bounds of the count parameters themselves (~max_particles, ...).
constexpr int kMaxParticlesLimit = 1000000;
constexpr int kMaxStepsPerRequestLimit = 10000000;
constexpr int kMaxLinksLimit = 1000000;
constexpr int kMaxSustainedForcesLimit = 1000000;
constexpr int kMaxBodiesLimit = 1000000;
constexpr int kMaxJointsLimit = 1000000;

// The type a node parameter must have. NodeHandle::param() quietly falls back to the default when
// the value has another type; the node refuses it instead, naming "~<name>" and the type expected.
enum class ParamType { kNumber, kInt, kBool, kString, kVec3 };
engine::Status checkParamType(const std::string& name, const XmlRpc::XmlRpcValue& value,
                              ParamType type);

}  // namespace node
}  // namespace mass_aggregate_sim
