#pragma once
// Interprets arbitrary bytes as a sequence of World calls with arbitrary fields (raw 64-bit
// patterns, so NaN, Inf, denormals and huge values all occur) and checks the engine's promises:
// a refused call changes nothing, a non-finite state never goes unreported, a copy steps on as
// the original does. Shared by the libFuzzer target (engine_fuzz.cpp) and the gtest that replays
// saved inputs.
//
// Three formats: an input whose first byte is kBodyFormat adds rigid bodies, joints, colliders,
// queries, divergence policies and copies to the particle calls; one whose first byte is
// kBodyForceFormat adds the force generators on bodies to those; any other input is read as the
// particle calls alone, as it was before bodies existed, so saved inputs keep their meaning.
// engine_body_seeds.py writes the body-format seeds; ENGINE_OPS_TRACE prints each call's outcome.

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <utility>
#include <vector>

#include "mass_aggregate_sim/engine/world/world.h"

namespace mass_aggregate_sim {
namespace fuzz {

constexpr std::uint8_t kBodyFormat = 0xB0;
constexpr std::uint8_t kBodyForceFormat = 0xB1;

class ByteReader {
 public:
  ByteReader(const std::uint8_t* data, std::size_t size) : data_(data), size_(size) {}
  bool empty() const { return offset_ >= size_; }
  std::uint8_t byte() { return offset_ < size_ ? data_[offset_++] : 0; }
  std::uint32_t u32() {
    std::uint32_t v = 0;
    for (int i = 0; i < 4; ++i) v = (v << 8) | byte();
    return v;
  }
  // Half the time a raw bit pattern (anything, NaN and Inf included), half a modest value.
  double real() {
    if (byte() & 1u) {
      std::uint64_t bits = 0;
      for (int i = 0; i < 8; ++i) bits = (bits << 8) | byte();
      double v;
      std::memcpy(&v, &bits, sizeof v);
      return v;
    }
    return (static_cast<double>(static_cast<std::int8_t>(byte())) / 8.0);
  }
  engine::Vec3 vec3() {
    const double x = real();
    const double y = real();
    const double z = real();
    return engine::Vec3(x, y, z);
  }
  // A size: mostly in (0, 8], a quarter of the time anything real() gives.
  double size() {
    if ((byte() & 3u) == 0) return real();
    return (1.0 + byte()) / 32.0;
  }
  engine::Vec3 sizes() {
    const double x = size();
    const double y = size();
    const double z = size();
    return engine::Vec3(x, y, z);
  }
  // Mostly a unit quaternion; one time in eight four arbitrary coefficients.
  engine::Quat quat() {
    const bool raw = (byte() & 7u) == 0;
    const double w = real();
    const double x = real();
    const double y = real();
    const double z = real();
    engine::Quat q(w, x, y, z);
    if (raw) return q;
    if (!q.coeffs().allFinite() || q.norm() < 1e-3 || q.norm() > 1e150) {
      return engine::Quat::Identity();
    }
    return q.normalized();
  }
  engine::Material material() {
    const double restitution = real();
    const double friction = real();
    return engine::Material{restitution, friction};
  }

 private:
  const std::uint8_t* data_;
  std::size_t size_;
  std::size_t offset_ = 0;
};

[[noreturn]] inline void fail(const std::string& what) {
  std::fprintf(stderr, "engine promise broken: %s\n", what.c_str());
  std::abort();
}

inline bool sameSettings(const engine::BodySettings& a, const engine::BodySettings& b) {
  return a.substeps == b.substeps && a.iterations == b.iterations &&
         a.relax_iterations == b.relax_iterations && a.contact_hertz == b.contact_hertz &&
         a.contact_damping_ratio == b.contact_damping_ratio && a.joint_hertz == b.joint_hertz &&
         a.joint_damping_ratio == b.joint_damping_ratio && a.max_push_speed == b.max_push_speed &&
         a.speculative_distance == b.speculative_distance && a.linear_slop == b.linear_slop &&
         a.min_twist_lever == b.min_twist_lever &&
         a.restitution_threshold == b.restitution_threshold && a.sleep == b.sleep &&
         a.sleep_speed == b.sleep_speed && a.time_to_sleep == b.time_to_sleep &&
         a.continuous == b.continuous && a.gyroscopic == b.gyroscopic &&
         a.runaway_speed == b.runaway_speed;
}

// What a refused call must leave as it was: the state hash, every count, the forces waiting for
// the next step (not part of the hash) and the settings.
struct Snapshot {
  std::uint64_t hash;
  std::size_t particles;
  std::size_t generators;
  std::size_t links;
  std::size_t colliders;
  std::size_t bodies;
  std::size_t joints;
  std::size_t body_generators;
  bool paused;
  std::vector<double> pending;
  engine::BodySettings body_settings;
  engine::WorldConfig config;

  explicit Snapshot(const engine::World& w)
      : hash(w.stateHash()),
        particles(w.particles().size()),
        generators(w.generators().size()),
        links(w.links().size()),
        colliders(w.colliders().size()),
        bodies(w.bodies().size()),
        joints(w.joints().size()),
        body_generators(w.bodyGenerators().size()),
        paused(w.paused()),
        body_settings(w.bodySettings()),
        config(w.config()) {
    const auto f = w.particles().forces();
    pending.assign(f.data(), f.data() + f.size());
    for (std::size_t i = 0; i < w.bodies().size(); ++i) {
      for (const engine::Vec3* v : {&w.bodies().force(i), &w.bodies().torque(i)}) {
        pending.insert(pending.end(), v->data(), v->data() + 3);
      }
    }
  }
  bool operator==(const Snapshot& o) const {
    // Bitwise for the pending forces: a NaN there would be a change too.
    return hash == o.hash && particles == o.particles && generators == o.generators &&
           links == o.links && colliders == o.colliders && bodies == o.bodies &&
           joints == o.joints && body_generators == o.body_generators && paused == o.paused &&
           pending.size() == o.pending.size() &&
           (pending.empty() ||
            std::memcmp(pending.data(), o.pending.data(), pending.size() * sizeof(double)) == 0) &&
           sameSettings(body_settings, o.body_settings) && config.dt == o.config.dt &&
           config.substeps == o.config.substeps && config.integrator == o.config.integrator &&
           config.divergence_policy == o.config.divergence_policy &&
           (config.gravity.array() == o.config.gravity.array()).all();
  }
};

inline bool stateFinite(const engine::World& world) {
  if (!world.particles().positions().allFinite() || !world.particles().velocities().allFinite()) {
    return false;
  }
  const engine::BodyStore& bodies = world.bodies();
  for (std::size_t i = 0; i < bodies.size(); ++i) {
    if (!bodies.position(i).allFinite() || !bodies.orientation(i).coeffs().allFinite() ||
        !bodies.linearVelocity(i).allFinite() || !bodies.angularVelocity(i).allFinite()) {
      return false;
    }
  }
  return true;
}

// One step, and what it promises: a paused world does not move, a non-finite state is reported,
// and a report names at most one particle or body, a live one.
inline void checkedStep(engine::World& world) {
  using namespace engine;
  const bool was_paused = world.paused();
  const std::uint64_t hash_before = was_paused ? world.stateHash() : 0;
  const std::uint64_t divergences = world.divergenceCount();
  world.step();
  if (was_paused && world.stateHash() != hash_before) fail("a paused world stepped");
  const bool reported = world.divergenceCount() != divergences;
  if (!was_paused && !reported && !stateFinite(world)) {
    fail("non-finite state after a step without a divergence report");
  }
  if (!reported) return;
  const auto& event = world.lastDivergence();
  if (!event) fail("a divergence was counted without an event");
  // Implicit Euler's failed factorisation names neither.
  if (event->particle.valid() && event->body.valid()) {
    fail("a divergence event names both a particle and a body: " + event->what);
  }
  if (world.config().divergence_policy == DivergencePolicy::kContinue) {
    if (event->body.valid() && !world.bodies().contains(event->body)) {
      fail("a divergence event names a body that is not live");
    }
    if (event->particle.valid() && !world.particles().contains(event->particle)) {
      fail("a divergence event names a particle that is not live");
    }
  }
}

// Every joint's ends are live: removing a body or particle removes its joints.
inline void checkJointEnds(const engine::World& world) {
  world.joints().forEach([&](const auto& kind) {
    for (const auto& joint : kind) {
      for (const engine::JointEnd* end : {&joint.a, &joint.b}) {
        if (end->isBody() && !world.bodies().contains(end->body)) {
          fail("joint " + std::to_string(joint.id) + " outlived its body");
        }
        if (end->isParticle() && !world.particles().contains(end->particle)) {
          fail("joint " + std::to_string(joint.id) + " outlived its particle");
        }
      }
    }
  });
}

// Every point spring's ends are live: removing a body or particle removes its generators.
inline void checkGeneratorEnds(const engine::World& world) {
  for (const engine::PointSpring& spring : world.bodyGenerators().of<engine::PointSpring>()) {
    for (const engine::JointEnd* end : {&spring.a, &spring.b}) {
      if ((end->isBody() && !world.bodies().contains(end->body)) ||
          (end->isParticle() && !world.particles().contains(end->particle))) {
        fail("point spring " + std::to_string(spring.id) + " outlived an end");
      }
    }
  }
  world.bodyGenerators().forEach([&](const auto& kind) {
    using Kind = typename std::decay_t<decltype(kind)>::value_type;
    for (const auto& generator : kind) {
      for (const engine::BodyId body : engine::BodyForceKind<Kind>::bodiesOf(generator)) {
        if (!world.bodies().contains(body)) {
          fail(std::string(engine::BodyForceKind<Kind>::kName) + " outlived its body");
        }
      }
    }
  });
}

inline void checkBodiesLive(const engine::World& world, const std::vector<engine::BodyId>& ids,
                            const char* what) {
  for (std::size_t k = 0; k < ids.size(); ++k) {
    if (!world.bodies().contains(ids[k])) fail(std::string(what) + " returned a dead body");
    for (std::size_t j = 0; j < k; ++j) {
      if (ids[j] == ids[k]) fail(std::string(what) + " returned a body twice");
    }
  }
}

inline void runEngineOps(const std::uint8_t* data, const std::size_t size) {
  using namespace engine;
  const bool forces = size > 0 && data[0] == kBodyForceFormat;
  const bool bodies = forces || (size > 0 && data[0] == kBodyFormat);
  ByteReader in(bodies ? data + 1 : data, bodies ? size - 1 : size);
  World world;
  std::vector<ParticleId> known;
  std::vector<BodyId> known_bodies;
  std::vector<JointId> known_joints;
  int steps_left = 64;
  int bodies_added = 0;
  const int max_ops = bodies ? 160 : 96;
  for (int op = 0; op < max_ops && !in.empty(); ++op) {
    const std::uint8_t raw_code = in.byte();
    const int code = forces ? raw_code % 43 : bodies ? raw_code % 40 : raw_code % 16;
    // An id from the ones handed out (live or stale), or an arbitrary one.
    const auto pickId = [&]() {
      const std::uint32_t pick = in.u32();
      if (!known.empty() && (pick & 1u)) return known[(pick >> 1) % known.size()];
      return ParticleId{in.u32() % 64, in.u32() % 4};
    };
    const auto pickBody = [&]() {
      const std::uint32_t pick = in.u32();
      if (!known_bodies.empty() && (pick & 1u)) {
        return known_bodies[(pick >> 1) % known_bodies.size()];
      }
      return BodyId{in.u32() % 32, in.u32() % 4};
    };
    const auto pickJoint = [&]() -> JointId {
      const std::uint32_t pick = in.u32();
      if (!known_joints.empty() && (pick & 1u)) {
        return known_joints[(pick >> 1) % known_joints.size()];
      }
      return in.u32() % 32;
    };
    // A body point, a particle, a world point, or (wrongly) both a body and a particle.
    const auto pickEnd = [&]() {
      switch (in.byte() % 6) {
        case 0:
        case 1:
        case 2: {
          const BodyId body = pickBody();
          return JointEnd::onBody(body, in.vec3());
        }
        case 3:
          return JointEnd::atParticle(pickId());
        case 4:
          return JointEnd::inWorld(in.vec3());
        default: {
          JointEnd end = JointEnd::onBody(pickBody(), in.vec3());
          end.particle = pickId();
          return end;
        }
      }
    };
    const auto addJoint = [&](auto joint) {
      joint.collide_connected = in.byte() & 1u;
      const auto id = world.addJoint(joint);
      if (id) known_joints.push_back(*id);
      return id.isOk();
    };
    const Snapshot before(world);
    bool accepted = true;
    switch (code) {
      case 0:
      case 1: {
        ParticleSpec spec;
        spec.position = in.vec3();
        spec.velocity = in.vec3();
        spec.acceleration = in.vec3();
        spec.inverse_mass = in.real();
        spec.damping = in.real();
        spec.radius = in.real();
        const auto id = world.addParticle(spec);
        accepted = id.isOk();
        if (accepted) known.push_back(*id);
        break;
      }
      case 2:
        accepted = world.removeParticle(pickId()).isOk();
        break;
      case 3:
        accepted =
            world.addGenerator(Spring::between(pickId(), pickId(), in.real(), in.real(), in.real()))
                .isOk();
        break;
      case 4:
        accepted =
            world
                .addGenerator(Spring::between(pickId(), pickId(), in.real(), in.real(), in.real())
                                  .pullingOnly())
                .isOk();
        break;
      case 5:
        accepted = world
                       .addGenerator(
                           Spring::anchoredAt(pickId(), in.vec3(), in.real(), in.real(), in.real()))
                       .isOk();
        break;
      case 6:
        accepted = world.addGenerator(Drag{pickId(), in.real(), in.real()}).isOk();
        break;
      case 7:
        accepted = world
                       .addGenerator(Buoyancy{pickId(), in.real(), in.real(), in.real(), in.real(),
                                              in.vec3()})
                       .isOk();
        break;
      case 8:
        accepted =
            world.addGenerator(StiffSpring{pickId(), in.vec3(), in.real(), in.real()}).isOk();
        break;
      case 9:
        accepted = world.setPosition(pickId(), in.vec3()).isOk();
        break;
      case 10:
        accepted = world.setVelocity(pickId(), in.vec3()).isOk();
        break;
      case 11:
        accepted = world.applyImpulse(pickId(), in.vec3()).isOk();
        break;
      case 12:
        accepted = world.addForce(pickId(), in.vec3()).isOk();
        break;
      case 13:
        accepted = world.removeGenerator(in.u32() % 64).isOk();
        break;
      case 14: {
        WorldConfig config = world.config();
        config.dt = in.real();
        config.substeps = static_cast<int>(in.byte() % 8);
        config.integrator = static_cast<Integrator>(in.byte() % 6);
        config.gravity = in.vec3();
        accepted = world.setConfig(config).isOk();
        break;
      }
      case 16:
      case 17: {
        if (bodies_added >= 32) break;
        BodySpec spec;
        const std::uint8_t flags = in.byte();
        spec.type = static_cast<BodyType>((flags & 3u) % 3);
        spec.can_sleep = flags & 4u;
        if (flags & 8u) spec.name = "body" + std::to_string(bodies_added);
        spec.pose.position = in.vec3();
        spec.pose.rotation = in.quat();
        spec.linear_velocity = in.vec3();
        spec.angular_velocity = in.vec3();
        // 0 shapes is refused; several make a compound.
        const int shapes = in.byte() % 5;
        for (int s = 0; s < shapes; ++s) {
          BodyShapeSpec shape;
          switch (in.byte() % 3) {
            case 0:
              shape.geometry = SphereShape{in.size()};
              break;
            case 1:
              shape.geometry = BoxShape{in.sizes()};
              break;
            default: {
              const double radius = in.size();
              shape.geometry = CapsuleShape{radius, in.size()};
              break;
            }
          }
          if (shapes > 1 || (in.byte() & 1u)) {
            shape.local.position = in.vec3();
            shape.local.rotation = in.quat();
          }
          shape.material = in.material();
          if (in.byte() & 1u) shape.density = in.size() * 250.0;
          spec.shapes.push_back(shape);
        }
        spec.mass = (flags & 16u) ? in.size() : 0.0;
        if (flags & 32u) {
          spec.linear_damping = in.real();
          spec.angular_damping = in.real();
        }
        const auto id = world.addBody(spec);
        accepted = id.isOk();
        if (accepted) {
          known_bodies.push_back(*id);
          ++bodies_added;
        }
        break;
      }
      case 18:
        accepted = world.removeBody(pickBody()).isOk();
        break;
      case 19: {
        const BodyId id = pickBody();
        Transform pose;
        pose.position = in.vec3();
        pose.rotation = in.quat();
        accepted = world.setBodyPose(id, pose).isOk();
        break;
      }
      case 20: {
        const BodyId id = pickBody();
        const Vec3 linear = in.vec3();
        accepted = world.setBodyVelocity(id, linear, in.vec3()).isOk();
        break;
      }
      case 21: {
        const BodyId id = pickBody();
        const Vec3 force = in.vec3();
        accepted = world.addBodyForce(id, force, in.vec3()).isOk();
        break;
      }
      case 22: {
        const BodyId id = pickBody();
        accepted = world.addBodyTorque(id, in.vec3()).isOk();
        break;
      }
      case 23: {
        const BodyId id = pickBody();
        const Vec3 impulse = in.vec3();
        const Vec3 point = in.vec3();
        accepted = world.applyBodyImpulse(id, impulse, point, in.vec3()).isOk();
        break;
      }
      case 24:
        accepted = world.wakeBody(pickBody()).isOk();
        break;
      case 25: {
        BallJoint joint;
        joint.a = pickEnd();
        joint.b = pickEnd();
        accepted = addJoint(joint);
        break;
      }
      case 26: {
        HingeJoint joint;
        joint.a = pickEnd();
        joint.b = pickEnd();
        joint.axis = in.vec3();
        const std::uint8_t flags = in.byte();
        joint.limit = flags & 1u;
        joint.motor = flags & 2u;
        if (joint.limit) {
          joint.lower = in.real();
          joint.upper = in.real();
        }
        if (joint.motor) {
          joint.motor_speed = in.real();
          joint.max_motor_torque = in.real();
        }
        accepted = addJoint(joint);
        break;
      }
      case 27: {
        FixedJoint joint;
        joint.a = pickEnd();
        joint.b = pickEnd();
        accepted = addJoint(joint);
        break;
      }
      case 28: {
        const JointEnd a = pickEnd();
        const JointEnd b = pickEnd();
        DistanceJoint joint;
        switch (in.byte() % 3) {
          case 0:
            joint = DistanceJoint::rod(a, b, in.real());
            break;
          case 1:
            joint = DistanceJoint::cable(a, b, in.real());
            break;
          default:
            joint.a = a;
            joint.b = b;
            joint.min_length = in.real();
            joint.max_length = in.real();
            break;
        }
        accepted = addJoint(joint);
        break;
      }
      case 29:
        accepted = world.removeJoint(pickJoint()).isOk();
        break;
      case 30: {
        const JointId id = pickJoint();
        const bool enabled = in.byte() & 1u;
        const double speed = in.real();
        accepted = world.setHingeMotor(id, enabled, speed, in.real()).isOk();
        break;
      }
      case 31: {
        BodySettings s = world.bodySettings();
        const std::uint32_t which = in.u32();
        // Counts stay small (a raw 64 would make a slow input, not a finding), but 0 and 65 occur.
        const auto count = [&](int& field) {
          const std::uint8_t b = in.byte();
          field = b == 255 ? 65 : b % 7;
        };
        if (which & (1u << 0)) count(s.substeps);
        if (which & (1u << 1)) count(s.iterations);
        if (which & (1u << 2)) count(s.relax_iterations);
        if (which & (1u << 3)) s.contact_hertz = in.size() * 10.0;
        if (which & (1u << 4)) s.contact_damping_ratio = in.real();
        if (which & (1u << 5)) s.joint_hertz = in.size() * 10.0;
        if (which & (1u << 6)) s.joint_damping_ratio = in.real();
        if (which & (1u << 7)) s.max_push_speed = in.size();
        if (which & (1u << 8)) s.speculative_distance = in.size() / 64.0;
        if (which & (1u << 9)) s.linear_slop = in.real();
        if (which & (1u << 10)) s.restitution_threshold = in.real();
        if (which & (1u << 11)) s.sleep = !s.sleep;
        if (which & (1u << 12)) s.sleep_speed = in.size();
        if (which & (1u << 13)) s.time_to_sleep = in.size() / 8.0;
        if (which & (1u << 14)) s.continuous = !s.continuous;
        if (which & (1u << 15)) s.gyroscopic = !s.gyroscopic;
        if (which & (1u << 16)) s.runaway_speed = in.real();
        if (which & (1u << 17)) s.min_twist_lever = in.real();
        accepted = world.setBodySettings(s).isOk();
        break;
      }
      case 32: {
        const Vec3 origin = in.vec3();
        const Vec3 direction = in.vec3();
        const double max_distance = in.real();
        const auto hit = world.raycast(origin, direction, max_distance);
        if (hit) {
          if (hit->hit_body && !world.bodies().contains(hit->body)) fail("a ray hit a dead body");
          if (hit->hit_particle && !world.particles().contains(hit->particle)) {
            fail("a ray hit a dead particle");
          }
          if (hit->hit_body && hit->hit_particle) fail("a ray hit a body and a particle at once");
          if (!(hit->distance >= 0.0) ||
              (!std::isnan(max_distance) &&
               hit->distance > max_distance + 1e-9 * std::abs(max_distance))) {
            fail("a ray hit beyond its range");
          }
        }
        break;
      }
      case 33: {
        const Vec3 center = in.vec3();
        const std::uint8_t which = in.byte();
        if (which & 1u) {
          const Vec3 half_extents = in.sizes();
          checkBodiesLive(world, world.bodiesOverlappingBox(center, half_extents, in.quat()),
                          "bodiesOverlappingBox");
          world.overlapBox(center, half_extents);
        } else {
          const double radius = in.size();
          checkBodiesLive(world, world.bodiesOverlappingSphere(center, radius),
                          "bodiesOverlappingSphere");
          world.overlapSphere(center, radius);
        }
        break;
      }
      case 34: {
        switch (in.byte() % 3) {
          case 0: {
            PlaneCollider plane;
            plane.normal = in.vec3();
            plane.offset = in.real();
            plane.material = in.material();
            accepted = world.addCollider(plane).isOk();
            break;
          }
          case 1: {
            BoxCollider box;
            box.center = in.vec3();
            box.half_extents = in.sizes();
            box.orientation = in.quat();
            box.material = in.material();
            accepted = world.addCollider(box).isOk();
            break;
          }
          default: {
            SphereCollider sphere;
            sphere.center = in.vec3();
            sphere.radius = in.size();
            accepted = world.addCollider(sphere).isOk();
            break;
          }
        }
        break;
      }
      case 35:
        accepted = world.removeCollider(in.u32() % 16).isOk();
        break;
      case 36: {
        if (in.byte() & 1u) {
          const ParticleId id = pickId();
          accepted = world.setParticleMaterial(id, in.material()).isOk();
        } else {
          CollisionSettings settings = world.collisionSettings();
          const std::uint8_t flags = in.byte();
          settings.particle_collisions = flags & 1u;
          settings.continuous = flags & 2u;
          settings.broadphase = (flags & 4u) ? Broadphase::kUniformGrid : Broadphase::kSortAndSweep;
          accepted = world.setCollisionSettings(settings).isOk();
        }
        break;
      }
      case 37: {
        const std::uint8_t flags = in.byte();
        if ((flags & 15u) == 15u) {
          world.clear();
          break;
        }
        WorldConfig config = world.config();
        config.divergence_policy = static_cast<DivergencePolicy>(flags % 3);
        accepted = world.setConfig(config).isOk();
        if (flags & 4u) world.setResetSnapshot();
        if (flags & 8u) world.resume();
        break;
      }
      case 38: {
        // A copy, an assigned copy and the world step on to the same hash; the world goes on as
        // the assigned copy, moved in, and the moved-from world must still work.
        if (steps_left < 3) break;
        steps_left -= 3;
        World copy(world);
        World assigned;
        assigned = world;
        if (copy.stateHash() != world.stateHash() || assigned.stateHash() != world.stateHash()) {
          fail("a copy hashes differently from its original");
        }
        checkedStep(world);
        checkedStep(copy);
        checkedStep(assigned);
        if (copy.stateHash() != world.stateHash() || assigned.stateHash() != world.stateHash()) {
          fail("a copy stepped to a different state than its original");
        }
        if (copy.divergenceCount() != world.divergenceCount()) {
          fail("a copy counted divergences differently from its original");
        }
        world = std::move(assigned);
        if (world.stateHash() != copy.stateHash()) fail("a moved world changed its state");
        assigned.clear();
        assigned.step();
        if (!assigned.addParticle(ParticleSpec{})) fail("a moved-from world refused a particle");
        assigned.step();
        break;
      }
      case 40: {
        // One read per statement: the order of a call's arguments is the compiler's.
        PointSpring spring;
        spring.a = pickEnd();
        spring.b = pickEnd();
        spring.stiffness = in.real();
        spring.rest_length = in.real();
        spring.damping = in.real();
        spring.pull_only = in.byte() & 1u;
        accepted = world.addBodyGenerator(spring).isOk();
        break;
      }
      case 41: {
        BodyDrag drag;
        drag.body = pickBody();
        drag.k1 = in.real();
        drag.k2 = in.real();
        drag.angular = in.real();
        accepted = world.addBodyGenerator(drag).isOk();
        break;
      }
      case 42: {
        BodyBuoyancy buoyancy;
        buoyancy.body = pickBody();
        buoyancy.model = static_cast<BuoyancyModel>(in.byte() % 3);  // 2: not a model
        buoyancy.max_depth = in.real();
        buoyancy.volume = in.real();
        buoyancy.liquid_density = in.real();
        buoyancy.surface_height = in.real();
        buoyancy.up = in.vec3();
        accepted = world.addBodyGenerator(buoyancy).isOk();
        break;
      }
      default: {
        if (steps_left-- <= 0) break;
        checkedStep(world);
        break;
      }
    }
#ifdef ENGINE_OPS_TRACE
    int asleep = 0;
    for (std::size_t i = 0; i < world.bodies().size(); ++i) {
      asleep += world.bodies().dynamic(i) && !world.bodies().awake(i) ? 1 : 0;
    }
    std::fprintf(stderr,
                 "op %d %s: %zu particles, %zu bodies (%d asleep), %zu joints, step %llu, "
                 "%llu divergences%s\n",
                 code, accepted ? "ok" : "refused", world.particles().size(), world.bodies().size(),
                 asleep, world.joints().size(), static_cast<unsigned long long>(world.stepCount()),
                 static_cast<unsigned long long>(world.divergenceCount()),
                 world.paused() ? ", paused" : "");
#endif
    if (!accepted && !(Snapshot(world) == before)) {
      fail("a refused call (op " + std::to_string(code) + ") changed the world");
    }
    if (bodies) checkJointEnds(world);
    if (forces) checkGeneratorEnds(world);
  }
}

}  // namespace fuzz
}  // namespace mass_aggregate_sim
