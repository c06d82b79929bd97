#include "mass_aggregate_sim/node/snapshot.h"

#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <thread>

namespace mass_aggregate_sim {
namespace node {
namespace {

using engine::Vec3;

TEST(SnapshotTest, CopiesWhatThePublishersNeed) {
  engine::World world;
  engine::ParticleSpec spec;
  spec.name = "a";
  spec.inverse_mass = 0.5;
  spec.radius = 0.2;
  spec.position = Vec3(1, 2, 3);
  spec.velocity = Vec3(0, 1, 0);
  const auto a = world.addParticle(spec);
  spec.name = "";
  spec.position = Vec3(0, 0, 0);
  const auto b = world.addParticle(spec);
  ASSERT_TRUE(a && b);
  engine::Spring spring;
  spring.a = *a;
  spring.b = *b;
  spring.stiffness = 10.0;
  spring.rest_length = 1.0;
  ASSERT_TRUE(world.addGenerator(spring));
  world.step();
  WorldSnapshot snapshot;
  takeSnapshot(world, snapshot);
  EXPECT_EQ(snapshot.step, 1u);
  ASSERT_EQ(snapshot.ids.size(), 2u);
  EXPECT_EQ(snapshot.ids[0], a.value().packed());
  EXPECT_EQ(snapshot.names[0], "a");
  EXPECT_EQ(snapshot.named, 1u);
  EXPECT_EQ(snapshot.positions, world.particles().positions());
  EXPECT_EQ(snapshot.velocities, world.particles().velocities());
  ASSERT_EQ(snapshot.links.size(), 1u);
  const Vec3 pa = world.particles().positions().col(0);
  const Vec3 pb = world.particles().positions().col(1);
  EXPECT_EQ(snapshot.links[0].a, pa);
  EXPECT_DOUBLE_EQ(snapshot.links[0].tension, 10.0 * ((pa - pb).norm() - 1.0));
}

TEST(SnapshotTest, DrawsASpringOnABodyAsALinkWithItsTension) {
  engine::World world;
  engine::BodySpec body;
  body.shapes.push_back(engine::BodyShapeSpec{});
  body.shapes[0].geometry = engine::SphereShape{0.5};
  body.pose.position = Vec3(0, 0, 2);
  const auto id = world.addBody(body);
  ASSERT_TRUE(id);
  ASSERT_TRUE(world.addBodyGenerator(
      engine::PointSpring::between(engine::JointEnd::onBody(*id, Vec3(0.5, 0, 0)),
                                   engine::JointEnd::inWorld(Vec3(0.5, 0, 5)), 4.0, 1.0)));
  WorldSnapshot snapshot;
  takeSnapshot(world, snapshot);
  ASSERT_EQ(snapshot.links.size(), 1u);
  EXPECT_NEAR((snapshot.links[0].a - Vec3(0.5, 0, 2)).norm(), 0.0, 1e-12);
  EXPECT_EQ(snapshot.links[0].b, Vec3(0.5, 0, 5));
  EXPECT_NEAR(snapshot.links[0].tension, 4.0 * (3.0 - 1.0), 1e-12);
}

// The consumer only ever sees whole frames, the latest one published, and never waits for the
// producer's copy.
TEST(FrameExchangeTest, HandsOverWholeFramesOnly) {
  struct Frame {
    std::vector<int> values;
  };
  FrameExchange<Frame> exchange;
  std::atomic<bool> done{false};
  std::thread producer([&] {
    for (int i = 1; i <= 20000; ++i) {
      Frame& frame = exchange.back();
      frame.values.assign(64, i);
      exchange.publish();
    }
    done = true;
    exchange.wake();
  });
  int last = 0;
  int taken = 0;
  while (!done || taken == 0) {
    if (!exchange.take(std::chrono::milliseconds(10))) continue;
    const Frame& frame = exchange.front();
    ASSERT_EQ(frame.values.size(), 64u);
    for (const int v : frame.values) ASSERT_EQ(v, frame.values[0]);
    ASSERT_GT(frame.values[0], last);
    last = frame.values[0];
    ++taken;
  }
  producer.join();
  if (exchange.take(std::chrono::milliseconds(0))) last = exchange.front().values[0];
  EXPECT_EQ(last, 20000);
}

}  // namespace
}  // namespace node
}  // namespace mass_aggregate_sim
