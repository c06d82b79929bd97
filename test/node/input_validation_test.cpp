// Every refusal names the field and the rule and changes nothing (docs/RELIABILITY.md): requests
// through Simulation, scenes through the loader, node parameters through checkParamType.
#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <limits>
#include <string>
#include <vector>

#include "mass_aggregate_sim/node/input_limits.h"
#include "mass_aggregate_sim/node/scene_loader.h"
#include "mass_aggregate_sim/node/simulation.h"
#include "yaml_to_xmlrpc.h"

namespace mass_aggregate_sim {
namespace node {
namespace {

using engine::ParticleSpec;
using engine::Status;
using engine::Vec3;

constexpr double kNan = std::numeric_limits<double>::quiet_NaN();
constexpr double kInf = std::numeric_limits<double>::infinity();

engine::World makeScene() {
  engine::WorldConfig config;
  config.dt = 0.01;
  engine::World world(config);
  ParticleSpec spec;
  spec.name = "ball";
  spec.inverse_mass = 0.5;
  spec.position = Vec3(0, 0, 1);
  world.addParticle(spec);
  spec.name = "post";
  spec.inverse_mass = 0.0;
  spec.position = Vec3(1, 0, 1);
  world.addParticle(spec);
  spec.name = "gone";
  spec.inverse_mass = 1.0;
  world.addParticle(spec);
  return world;
}

ParticleSpec particle(const std::string& name, const Vec3& position = Vec3::Zero()) {
  ParticleSpec spec;
  spec.name = name;
  spec.inverse_mass = 1.0;
  spec.position = position;
  return spec;
}

// What a refused request must leave untouched: the dynamic state and every count.
struct Fingerprint {
  std::uint64_t hash;
  std::size_t particles;
  std::size_t generators;
  std::size_t links;
  std::size_t sustained;
  bool operator==(const Fingerprint& o) const {
    return hash == o.hash && particles == o.particles && generators == o.generators &&
           links == o.links && sustained == o.sustained;
  }
};

Fingerprint fingerprint(const Simulation& sim) {
  return {sim.world().stateHash(), sim.world().particles().size(), sim.world().generators().size(),
          sim.world().links().size(), sim.sustainedForceCount()};
}

struct Case {
  const char* what;
  std::function<Status(Simulation&)> request;
  std::string field;  // the message must contain it
};

LinkRequest spring(const std::string& a, const std::string& b) {
  LinkRequest r;
  r.a.name = a;
  r.b = ParticleRef{0, b};
  r.stiffness = 10.0;
  return r;
}

TEST(InputValidationTest, RefusedRequestsNameTheFieldAndChangeNothing) {
  SimulationLimits limits;
  limits.max_particles = 6;
  limits.max_steps_per_request = 50;
  limits.world_frame = "map";
  Simulation sim(makeScene(), limits);
  const std::uint64_t stale = sim.resolve(ParticleRef{0, "gone"}).value().packed();
  ASSERT_TRUE(sim.remove({ParticleRef{0, "gone"}}).isOk());
  ASSERT_TRUE(sim.addLink(spring("ball", "post")).isOk());
  sim.step();

  const auto spawnOne = [](const ParticleSpec& spec) {
    return [spec](Simulation& s) { return s.spawn({spec}).status(); };
  };
  const auto withMass = [](const double mass) {
    ParticleSpec spec = particle("m");
    spec.inverse_mass = 1.0 / mass;
    return spec;
  };
  ParticleSpec fast = particle("fast");
  fast.velocity = Vec3(0, -2e5, 0);
  ParticleSpec big = particle("big");
  big.radius = 2e3;
  ParticleSpec pushed = particle("pushed");
  pushed.acceleration = Vec3(0, 0, 1e7);
  const auto link = [](LinkRequest r) {
    return [r](Simulation& s) { return s.addLink(r).status(); };
  };
  LinkRequest negative_k = spring("ball", "post");
  negative_k.stiffness = -1.0;
  LinkRequest huge_k = spring("ball", "post");
  huge_k.stiffness = 1e13;
  LinkRequest negative_c = spring("ball", "post");
  negative_c.damping = -0.5;
  LinkRequest long_rest = spring("ball", "post");
  long_rest.rest_length = 5e6;
  LinkRequest nan_rest = spring("ball", "post");
  nan_rest.rest_length = kNan;
  LinkRequest bouncy = spring("ball", "post");
  bouncy.type = LinkType::kCable;
  bouncy.restitution = 1.5;
  LinkRequest far_anchor = spring("ball", "");
  far_anchor.b.reset();
  far_anchor.anchor = Vec3(0, 2e6, 0);
  LinkRequest stale_a = spring("", "post");
  stale_a.a.id = stale;
  LinkRequest unknown_b = spring("ball", "nobody");
  ForceRequest huge_force{ParticleRef{0, "ball"}, Vec3(1e10, 0, 0), ForceMode::kOneStep, 0.0};
  ForceRequest nan_force{ParticleRef{0, "ball"}, Vec3(0, kNan, 0), ForceMode::kUntilCleared, 0.0};
  ForceRequest no_duration{ParticleRef{0, "ball"}, Vec3(1, 0, 0), ForceMode::kDuration, 0.0};

  const std::vector<Case> cases = {
      {"spawn beyond the coordinate bound", spawnOne(particle("far", Vec3(0, 0, 1.5e6))),
       "particles[0]: position"},
      {"spawn NaN position", spawnOne(particle("nan", Vec3(kNan, 0, 0))), "position"},
      {"spawn too fast", spawnOne(fast), "particles[0]: velocity"},
      {"spawn too light", spawnOne(withMass(1e-9)), "particles[0]: mass"},
      {"spawn too heavy", spawnOne(withMass(1e12)), "particles[0]: mass"},
      {"spawn too big", spawnOne(big), "particles[0]: radius"},
      {"spawn too accelerated", spawnOne(pushed), "particles[0]: acceleration"},
      {"spawn named as the world frame", spawnOne(particle("map")), "particles[0]: name"},
      {"spawn named as a collider frame", spawnOne(particle("map/collider_1")), "name"},
      {"spawn with a space in the name", spawnOne(particle("a b")), "name"},
      {"spawn with a leading slash", spawnOne(particle("/a")), "name"},
      {"spawn with a long name", spawnOne(particle(std::string(kMaxNameLength + 1, 'x'))), "name"},
      {"spawn a taken name", spawnOne(particle("ball")), "already taken"},
      {"spawn one name twice",
       [](Simulation& s) {
         return s.spawn({particle("twin"), particle("twin")}).status();
       },
       "particles[1]"},
      {"spawn over max_particles",
       [](Simulation& s) { return s.spawn(std::vector<ParticleSpec>(5, ParticleSpec{})).status(); },
       "max_particles"},
      {"remove an unknown name",
       [](Simulation& s) {
         return s.remove({ParticleRef{0, "nobody"}}).status();
       },
       "nobody"},
      {"remove a stale id",
       [stale](Simulation& s) {
         return s.remove({ParticleRef{stale, ""}}).status();
       },
       std::to_string(stale)},
      {"remove more refs than max_particles",
       [](Simulation& s) {
         return s.remove(std::vector<ParticleRef>(7, ParticleRef{0, "ball"})).status();
       },
       "max_particles"},
      {"teleport beyond the bound",
       [](Simulation& s) {
         return s.setState({0, "ball"}, Vec3(-2e6, 0, 0), std::nullopt);
       },
       "position"},
      {"set an infinite velocity",
       [](Simulation& s) {
         return s.setState({0, "ball"}, std::nullopt, Vec3(0, kInf, 0));
       },
       "velocity"},
      {"set a velocity beyond the bound",
       [](Simulation& s) {
         return s.setState({0, "ball"}, std::nullopt, Vec3(0, 0, 1e6));
       },
       "velocity"},
      {"set the state of a stale id",
       [stale](Simulation& s) {
         return s.setState({stale, ""}, Vec3::Zero(), std::nullopt);
       },
       "no particle with id"},
      {"force beyond the bound",
       [huge_force](Simulation& s) { return s.applyForce(huge_force).status(); }, "force"},
      {"NaN force", [nan_force](Simulation& s) { return s.applyForce(nan_force).status(); },
       "force"},
      {"zero duration", [no_duration](Simulation& s) { return s.applyForce(no_duration).status(); },
       "duration"},
      {"impulse giving a speed beyond the bound",
       [](Simulation& s) {
         return s.applyImpulse({0, "ball"}, Vec3(4e5, 0, 0)).status();
       },
       "impulse"},
      {"NaN impulse",
       [](Simulation& s) {
         return s.applyImpulse({0, "ball"}, Vec3(kNan, 0, 0)).status();
       },
       "impulse"},
      {"negative stiffness", link(negative_k), "stiffness"},
      {"stiffness beyond the bound", link(huge_k), "stiffness"},
      {"negative damping", link(negative_c), "damping"},
      {"rest length beyond the bound", link(long_rest), "rest_length"},
      {"NaN rest length", link(nan_rest), "rest_length"},
      {"restitution above 1", link(bouncy), "restitution"},
      {"anchor beyond the bound", link(far_anchor), "anchor"},
      {"link from a stale id", link(stale_a), "a: "},
      {"link to an unknown name", link(unknown_b), "b: "},
      {"remove an unknown link", [](Simulation& s) { return s.removeLink(9999); }, "9999"},
      {"zero steps", [](Simulation& s) { return s.stepMany(0); }, "steps"},
      {"too many steps", [](Simulation& s) { return s.stepMany(51); }, "steps"},
  };
  for (const Case& c : cases) {
    const Fingerprint before = fingerprint(sim);
    const Status status = c.request(sim);
    EXPECT_FALSE(status.isOk()) << c.what;
    EXPECT_NE(status.message().find(c.field), std::string::npos)
        << c.what << ": '" << status.message() << "' should name " << c.field;
    EXPECT_TRUE(fingerprint(sim) == before) << c.what << " changed the world";
  }
}

TEST(InputValidationTest, ValuesAtTheBoundsAreAccepted) {
  Simulation sim(makeScene(), SimulationLimits{});
  ParticleSpec edge = particle("edge", Vec3(kMaxCoordinate, -kMaxCoordinate, kMaxCoordinate));
  edge.velocity = Vec3(kMaxSpeed, 0, -kMaxSpeed);
  edge.inverse_mass = 1.0 / kMinMass;
  edge.radius = kMaxRadius;
  ASSERT_TRUE(sim.spawn({edge}).isOk());
  ParticleSpec heavy = particle("heavy");
  heavy.inverse_mass = 1.0 / kMaxMass;
  ASSERT_TRUE(sim.spawn({heavy}).isOk());
  EXPECT_TRUE(sim.setState({0, "ball"}, Vec3(0, 0, -kMaxCoordinate), Vec3(0, kMaxSpeed, 0)));
  // From rest: v = J / m = J * 0.5 lands exactly on the bound.
  ASSERT_TRUE(sim.setState({0, "ball"}, std::nullopt, Vec3::Zero()));
  EXPECT_TRUE(sim.applyImpulse({0, "ball"}, Vec3(2.0 * kMaxSpeed, 0, 0)).isOk());
  LinkRequest r = spring("ball", "heavy");
  r.stiffness = kMaxStiffness;
  r.damping = kMaxLinkDamping;
  r.rest_length = kMaxLength;
  EXPECT_TRUE(sim.addLink(r).isOk());
  EXPECT_TRUE(sim.applyForce({{0, "ball"}, Vec3(kMaxForce, 0, 0), ForceMode::kOneStep, 0.0}));
}

TEST(InputValidationTest, ForcesOnBodiesCountAgainstTheLinkLimit) {
  engine::World world = makeScene();
  engine::BodySpec crate;
  crate.shapes.push_back(engine::BodyShapeSpec{});
  const engine::BodyId id = *world.addBody(crate);
  engine::BodyDrag drag;
  drag.body = id;
  drag.k1 = 1.0;
  ASSERT_TRUE(world.addBodyGenerator(drag));
  SimulationLimits limits;
  limits.max_links = 1;
  Simulation sim(world, limits);
  const Fingerprint before = fingerprint(sim);
  const auto refused = sim.addLink(spring("ball", "post"));
  ASSERT_FALSE(refused.isOk());
  EXPECT_NE(refused.message().find("already 1 links and force generators"), std::string::npos)
      << refused.message();
  EXPECT_TRUE(fingerprint(sim) == before);
}

TEST(InputValidationTest, ASpringOnABodyIsALinkToRemoveButDragIsNot) {
  engine::World world = makeScene();
  engine::BodySpec crate;
  crate.shapes.push_back(engine::BodyShapeSpec{});
  const engine::BodyId id = *world.addBody(crate);
  const engine::GeneratorId spring = *world.addBodyGenerator(engine::PointSpring::between(
      engine::JointEnd::onBody(id), engine::JointEnd::inWorld(Vec3(0, 0, 3)), 10.0));
  engine::BodyDrag drag;
  drag.body = id;
  drag.k1 = 1.0;
  const engine::GeneratorId drag_id = *world.addBodyGenerator(drag);
  Simulation sim(world, SimulationLimits{});
  const Fingerprint before = fingerprint(sim);
  const auto refused = sim.removeLink(drag_id);
  ASSERT_FALSE(refused.isOk());
  EXPECT_NE(refused.message().find("no link with id"), std::string::npos) << refused.message();
  EXPECT_TRUE(fingerprint(sim) == before);
  ASSERT_TRUE(sim.removeLink(spring).isOk());
  EXPECT_TRUE(sim.world().bodyGenerators().of<engine::PointSpring>().empty());
  EXPECT_EQ(sim.world().bodyGenerators().of<engine::BodyDrag>().size(), 1u);
}

TEST(InputValidationTest, LinkAndSustainedForceLimitsHold) {
  SimulationLimits limits;
  limits.max_links = 1;
  limits.max_sustained_forces = 1;
  Simulation sim(makeScene(), limits);
  ASSERT_TRUE(sim.addLink(spring("ball", "post")).isOk());
  Fingerprint before = fingerprint(sim);
  const auto second = sim.addLink(spring("ball", "gone"));
  ASSERT_FALSE(second.isOk());
  EXPECT_NE(second.message().find("~max_links"), std::string::npos) << second.message();
  EXPECT_TRUE(fingerprint(sim) == before);

  const ForceRequest forever{{0, "ball"}, Vec3(1, 0, 0), ForceMode::kUntilCleared, 0.0};
  ASSERT_TRUE(sim.applyForce(forever).isOk());
  before = fingerprint(sim);
  const auto again = sim.applyForce(forever);
  ASSERT_FALSE(again.isOk());
  EXPECT_NE(again.message().find("sustained"), std::string::npos) << again.message();
  EXPECT_TRUE(fingerprint(sim) == before);
  // A one-step force is not kept, so the limit does not apply to it.
  EXPECT_TRUE(sim.applyForce({{0, "ball"}, Vec3(1, 0, 0), ForceMode::kOneStep, 0.0}).isOk());
}

void expectSceneError(const std::string& yaml, const std::string& key,
                      const SceneOverrides& overrides = {}) {
  const auto loaded = loadScene(test::yamlToXmlRpc(yaml), overrides);
  ASSERT_FALSE(loaded.isOk()) << yaml;
  EXPECT_EQ(loaded.message().rfind(key + ": ", 0), 0u) << loaded.message();
}

TEST(InputValidationTest, ScenesKeepTheSameBounds) {
  expectSceneError("{particles: [{name: a, position: [0, 0, 1.000001e+6]}]}",
                   "scene.particles[0].position");
  expectSceneError("{particles: [{position: [0, 0, 0], velocity: [1.0e+6, 0, 0]}]}",
                   "scene.particles[0].velocity");
  expectSceneError("{particles: [{position: [0, 0, 0], mass: 1.0e-12}]}",
                   "scene.particles[0].mass");
  expectSceneError("{particles: [{position: [0, 0, 0], radius: 5000}]}",
                   "scene.particles[0].radius");
  expectSceneError("{particles: [{name: world, position: [0, 0, 0]}]}", "scene.particles[0].name");
  expectSceneError("{particles: [{name: 'a b', position: [0, 0, 0]}]}", "scene.particles[0].name");
  expectSceneError("{gravity: [0, 0, -1.0e+7]}", "scene.gravity");
  // A block whose far corner leaves the box is refused at that particle.
  expectSceneError("{blocks: [{origin: [999990, 0, 0], count: [20, 1, 1], spacing: 1}]}",
                   "scene.blocks[0].position");
  // A line's count is checked before anything is allocated for it.
  SceneOverrides small;
  small.max_particles = 100;
  expectSceneError("{lines: [{name: l, start: [0, 0, 0], end: [1, 0, 0], count: 2000000000}]}",
                   "scene.lines[0].count", small);
  expectSceneError(
      "{particles: [{name: a, position: [0, 0, 0]}], links: [{type: spring, a: a, anchor: [2.0e+6, "
      "0, 0], stiffness: 1}]}",
      "scene.links[0]");
  expectSceneError(
      "{particles: [{name: a, position: [0, 0, 0]}], links: [{type: spring, a: a, anchor: [1, 0, "
      "0], stiffness: 1.0e+13}]}",
      "scene.links[0]");
  expectSceneError("{colliders: [{type: sphere, center: [0, 3.0e+6, 0], radius: 1}]}",
                   "scene.colliders[0].center");
  expectSceneError("{colliders: [{type: plane, normal: [0, 0, 1], offset: -2.0e+6}]}",
                   "scene.colliders[0].offset");
  expectSceneError("{colliders: [{type: box, half_extents: [1, 1, 5.0e+6]}]}",
                   "scene.colliders[0].half_extents");
  SceneOverrides one_link;
  one_link.max_links = 1;
  expectSceneError(
      "{particles: [{name: a, position: [0, 0, 0]}, {name: b, position: [1, 0, 0]}], links: "
      "[{type: spring, a: a, b: b, stiffness: 1}, {type: rod, a: a, b: b}]}",
      "scene.links[1]", one_link);
  SceneOverrides framed;
  framed.world_frame = "odom";
  expectSceneError("{particles: [{name: odom, position: [0, 0, 0]}]}", "scene.particles[0].name",
                   framed);
}

TEST(InputValidationTest, NodeParametersMustHaveTheirType) {
  using XmlRpc::XmlRpcValue;
  EXPECT_TRUE(checkParamType("rate", XmlRpcValue(100), ParamType::kNumber));
  EXPECT_TRUE(checkParamType("rate", XmlRpcValue(99.5), ParamType::kNumber));
  const Status as_text = checkParamType("rate", XmlRpcValue("fast"), ParamType::kNumber);
  ASSERT_FALSE(as_text);
  EXPECT_EQ(as_text.message(), "~rate: expected a number");
  EXPECT_FALSE(checkParamType("substeps", XmlRpcValue(2.5), ParamType::kInt));
  EXPECT_FALSE(checkParamType("paused", XmlRpcValue(1), ParamType::kBool));
  EXPECT_FALSE(checkParamType("frame_id", XmlRpcValue(3), ParamType::kString));
  XmlRpcValue gravity;
  gravity.setSize(3);
  gravity[0] = 0;
  gravity[1] = 0.0;
  gravity[2] = -9.81;
  EXPECT_TRUE(checkParamType("gravity", gravity, ParamType::kVec3));
  gravity[2] = "down";
  EXPECT_FALSE(checkParamType("gravity", gravity, ParamType::kVec3));
  gravity.setSize(2);
  EXPECT_FALSE(checkParamType("gravity", gravity, ParamType::kVec3));
}

}  // namespace
}  // namespace node
}  // namespace mass_aggregate_sim
