#pragma once
// Rigid bodies as the node's requests and scenes give them, without ROS: naming a body, the node's
// twist convention, frames a request may be given in, and the checks a body spec passes before it
// reaches the engine.

#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>

#include "mass_aggregate_sim/engine/world/world.h"

namespace mass_aggregate_sim {
namespace node {

// Bounds of the numbers a body request or scene may hold (docs/RELIABILITY.md); the positions,
// speeds and masses of particles (input_limits.h) hold for bodies too.
constexpr engine::Real kMaxAngularSpeed = 1e4;  // rad/s, each component
constexpr engine::Real kMinBodySize = 1e-4;     // m, a radius, half extent or half length
constexpr engine::Real kMaxBodySize = 1e3;      // m, the same, and a shape's offset in its body
constexpr engine::Real kMinDensity = 1e-3;      // kg/m^3
constexpr engine::Real kMaxDensity = 1e6;       // kg/m^3
constexpr engine::Real kMaxFriction = 100.0;
constexpr engine::Real kMaxBodyDamping = 1e3;  // 1/s
constexpr engine::Real kMaxTorque = 1e9;       // N m, each component of a requested torque
// A body whose smallest principal moment is below this fraction of its largest is refused as
// singular: the smallest torque would spin it without bound and the solver's sums lose every digit.
constexpr engine::Real kMinInertiaRatio = 1e-10;
constexpr std::size_t kMaxShapesPerBody = 64;
// A quaternion is a rotation when |q| is within this of 1 (the engine's own tolerance).
constexpr engine::Real kUnitQuaternionTolerance = 1e-6;

// Names a body in a request: by name when the name is non-empty, otherwise by packed id.
struct BodyRef {
  std::uint64_t id = 0;
  std::string name;
};

engine::Result<engine::BodyId> resolveBody(const engine::World& world, const BodyRef& ref);

// A twist as the node shows it: `linear` is the velocity of the body frame's origin (not of its
// centre of mass), `angular` the angular velocity; both in world axes unless said otherwise.
struct Twist {
  engine::Vec3 linear = engine::Vec3::Zero();
  engine::Vec3 angular = engine::Vec3::Zero();
};

// The velocity of the body's frame origin from the centre of mass's: v + w x (origin - c).
Twist bodyTwist(const engine::BodyStore& bodies, std::size_t dense);
// The centre of mass's linear velocity for a body (frame `pose`, mass frame `mass_frame` in it)
// whose frame origin moves with `twist`.
engine::Vec3 centreVelocity(const engine::Transform& pose, const engine::Transform& mass_frame,
                            const Twist& twist);

// Sets the spec's velocities from a twist of its frame's origin (the centre of mass's velocity
// from its shapes' mass frame); with shapes that have no mass frame, as given (the spec is then
// refused for its shapes).
void setSpecTwist(engine::BodySpec& spec, const Twist& twist);

// A frame a request may be given in: its pose in the world and, for a body, how its origin moves
// (tf frames are taken as still).
struct ReferenceFrame {
  engine::Transform pose;
  Twist twist;
};
ReferenceFrame bodyFrame(const engine::BodyStore& bodies, std::size_t dense);

// A pose given in `frame` into the world, and back.
engine::Transform poseToWorld(const ReferenceFrame& frame, const engine::Transform& local);
engine::Transform poseInFrame(const ReferenceFrame& frame, const engine::Transform& world);
// The twist of a frame whose origin is at world point `origin`: given relative to `frame` (its
// motion taken away, in its axes) into the world, and back.
Twist twistToWorld(const ReferenceFrame& frame, const engine::Vec3& origin, const Twist& relative);
Twist twistInFrame(const ReferenceFrame& frame, const engine::Vec3& origin, const Twist& world);

// Finite and |q| within kUnitQuaternionTolerance of 1 (a zero quaternion is refused).
engine::Status checkUnitQuaternion(const engine::Quat& q, const std::string& field);

// Everything about a body spec the engine does not check itself, then its mass properties: the
// name (the rules of particle names; names become tf frames), the node's bounds on pose, twist,
// shapes (1 to kMaxShapesPerBody, each size in [kMinBodySize, kMaxBodySize], offsets within
// kMaxBodySize, density, friction, restitution), mass 0 or in [kMinMass, kMaxMass], dampings; a
// fixed body has no velocity; the resulting mass within [kMinMass, kMaxMass] and an inertia that
// is not singular (kMinInertiaRatio). The message names the field, e.g. "shapes[1].radius: ...".
engine::Status checkBodySpec(const engine::BodySpec& spec, const std::string& world_frame);

// The shape kind named `type` (BodyShapeKinds) with its fields read by `reader`
// (reader.length(name, Real&), reader.extents(name, Vec3&): what BodyShapeKind<K>::fields calls),
// or nothing for a name no kind has.
template <typename Reader>
std::optional<engine::AnyBodyShape> readBodyShape(const std::string& type, Reader& reader) {
  std::optional<engine::AnyBodyShape> out;
  engine::forEachKind(engine::BodyShapeKinds{}, [&](const auto tag) {
    using Shape = typename decltype(tag)::type;
    if (out || type != engine::BodyShapeKind<Shape>::kName) return;
    Shape shape;
    engine::BodyShapeKind<Shape>::fields(shape, reader);
    out = shape;
  });
  return out;
}
// The names a scene or request may give, comma separated.
std::string bodyShapeNames();

const char* bodyTypeName(engine::BodyType type);
std::optional<engine::BodyType> parseBodyType(const std::string& name);

}  // namespace node
}  // namespace mass_aggregate_sim
