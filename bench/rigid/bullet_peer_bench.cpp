// Bullet 3 (btDiscreteDynamicsWorld, btDbvtBroadphase, btSequentialImpulseConstraintSolver with
// 10 iterations) on the shared rigid scenes of rigid_scenes.h: the peer the project's own rigid
// bodies are measured against. Only this executable links Bullet; the engine never does.
//
// Arguments of every case: /<scene size>/<substeps>/<sleeping>. A frame is 1/60 s made of
// `substeps` calls stepSimulation(1 / (60 substeps), 0): maxSubSteps = 0 makes Bullet take exactly
// that one step, where stepSimulation(1/60, n, 1/(60 n)) lets its accumulator round to n - 1 or
// n + 1 steps in a frame. sleeping = 0 turns deactivation off for every body (the timing runs);
// 1 keeps Bullet's default (a body at rest for 2 s sleeps).
//
// Each case builds its scene and simulates 10 s untimed (their mean cost per frame is settle_ms;
// the worst and mean deepest overlap over their last 3 s are late_max_pen_m and late_mean_pen_m,
// the bodies that moved more than 1 mm and 1 cm over them late_moved_mm and late_moved_cm, the
// bodies in free fall over the last frame in_flight and the others' kinetic energy inside the walls
// pile_kinetic_J),
// records the at-rest quality then (counters, rigid_report.h), and times a fixed number of further
// frames: Time and CPU are per frame (1/60 s, all its substeps), one thread.
#include <benchmark/benchmark.h>
#include <btBulletDynamicsCommon.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <map>
#include <memory>
#include <string>
#include <tuple>
#include <vector>

#include "rigid_report.h"
#include "rigid_scenes.h"

namespace mass_aggregate_sim {
namespace bench {
namespace rigid {
namespace {

constexpr int kSolverIterations = 10;

btVector3 toBullet(const Eigen::Vector3d& v) {
  return btVector3(static_cast<btScalar>(v.x()), static_cast<btScalar>(v.y()),
                   static_cast<btScalar>(v.z()));
}

// Bullet multiplies the two bodies' coefficients; the scenes take the geometric mean (Box2D), which
// is the product of the square roots. Restitution is 0 everywhere (checked in runScene), which
// Bullet's product gives as well.
btScalar bulletFriction(const double friction) {
  return static_cast<btScalar>(std::sqrt(friction));
}

bool hasRestitution(const RigidScene& scene) {
  return scene.ground.restitution != 0.0 ||
         std::any_of(scene.bodies.begin(), scene.bodies.end(),
                     [](const BodySpec& body) { return body.restitution != 0.0; });
}

class BulletWorld {
 public:
  BulletWorld(const RigidScene& scene, const int substeps, const bool sleeping)
      : scene_(scene), substeps_(substeps) {
    world_.setGravity(toBullet(scene.gravity));
    world_.getSolverInfo().m_numIterations = kSolverIterations;

    ground_shape_ = std::make_unique<btStaticPlaneShape>(
        btVector3(0, 0, 1), static_cast<btScalar>(scene.ground.height));
    btRigidBody::btRigidBodyConstructionInfo ground_info(0, nullptr, ground_shape_.get());
    ground_info.m_friction = bulletFriction(scene.ground.friction);
    ground_info.m_restitution = static_cast<btScalar>(scene.ground.restitution);
    ground_ = std::make_unique<btRigidBody>(ground_info);
    world_.addRigidBody(ground_.get());

    bodies_.reserve(scene.bodies.size());
    for (const BodySpec& spec : scene.bodies) {
      btCollisionShape* const shape = shapeFor(spec);
      const auto mass = static_cast<btScalar>(spec.isFixed() ? 0.0 : spec.mass);
      btVector3 inertia(0, 0, 0);
      if (!spec.isFixed()) shape->calculateLocalInertia(mass, inertia);
      btRigidBody::btRigidBodyConstructionInfo info(mass, nullptr, shape, inertia);
      const Eigen::Quaterniond& q = spec.orientation;
      info.m_startWorldTransform =
          btTransform(btQuaternion(static_cast<btScalar>(q.x()), static_cast<btScalar>(q.y()),
                                   static_cast<btScalar>(q.z()), static_cast<btScalar>(q.w())),
                      toBullet(spec.position));
      info.m_friction = bulletFriction(spec.friction);
      info.m_restitution = static_cast<btScalar>(spec.restitution);
      auto body = std::make_unique<btRigidBody>(info);
      if (!spec.isFixed()) {
        body->setLinearVelocity(toBullet(spec.linear_velocity));
        body->setAngularVelocity(toBullet(spec.angular_velocity));
        if (!sleeping) body->setActivationState(DISABLE_DEACTIVATION);
      }
      world_.addRigidBody(body.get());
      bodies_.push_back(std::move(body));
    }
  }

  // The world refers to its bodies until they are removed, and its destructor reads them.
  ~BulletWorld() {
    for (auto& body : bodies_) world_.removeRigidBody(body.get());
    world_.removeRigidBody(ground_.get());
  }

  BulletWorld(const BulletWorld&) = delete;
  BulletWorld& operator=(const BulletWorld&) = delete;

  void stepFrame() {
    const auto dt = static_cast<btScalar>(kFrameSeconds / substeps_);
    for (int s = 0; s < substeps_; ++s) world_.stepSimulation(dt, 0, dt);
  }

  AtRest atRest() const {
    AtRest result;
    for (std::size_t i = 0; i < bodies_.size(); ++i) {
      const BodySpec& spec = scene_.bodies[i];
      if (spec.isFixed()) continue;
      result.kinetic_energy += kineticEnergy(i);
      if (hasEscaped(scene_, position(i))) ++result.escaped;
      if (!bodies_[i]->isActive()) ++result.asleep;
    }
    if (scene_.top_body >= 0) {
      const Eigen::Vector3d& start = scene_.bodies[scene_.top_body].position;
      const btVector3& now = bodies_[scene_.top_body]->getWorldTransform().getOrigin();
      result.top_drop = start.z() - now.z();
      result.top_distance = (start - Eigen::Vector3d(now.x(), now.y(), now.z())).norm();
    }
    for (int m = 0; m < dispatcher_.getNumManifolds(); ++m) {
      result.contacts += dispatcher_.getManifoldByIndexInternal(m)->getNumContacts();
    }
    result.max_penetration = deepestOverlap();
    return result;
  }

  Eigen::Vector3d position(const std::size_t k) const {
    const btVector3& p = bodies_[k]->getWorldTransform().getOrigin();
    return Eigen::Vector3d(p.x(), p.y(), p.z());
  }

  Eigen::Vector3d linearVelocity(const std::size_t k) const {
    const btVector3& v = bodies_[k]->getLinearVelocity();
    return Eigen::Vector3d(v.x(), v.y(), v.z());
  }

  // m v^2 / 2 + w_b . I w_b / 2, w_b the angular velocity in the body's principal frame.
  double kineticEnergy(const std::size_t k) const {
    const btRigidBody& body = *bodies_[k];
    const btVector3& v = body.getLinearVelocity();
    const btVector3 w = body.getWorldTransform().getBasis().transpose() * body.getAngularVelocity();
    const btVector3& inertia = body.getLocalInertia();
    return 0.5 * (scene_.bodies[k].mass * static_cast<double>(v.length2()) +
                  static_cast<double>(inertia.x() * w.x() * w.x() + inertia.y() * w.y() * w.y() +
                                      inertia.z() * w.z() * w.z()));
  }

  double deepestOverlap() const {
    double deepest = 0.0;
    for (int m = 0; m < dispatcher_.getNumManifolds(); ++m) {
      const btPersistentManifold& manifold = *dispatcher_.getManifoldByIndexInternal(m);
      for (int c = 0; c < manifold.getNumContacts(); ++c) {
        deepest =
            std::max(deepest, -static_cast<double>(manifold.getContactPoint(c).getDistance()));
      }
    }
    return deepest;
  }

 private:
  // One shape per distinct size: the pyramid's 5,050 boxes share one.
  btCollisionShape* shapeFor(const BodySpec& spec) {
    const auto key = std::make_tuple(spec.shape, spec.half_extents.x(), spec.half_extents.y(),
                                     spec.half_extents.z(), spec.radius);
    auto found = shapes_.find(key);
    if (found == shapes_.end()) {
      std::unique_ptr<btCollisionShape> shape;
      if (spec.shape == ShapeType::kSphere) {
        shape = std::make_unique<btSphereShape>(static_cast<btScalar>(spec.radius));
      } else {
        shape = std::make_unique<btBoxShape>(toBullet(spec.half_extents));
      }
      found = shapes_.emplace(key, std::move(shape)).first;
    }
    return found->second.get();
  }

  const RigidScene& scene_;
  const int substeps_;
  btDefaultCollisionConfiguration configuration_;
  btCollisionDispatcher dispatcher_{&configuration_};
  btDbvtBroadphase broadphase_;
  btSequentialImpulseConstraintSolver solver_;
  btDiscreteDynamicsWorld world_{&dispatcher_, &broadphase_, &solver_, &configuration_};
  std::map<std::tuple<ShapeType, double, double, double, double>, std::unique_ptr<btCollisionShape>>
      shapes_;
  std::unique_ptr<btCollisionShape> ground_shape_;
  std::unique_ptr<btRigidBody> ground_;
  std::vector<std::unique_ptr<btRigidBody>> bodies_;  // in the order of scene_.bodies
};

void runScene(benchmark::State& state, const RigidScene& scene) {
  const auto substeps = static_cast<int>(state.range(1));
  const bool sleeping = state.range(2) != 0;
  if (hasRestitution(scene)) {
    state.SkipWithError("restitution other than 0: Bullet combines it differently (product)");
    return;
  }
  state.SetLabel(std::string(btIsDoublePrecision() ? "double" : "float") + ", " + scene.name +
                 (sleeping ? ", default deactivation" : ", deactivation off"));

  BulletWorld world(scene, substeps, sleeping);
  const Settled settled = settle(world, scene);
  const AtRest at_rest = world.atRest();

  for (auto _ : state) {
    world.stepFrame();
    benchmark::ClobberMemory();
  }

  state.counters["double_prec"] = btIsDoublePrecision() ? 1.0 : 0.0;
  reportAtRest(state, scene, at_rest, settled);
}

// Substeps 1 and 4, deactivation off and Bullet's default; `kFrames` timed frames each.
template <int kSize, int kFrames>
void runs(benchmark::internal::Benchmark* b) {
  for (const int sleeping : {0, 1}) {
    for (const int substeps : {1, 4}) b->Args({kSize, substeps, sleeping});
  }
  b->Iterations(kFrames)->Unit(benchmark::kMillisecond);
}

// The quality ladder, deactivation off: 2, 8 and 16 substeps (those up to kMaxSubsteps), to find
// the least that reaches a given at-rest quality (docs/BENCHMARKS.md, "equal quality").
template <int kSize, int kMaxSubsteps>
void ladderRuns(benchmark::internal::Benchmark* b) {
  for (const int substeps : {2, 8, 16}) {
    if (substeps <= kMaxSubsteps) b->Args({kSize, substeps, 0});
  }
}

void BM_Bullet_RigidPyramid(benchmark::State& state) {
  runScene(state, pyramid(static_cast<int>(state.range(0))));
}
void BM_Bullet_DroppedPyramid(benchmark::State& state) {
  runScene(state, droppedPyramid(static_cast<int>(state.range(0))));
}
void BM_Bullet_PyramidAndRoller(benchmark::State& state) {
  runScene(state, pyramidAndRoller(static_cast<int>(state.range(0))));
}
void BM_Bullet_RigidStack(benchmark::State& state) {
  runScene(state, stack(static_cast<int>(state.range(0))));
}
void BM_Bullet_RandomDrop(benchmark::State& state) {
  runScene(state,
           randomDrop(static_cast<int>(state.range(0)), benchmarkSeed(kRandomDropDefaultSeed)));
}
void BM_Bullet_ParticleRain(benchmark::State& state) {
  runScene(state, particleRain(static_cast<int>(state.range(0)), benchmarkSeed(kRainDefaultSeed)));
}

BENCHMARK(BM_Bullet_RigidPyramid)->Apply(runs<20, 600>)->Apply(ladderRuns<20, 16>);
BENCHMARK(BM_Bullet_RigidPyramid)->Apply(runs<100, 60>)->Apply(ladderRuns<100, 8>);
BENCHMARK(BM_Bullet_DroppedPyramid)->Apply(runs<20, 600>)->Apply(ladderRuns<20, 16>);
BENCHMARK(BM_Bullet_PyramidAndRoller)
    ->Args({100, 4, 1})
    ->Iterations(60)
    ->Unit(benchmark::kMillisecond);
BENCHMARK(BM_Bullet_RigidStack)->Apply(runs<10, 600>)->Apply(ladderRuns<10, 16>);
BENCHMARK(BM_Bullet_RigidStack)->Apply(runs<20, 600>)->Apply(ladderRuns<20, 16>);
BENCHMARK(BM_Bullet_RandomDrop)->Apply(runs<1000, 300>)->Apply(ladderRuns<1000, 16>);
BENCHMARK(BM_Bullet_ParticleRain)
    ->Apply(runs<kRainDefaultSpheres, 300>)
    ->Apply(ladderRuns<kRainDefaultSpheres, 16>);

}  // namespace
}  // namespace rigid
}  // namespace bench
}  // namespace mass_aggregate_sim

BENCHMARK_MAIN();
