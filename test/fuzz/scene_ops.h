#pragma once
// Interprets arbitrary bytes as input to the node's checks, without ROS: the first byte picks
//   0: YAML text -> yaml-cpp -> XmlRpc tree (as `rosparam load` would store it) -> loadScene
//   1: an XmlRpc tree built straight from the bytes, its map keys drawn from the scene vocabulary
//   2: a sequence of service requests (ParticleSpec messages through toParticleSpec, then
//      Simulation::spawn / remove / setState / applyForce / applyImpulse / addLink / removeLink /
//      stepMany / reset, and the body requests spawnBodies / removeBodies / setBodyState /
//      applyBodyWrench / applyBodyImpulse / addJoint / removeJoint / setHingeMotor, and live
//      reconfigures through applyLiveSettings and Simulation::configure) with arbitrary fields, on
//      a small fixed scene with bodies and a joint.
// and checks the promises of docs/RELIABILITY.md: a scene that loads keeps every bound and limit,
// a refused request answers a message and changes nothing, an accepted one keeps the limits, and a
// non-finite state after a step is always reported. A broken promise aborts. Shared by the
// libFuzzer target (scene_fuzz.cpp) and the gtest that replays saved inputs.

#include <xmlrpcpp/XmlRpcValue.h>
#include <yaml-cpp/yaml.h>

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <vector>

#include "../node/yaml_to_xmlrpc.h"
#include "mass_aggregate_sim/ParticleSpec.h"
#include "mass_aggregate_sim/node/conversions.h"
#include "mass_aggregate_sim/node/input_limits.h"
#include "mass_aggregate_sim/node/links.h"
#include "mass_aggregate_sim/node/scene_loader.h"
#include "mass_aggregate_sim/node/settings.h"
#include "mass_aggregate_sim/node/simulation.h"

namespace mass_aggregate_sim {
namespace fuzz {
namespace scene {

class Bytes {
 public:
  Bytes(const std::uint8_t* data, std::size_t size) : data_(data), size_(size) {}
  bool empty() const { return offset_ >= size_; }
  std::uint8_t byte() { return offset_ < size_ ? data_[offset_++] : 0; }
  std::uint64_t u64() {
    std::uint64_t v = 0;
    for (int i = 0; i < 8; ++i) v = (v << 8) | byte();
    return v;
  }
  // Values at and around every bound, specials, raw bit patterns and modest numbers.
  double real() {
    static const double kInteresting[] = {
        0.0,     -0.0,    1.0,   -1.0,   0.5,    1e6,     -1e6, 1e6 + 1,  1e5,
        -1e5,    1e5 + 1, 1e-6,  1e-7,   1e9,    1e9 + 1, 1e12, 1e13,     4e6,
        4e6 + 1, 1e3,     1e300, -1e300, 1e-300, 5e-324,  NAN,  INFINITY, -INFINITY};
    const std::uint8_t kind = byte();
    if (kind < 96) return kInteresting[kind % (sizeof kInteresting / sizeof *kInteresting)];
    if (kind < 160) {
      const std::uint64_t bits = u64();
      double v;
      std::memcpy(&v, &bits, sizeof v);
      return v;
    }
    return static_cast<double>(static_cast<std::int8_t>(byte())) / 4.0;
  }
  std::string text(const std::vector<const char*>& vocabulary) {
    const std::uint8_t pick = byte();
    if (pick < 200) return vocabulary[pick % vocabulary.size()];
    std::string s;
    const int n = byte() % 12;
    for (int i = 0; i < n; ++i) s.push_back(static_cast<char>(byte()));
    return s;
  }
  std::string rest() {
    const std::string s(reinterpret_cast<const char*>(data_) + offset_, size_ - offset_);
    offset_ = size_;
    return s;
  }

 private:
  const std::uint8_t* data_;
  std::size_t size_;
  std::size_t offset_ = 0;
};

[[noreturn]] inline void fail(const std::string& what) {
  std::fprintf(stderr, "node promise broken: %s\n", what.c_str());
  std::abort();
}

// Scene keys, link / force / collider / integrator names, and particle names.
inline const std::vector<const char*>& vocabulary() {
  static const std::vector<const char*> words = {"name",
                                                 "description",
                                                 "rate",
                                                 "dt",
                                                 "substeps",
                                                 "integrator",
                                                 "gravity",
                                                 "particles",
                                                 "lines",
                                                 "blocks",
                                                 "links",
                                                 "forces",
                                                 "colliders",
                                                 "collisions",
                                                 "position",
                                                 "velocity",
                                                 "acceleration",
                                                 "mass",
                                                 "fixed",
                                                 "radius",
                                                 "damping",
                                                 "start",
                                                 "end",
                                                 "count",
                                                 "fixed_indices",
                                                 "link",
                                                 "origin",
                                                 "spacing",
                                                 "jitter",
                                                 "seed",
                                                 "type",
                                                 "a",
                                                 "b",
                                                 "anchor",
                                                 "stiffness",
                                                 "rest_length",
                                                 "max_length",
                                                 "length",
                                                 "restitution",
                                                 "all",
                                                 "k1",
                                                 "k2",
                                                 "volume",
                                                 "max_depth",
                                                 "liquid_density",
                                                 "surface_height",
                                                 "up",
                                                 "normal",
                                                 "offset",
                                                 "center",
                                                 "half_extents",
                                                 "orientation",
                                                 "friction",
                                                 "particle_collisions",
                                                 "broadphase",
                                                 "continuous",
                                                 "particle_restitution",
                                                 "particle_friction",
                                                 "max_iterations",
                                                 "penetration_slop",
                                                 "collide_linked",
                                                 "rod_tolerance",
                                                 "velocity_tolerance",
                                                 "max_contacts",
                                                 "runaway_speed",
                                                 "spring",
                                                 "bungee",
                                                 "stiff_spring",
                                                 "cable",
                                                 "rod",
                                                 "drag",
                                                 "buoyancy",
                                                 "plane",
                                                 "sphere",
                                                 "box",
                                                 "capsule",
                                                 "uniform_grid",
                                                 "sort_and_sweep",
                                                 "rk4",
                                                 "implicit_euler",
                                                 "position_verlet",
                                                 "p",
                                                 "p_0",
                                                 "p_1",
                                                 "q",
                                                 "world",
                                                 "bodies",
                                                 "joints",
                                                 "body_solver",
                                                 "shapes",
                                                 "half_length",
                                                 "angular_velocity",
                                                 "linear_damping",
                                                 "angular_damping",
                                                 "can_sleep",
                                                 "offset",
                                                 "density",
                                                 "anchor_b",
                                                 "axis",
                                                 "limit",
                                                 "lower",
                                                 "upper",
                                                 "motor",
                                                 "motor_speed",
                                                 "max_motor_torque",
                                                 "min_length",
                                                 "collide_connected",
                                                 "ball",
                                                 "hinge",
                                                 "distance",
                                                 "dynamic",
                                                 "kinematic",
                                                 "iterations",
                                                 "sleep",
                                                 "crate",
                                                 "wheel",
                                                 ""};
  return words;
}

inline XmlRpc::XmlRpcValue treeFromBytes(Bytes& in, const int depth) {
  using XmlRpc::XmlRpcValue;
  const std::uint8_t kind = in.byte() % (depth >= 5 ? 5 : 8);
  switch (kind) {
    case 0:
      return XmlRpcValue(static_cast<int>(static_cast<std::int32_t>(in.u64())));
    case 1:
    case 2:
      return XmlRpcValue(in.real());
    case 3:
      return XmlRpcValue(static_cast<bool>(in.byte() & 1u));
    case 4:
      return XmlRpcValue(in.text(vocabulary()));
    case 5: {  // [x, y, z] or any short list
      XmlRpcValue list;
      const int n = in.byte() % 2 ? 3 : in.byte() % 5;
      list.setSize(n);
      for (int i = 0; i < n; ++i) list[i] = treeFromBytes(in, depth + 1);
      return list;
    }
    case 6:
    case 7: {
      XmlRpcValue map;
      const int n = in.byte() % 7;
      for (int i = 0; i < n; ++i) map[in.text(vocabulary())] = treeFromBytes(in, depth + 1);
      if (n == 0) map["name"] = XmlRpcValue("empty");
      return map;
    }
  }
  return XmlRpcValue();
}

constexpr std::size_t kMaxParticles = 128;
constexpr std::size_t kMaxLinks = 128;
constexpr std::size_t kMaxBodies = 16;
constexpr std::size_t kMaxJoints = 16;

// The promises about bodies: within the limits, finite, inside the coordinate box, named by the
// rules; the joints within their limit.
inline void checkBodies(const engine::World& world) {
  const engine::BodyStore& b = world.bodies();
  if (b.size() > kMaxBodies) fail("more than max_bodies");
  if (world.joints().size() > kMaxJoints) fail("more than max_joints");
  for (std::size_t i = 0; i < b.size(); ++i) {
    if (!node::checkParticleName(b.name(i), "world")) fail("a body name breaks the rules");
    if (!(b.mass(i) >= node::kMinMass && b.mass(i) <= node::kMaxMass)) {
      fail("a body mass out of bounds");
    }
  }
}

inline void checkLoadedScene(const engine::World& world) {
  const engine::ParticleStore& p = world.particles();
  if (p.size() > kMaxParticles) fail("a scene loaded with more than max_particles");
  if (world.generators().size() + world.links().size() > kMaxLinks) {
    fail("a scene loaded with more than max_links");
  }
  for (std::size_t i = 0; i < p.size(); ++i) {
    if (!node::checkPosition(p.positions().col(i), "position"))
      fail("a scene position out of bounds");
    if (!node::checkVelocity(p.velocities().col(i), "velocity"))
      fail("a scene velocity out of bounds");
    const double w = p.inverseMasses()[i];
    if (w < 0.0 || (w > 0.0 && (w > 1.0 / node::kMinMass || w < 1.0 / node::kMaxMass))) {
      fail("a scene mass out of bounds");
    }
    if (!node::checkParticleName(p.name(i), "world"))
      fail("a scene particle name breaks the rules");
  }
  checkBodies(world);
}

inline void loadAndStep(const XmlRpc::XmlRpcValue& tree) {
  node::SceneOverrides overrides;
  overrides.max_particles = kMaxParticles;
  overrides.max_links = kMaxLinks;
  overrides.max_bodies = kMaxBodies;
  overrides.max_joints = kMaxJoints;
  const auto loaded = node::loadScene(tree, overrides);
  if (!loaded) {
    if (loaded.message().empty()) fail("a refused scene without a message");
    return;
  }
  checkLoadedScene(loaded.value().world);
  node::SimulationLimits limits;
  limits.max_particles = kMaxParticles;
  limits.max_links = kMaxLinks;
  limits.max_bodies = kMaxBodies;
  limits.max_joints = kMaxJoints;
  node::Simulation sim(loaded.value().world, limits, loaded.value().joint_names);
  // A few steps, bounded in work: substeps can be up to 1000.
  const int steps = loaded.value().world.config().substeps > 50 ? 1 : 3;
  for (int i = 0; i < steps; ++i) {
    const std::uint64_t divergences = sim.world().divergenceCount();
    sim.step();
    const auto& p = sim.world().particles();
    if ((!p.positions().allFinite() || !p.velocities().allFinite()) &&
        sim.world().divergenceCount() == divergences) {
      fail("a non-finite state went unreported");
    }
  }
}

struct Fingerprint {
  std::uint64_t hash;
  std::size_t particles;
  std::size_t links;
  std::size_t sustained;
  std::size_t bodies;
  std::size_t joints;
  std::size_t joint_names;
  explicit Fingerprint(const node::Simulation& s)
      : hash(s.world().stateHash()),
        particles(s.world().particles().size()),
        links(s.world().generators().size() + s.world().links().size()),
        sustained(s.sustainedForceCount()),
        bodies(s.world().bodies().size()),
        joints(s.world().joints().size()),
        joint_names(s.jointNames().size()) {}
  bool operator==(const Fingerprint& o) const {
    return hash == o.hash && particles == o.particles && links == o.links &&
           sustained == o.sustained && bodies == o.bodies && joints == o.joints &&
           joint_names == o.joint_names;
  }
};

inline const char* kRequestScene = R"(
rate: 100
collisions: {particle_collisions: true}
colliders: [{type: plane, normal: [0, 0, 1], offset: 0}]
particles:
  - {name: p, position: [0, 0, 1], mass: 2}
  - {name: q, position: [1, 0, 1], fixed: true}
lines:
  - {name: l, start: [0, 1, 2], end: [1, 1, 2], count: 4, link: {type: spring, stiffness: 50}}
bodies:
  - {name: crate, position: [0, 0, 0.5], shapes: [{type: box, half_extents: [0.5, 0.5, 0.5]}]}
  - {name: wheel, position: [2, 0, 1], shapes: [{type: capsule, radius: 0.1, half_length: 0.3},
                                              {type: sphere, radius: 0.2, position: [0, 0, 0.4]}]}
joints:
  - {type: hinge, name: axle, a: wheel, anchor: [2, 0, 1.5], axis: [0, 1, 0], motor: true,
     motor_speed: 1, max_motor_torque: 5}
)";

inline engine::BodySpec bodySpecFrom(Bytes& in) {
  engine::BodySpec spec;
  spec.name = in.text(vocabulary());
  spec.type = static_cast<engine::BodyType>(in.byte() % 3);
  spec.pose.position = engine::Vec3(in.real(), in.real(), in.real());
  if (in.byte() & 1u) spec.pose.rotation = engine::Quat(in.real(), in.real(), in.real(), in.real());
  node::Twist twist;
  if (in.byte() & 1u) twist.linear = engine::Vec3(in.real(), in.real(), in.real());
  if (in.byte() & 1u) twist.angular = engine::Vec3(in.real(), in.real(), in.real());
  spec.mass = in.byte() & 1u ? in.real() : 0.0;
  spec.linear_damping = in.byte() & 1u ? in.real() : 0.0;
  const int shapes = in.byte() % 4;
  for (int k = 0; k < shapes; ++k) {
    engine::BodyShapeSpec shape;
    switch (in.byte() % 3) {
      case 0:
        shape.geometry = engine::SphereShape{in.real()};
        break;
      case 1:
        shape.geometry = engine::BoxShape{engine::Vec3(in.real(), in.real(), in.real())};
        break;
      default:
        shape.geometry = engine::CapsuleShape{in.real(), in.real()};
        break;
    }
    if (in.byte() & 1u) shape.local.position = engine::Vec3(in.real(), in.real(), in.real());
    if (in.byte() & 1u) shape.density = in.real();
    if (in.byte() & 1u) shape.material.friction = in.real();
    spec.shapes.push_back(shape);
  }
  node::setSpecTwist(spec, twist);
  return spec;
}

inline void runRequests(Bytes& in) {
  // Loaded once: every input starts from the same scene.
  static const engine::Result<node::LoadedScene> loaded =
      node::loadScene(test::yamlToXmlRpc(kRequestScene), node::SceneOverrides{});
  if (!loaded) fail("the request scene does not load: " + loaded.message());
  node::SimulationLimits limits;
  limits.max_particles = 24;
  limits.max_steps_per_request = 20;
  limits.max_links = 16;
  limits.max_sustained_forces = 4;
  limits.max_bodies = 6;
  limits.max_joints = 4;
  node::Simulation sim(loaded.value().world, limits, loaded.value().joint_names);
  std::vector<std::uint64_t> handed_out;
  for (const char* name : {"p", "q", "l_0", "l_3"}) {
    handed_out.push_back(sim.resolve({0, name}).value().packed());
  }
  const auto ref = [&]() {
    node::ParticleRef r;
    const std::uint8_t how = in.byte() % 4;
    if (how == 0) r.name = in.text(vocabulary());
    if (how == 1) r.id = in.u64();
    if (how >= 2) r.id = handed_out[in.byte() % handed_out.size()];
    return r;
  };
  std::vector<std::uint64_t> bodies_handed_out;
  for (const char* name : {"crate", "wheel"}) {
    bodies_handed_out.push_back(sim.resolveBody({0, name}).value().packed());
  }
  const auto body_ref = [&]() {
    node::BodyRef r;
    const std::uint8_t how = in.byte() % 4;
    if (how == 0) r.name = in.text(vocabulary());
    if (how == 1) r.id = in.u64();
    if (how >= 2) r.id = bodies_handed_out[in.byte() % bodies_handed_out.size()];
    return r;
  };
  const auto joint_end = [&]() {
    node::JointEndRef end;
    end.kind = static_cast<node::JointEndRef::Kind>(in.byte() % 3);
    if (end.kind == node::JointEndRef::Kind::kBody) {
      const node::BodyRef r = body_ref();
      end.id = r.id;
      end.name = r.name;
    } else if (end.kind == node::JointEndRef::Kind::kParticle) {
      const node::ParticleRef r = ref();
      end.id = r.id;
      end.name = r.name;
    }
    return end;
  };
  int budget = 60;  // steps per input, so one input stays fast
  for (int op = 0; op < 64 && !in.empty(); ++op) {
    const Fingerprint before(sim);
    engine::Status status = engine::Status::ok();
    bool may_change = true;
    switch (in.byte() % 19) {
      case 0: {
        std::vector<engine::ParticleSpec> specs;
        const int n = 1 + in.byte() % 3;
        for (int i = 0; i < n && status; ++i) {
          ParticleSpec msg;
          msg.name = in.text(vocabulary());
          msg.position.x = in.real();
          msg.position.y = in.real();
          msg.position.z = in.real();
          msg.velocity.x = in.real();
          msg.mass = in.real();
          msg.fixed = in.byte() % 5 == 0;
          msg.radius = in.real();
          msg.damping = in.real();
          const auto spec = node::toParticleSpec(msg, 0.1);
          if (!spec) status = spec.status();
          if (spec) specs.push_back(*spec);
        }
        if (status) {
          const auto ids = sim.spawn(specs);
          status = ids.status();
          if (ids) {
            for (const auto id : *ids) {
              handed_out.push_back(id.packed());
              const auto dense = *sim.world().particles().find(id);
              if (!node::checkPosition(sim.world().particles().positions().col(dense), "x")) {
                fail("a spawned particle out of bounds");
              }
            }
          }
        }
        break;
      }
      case 1: {
        std::vector<node::ParticleRef> refs;
        const int n = in.byte() % 4;
        for (int i = 0; i < n; ++i) refs.push_back(ref());
        status = sim.remove(refs).status();
        break;
      }
      case 2: {
        const node::ParticleRef r = ref();
        std::optional<engine::Vec3> x;
        std::optional<engine::Vec3> v;
        const std::uint8_t which = in.byte();
        if (which & 1u) x = engine::Vec3(in.real(), in.real(), in.real());
        if (which & 2u) v = engine::Vec3(in.real(), in.real(), in.real());
        status = sim.setState(r, x, v);
        break;
      }
      case 3: {
        node::ForceRequest f;
        f.particle = ref();
        f.force = engine::Vec3(in.real(), in.real(), in.real());
        f.mode = static_cast<node::ForceMode>(in.byte() % 4);
        f.duration = in.real();
        status = sim.applyForce(f).status();
        break;
      }
      case 4: {
        const node::ParticleRef r = ref();
        status = sim.applyImpulse(r, engine::Vec3(in.real(), in.real(), in.real())).status();
        break;
      }
      case 5: {
        node::LinkRequest l;
        const auto type = node::parseLinkType(in.text(vocabulary()));
        if (!type) {
          may_change = false;
          break;
        }
        l.type = *type;
        l.a = ref();
        if (in.byte() & 1u) l.b = ref();
        l.anchor = engine::Vec3(in.real(), in.real(), in.real());
        l.stiffness = in.real();
        l.damping = in.real();
        l.rest_length = in.real();
        l.max_length = in.real();
        l.length = in.real();
        l.restitution = in.real();
        status = sim.addLink(l).status();
        break;
      }
      case 6:
        status = sim.removeLink(static_cast<engine::GeneratorId>(in.byte() % 24));
        break;
      case 7:
      case 8: {
        const std::uint32_t n = in.byte() % 24;
        if (static_cast<int>(n) > budget) {
          may_change = false;
          break;
        }
        budget -= static_cast<int>(n);
        const std::uint64_t divergences = sim.world().divergenceCount();
        status = sim.stepMany(n);
        const auto& p = sim.world().particles();
        if ((!p.positions().allFinite() || !p.velocities().allFinite()) &&
            sim.world().divergenceCount() == divergences && status) {
          fail("a non-finite state went unreported");
        }
        break;
      }
      case 9:
        sim.reset();
        break;
      case 10: {
        std::vector<engine::BodySpec> specs;
        const int n = 1 + in.byte() % 2;
        for (int i = 0; i < n; ++i) specs.push_back(bodySpecFrom(in));
        const auto ids = sim.spawnBodies(specs);
        status = ids.status();
        if (ids) {
          for (const auto id : *ids) bodies_handed_out.push_back(id.packed());
        }
        break;
      }
      case 11: {
        std::vector<node::BodyRef> refs;
        const int n = in.byte() % 3;
        for (int i = 0; i < n; ++i) refs.push_back(body_ref());
        status = sim.removeBodies(refs).status();
        break;
      }
      case 12: {
        const node::BodyRef r = body_ref();
        std::optional<engine::Transform> pose;
        std::optional<node::Twist> twist;
        const std::uint8_t which = in.byte();
        if (which & 1u) {
          pose = engine::Transform{engine::Vec3(in.real(), in.real(), in.real()),
                                   engine::Quat(in.real(), in.real(), in.real(), in.real())};
        }
        if (which & 2u) {
          twist = node::Twist{engine::Vec3(in.real(), in.real(), in.real()),
                              engine::Vec3(in.real(), in.real(), in.real())};
        }
        status = sim.setBodyState(r, pose, twist);
        break;
      }
      case 13: {
        node::WrenchRequest w;
        w.body = body_ref();
        w.force = engine::Vec3(in.real(), in.real(), in.real());
        w.torque = engine::Vec3(in.real(), in.real(), in.real());
        w.point = engine::Vec3(in.real(), in.real(), in.real());
        w.mode = static_cast<node::ForceMode>(in.byte() % 4);
        w.duration = in.real();
        status = sim.applyBodyWrench(w).status();
        break;
      }
      case 14: {
        const node::BodyRef r = body_ref();
        status = sim.applyBodyImpulse(r, engine::Vec3(in.real(), in.real(), in.real()),
                                      engine::Vec3(in.real(), in.real(), in.real()),
                                      engine::Vec3(in.real(), in.real(), in.real()))
                     .status();
        break;
      }
      case 15: {
        node::JointRequest j;
        j.type = in.text(vocabulary());
        j.name = in.byte() & 1u ? in.text(vocabulary()) : "";
        j.a = joint_end();
        j.b = joint_end();
        j.anchor_a = engine::Vec3(in.real(), in.real(), in.real());
        j.anchor_b = in.byte() & 1u ? engine::Vec3(in.real(), in.real(), in.real()) : j.anchor_a;
        if (in.byte() & 1u)
          j.values.directions["axis"] = engine::Vec3(in.real(), in.real(), in.real());
        if (in.byte() & 1u) j.values.flags["limit"] = in.byte() & 1u;
        if (in.byte() & 1u) j.values.flags["motor"] = in.byte() & 1u;
        for (const char* field :
             {"lower", "upper", "motor_speed", "max_motor_torque", "min_length", "max_length"}) {
          if (in.byte() & 1u) j.values.numbers[field] = in.real();
        }
        j.every_field = in.byte() % 4 == 0;
        j.collide_connected = in.byte() & 1u;
        status = sim.addJoint(j).status();
        break;
      }
      case 16:
        status = sim.removeJoint(static_cast<engine::JointId>(in.byte() % 8));
        break;
      case 17:
        status = sim.setHingeMotor(static_cast<engine::JointId>(in.byte() % 8), in.byte() & 1u,
                                   in.real(), in.real());
        break;
      case 18: {
        // A live reconfigure: a few of the settings changed, checked as the node checks them; a
        // change they pass must be one Simulation::configure takes.
        node::LiveSettings live = node::liveSettingsOf(sim.settings(), 30.0, false);
        const std::uint8_t which = in.byte();
        if (which & 1u) live.rate = in.real();
        if (which & 2u) live.substeps = in.byte() - 8;
        if (which & 4u) live.gravity = engine::Vec3(in.real(), in.real(), in.real());
        if (which & 8u) live.max_iterations = in.byte() - 8;
        if (which & 16u) live.penetration_slop = in.real();
        if (which & 32u) live.body_substeps = in.byte() - 8;
        if (which & 64u) live.body_iterations = in.byte() - 8;
        if (which & 128u) {
          live.body_relax_iterations = in.byte() - 8;
          live.body_sleep = in.byte() & 1u;
        }
        const auto physics = node::applyLiveSettings(live, sim.settings());
        status = physics.status();
        if (physics) {
          status = sim.configure(*physics);
          if (!status) fail("a checked reconfigure was refused: " + status.message());
        }
        break;
      }
    }
    if (!may_change) continue;
    if (!status) {
      if (status.message().empty()) fail("a refusal without a message");
      if (!(Fingerprint(sim) == before))
        fail("a refused request changed the world: " + status.message());
    }
    if (sim.world().particles().size() > limits.max_particles) fail("more than max_particles");
    if (sim.world().generators().size() + sim.world().links().size() > limits.max_links) {
      fail("more than max_links");
    }
    if (sim.sustainedForceCount() > limits.max_sustained_forces) fail("more than max_sustained");
    if (sim.world().bodies().size() > limits.max_bodies) fail("more than max_bodies");
    if (sim.world().joints().size() > limits.max_joints) fail("more than max_joints");
    const engine::BodyStore& b = sim.world().bodies();
    for (std::size_t i = 0; i < b.size(); ++i) {
      if (!b.position(i).allFinite() && sim.world().divergenceCount() == 0) {
        fail("a non-finite body went unreported");
      }
    }
  }
}

inline void runSceneInput(const std::uint8_t* data, const std::size_t size) {
  if (size == 0) return;
  Bytes in(data + 1, size - 1);
  switch (data[0] % 3) {
    case 0: {
      XmlRpc::XmlRpcValue tree;
      try {
        tree = test::yamlToXmlRpc(in.rest());
      } catch (const YAML::Exception&) {
        return;  // not YAML: rosparam would refuse it before the node sees it
      }
      loadAndStep(tree);
      break;
    }
    case 1: {
      XmlRpc::XmlRpcValue tree = treeFromBytes(in, 0);
      loadAndStep(tree);
      break;
    }
    case 2:
      runRequests(in);
      break;
  }
}

}  // namespace scene
}  // namespace fuzz
}  // namespace mass_aggregate_sim
