#include "mass_aggregate_sim/node/markers.h"

#include <gtest/gtest.h>

#include <map>

namespace mass_aggregate_sim {
namespace node {
namespace {

using engine::Vec3;
using visualization_msgs::Marker;

engine::ParticleId add(engine::World& world, const Vec3& x, const double radius,
                       const double inverse_mass = 1.0) {
  engine::ParticleSpec spec;
  spec.position = x;
  spec.radius = radius;
  spec.inverse_mass = inverse_mass;
  return *world.addParticle(spec);
}

std::map<std::string, int> countByNamespace(const visualization_msgs::MarkerArray& array,
                                            const int action) {
  std::map<std::string, int> count;
  for (const auto& m : array.markers) {
    if (m.action == action) ++count[m.ns];
  }
  return count;
}

TEST(MarkersTest, OneSphereListPerRadiusStartingWithDeleteAll) {
  engine::World world;
  for (int i = 0; i < 1000; ++i) add(world, Vec3(i, 0, 0), i % 2 ? 0.1 : 0.2);
  MarkerBuilder builder("world", 10.0);
  const auto first = builder.build(world, ros::Time(1.0));
  ASSERT_FALSE(first.markers.empty());
  EXPECT_EQ(first.markers[0].action, Marker::DELETEALL);
  ASSERT_EQ(first.markers.size(), 3u);
  std::size_t points = 0;
  for (std::size_t i = 1; i < first.markers.size(); ++i) {
    const Marker& m = first.markers[i];
    EXPECT_EQ(m.type, Marker::SPHERE_LIST);
    EXPECT_EQ(m.header.frame_id, "world");
    EXPECT_EQ(m.points.size(), 500u);
    EXPECT_TRUE(m.scale.x == 0.2 || m.scale.x == 0.4);
    points += m.points.size();
  }
  EXPECT_EQ(points, 1000u);
  // No DELETEALL the second time.
  const auto second = builder.build(world, ros::Time(2.0));
  EXPECT_EQ(countByNamespace(second, Marker::DELETEALL).size(), 0u);
  EXPECT_EQ(countByNamespace(second, Marker::ADD)["particles"], 2);
}

TEST(MarkersTest, VanishedMarkersAreDeletedAndRestartClearsAll) {
  engine::World world;
  const auto a = add(world, Vec3(0, 0, 0), 0.1);
  const auto b = add(world, Vec3(1, 0, 0), 0.3);
  const engine::Spring spring = engine::Spring::between(a, b, 10.0, 0.5, 0.0);
  const auto link = world.addGenerator(spring);
  ASSERT_TRUE(link.isOk());
  MarkerBuilder builder("world", 10.0);
  const auto first = builder.build(world, ros::Time(1.0));
  EXPECT_EQ(countByNamespace(first, Marker::ADD)["links"], 1);

  world.removeParticle(b);  // also removes the spring
  const auto second = builder.build(world, ros::Time(2.0));
  const auto deleted = countByNamespace(second, Marker::DELETE);
  EXPECT_EQ(deleted.at("particles"), 1);
  EXPECT_EQ(deleted.at("links"), 1);
  EXPECT_EQ(countByNamespace(second, Marker::ADD)["particles"], 1);

  builder.restart();
  const auto third = builder.build(world, ros::Time(3.0));
  EXPECT_EQ(third.markers[0].action, Marker::DELETEALL);
  EXPECT_EQ(countByNamespace(third, Marker::DELETE).size(), 0u);
}

TEST(MarkersTest, LinksAreColouredByTension) {
  engine::World world;
  const auto a = add(world, Vec3(0, 0, 0), 0.1);
  const auto b = add(world, Vec3(2, 0, 0), 0.1);
  const auto c = add(world, Vec3(0, 1, 0), 0.1);
  world.addGenerator(engine::Spring::between(a, b, 10.0, 1.0, 0.0));  // stretched by 1 m: 10 N
  world.addGenerator(engine::Spring::between(a, c, 10.0, 2.0, 0.0));  // compressed by 1 m: -10 N
  MarkerBuilder builder("world", 10.0);
  const auto array = builder.build(world, ros::Time(1.0));
  const Marker* lines = nullptr;
  for (const auto& m : array.markers) {
    if (m.ns == "links") lines = &m;
  }
  ASSERT_NE(lines, nullptr);
  EXPECT_EQ(lines->type, Marker::LINE_LIST);
  ASSERT_EQ(lines->points.size(), 4u);
  ASSERT_EQ(lines->colors.size(), 4u);
  EXPECT_FLOAT_EQ(lines->colors[0].r, 1.0f);  // fully stretched: red
  EXPECT_FLOAT_EQ(lines->colors[0].g, 0.0f);
  EXPECT_FLOAT_EQ(lines->colors[2].b, 1.0f);  // fully compressed: blue
  EXPECT_FLOAT_EQ(lines->colors[2].r, 0.0f);
  const auto slack = tensionColor(0.0, 10.0);
  EXPECT_FLOAT_EQ(slack.r, 1.0f);
  EXPECT_FLOAT_EQ(slack.g, 1.0f);
  EXPECT_FLOAT_EQ(slack.b, 1.0f);
}

TEST(MarkersTest, CablesAndRodsAreColouredByTheirTension) {
  engine::WorldConfig config;
  config.gravity = Vec3(0, 0, -9.81);
  config.substeps = 4;
  engine::World world(config);
  const auto hanging = add(world, Vec3(0, 0, -1), 0.1);  // 1 kg below a cable: +9.81 N
  const auto standing = add(world, Vec3(3, 0, 1), 0.1);  // 1 kg on top of a rod: -9.81 N
  ASSERT_TRUE(world.addLink(engine::Cable::anchoredAt(hanging, Vec3(0, 0, 0), 1.0, 0.0)).isOk());
  // 1 m from its anchor on a 2 m cable: slack.
  ASSERT_TRUE(world.addLink(engine::Cable::anchoredAt(standing, Vec3(3, 0, 2), 2.0, 0.0)).isOk());
  ASSERT_TRUE(world.addLink(engine::Rod::anchoredAt(standing, Vec3(3, 0, 0), 1.0)).isOk());
  for (int s = 0; s < 120; ++s) world.step();
  MarkerBuilder builder("world", 2.0 * 9.81);  // the weight is half the scale
  const auto array = builder.build(world, ros::Time(1.0));
  const Marker* lines = nullptr;
  for (const auto& m : array.markers) {
    if (m.ns == "links") lines = &m;
  }
  ASSERT_NE(lines, nullptr);
  ASSERT_EQ(lines->colors.size(), 6u);        // anchored cables first, then the rod
  EXPECT_FLOAT_EQ(lines->colors[0].r, 1.0f);  // half stretched: pink
  EXPECT_NEAR(lines->colors[0].g, 0.5f, 0.01f);
  EXPECT_NEAR(lines->colors[0].b, 0.5f, 0.01f);
  EXPECT_FLOAT_EQ(lines->colors[2].r, 1.0f);  // slack: white
  EXPECT_FLOAT_EQ(lines->colors[2].g, 1.0f);
  EXPECT_FLOAT_EQ(lines->colors[2].b, 1.0f);
  EXPECT_NEAR(lines->colors[4].r, 0.5f, 0.01f);  // half compressed: light blue
  EXPECT_NEAR(lines->colors[4].g, 0.5f, 0.01f);
  EXPECT_FLOAT_EQ(lines->colors[4].b, 1.0f);
}

TEST(MarkersTest, CollidersAreDrawnAsTheirShapes) {
  engine::World world;
  ASSERT_TRUE(world.addCollider(engine::PlaneCollider{}).isOk());
  engine::SphereCollider sphere;
  sphere.center = Vec3(1, 2, 3);
  sphere.radius = 0.5;
  ASSERT_TRUE(world.addCollider(sphere).isOk());
  engine::BoxCollider box;
  box.half_extents = Vec3(1, 2, 3);
  ASSERT_TRUE(world.addCollider(box).isOk());
  ASSERT_TRUE(world.addCollider(engine::CapsuleCollider{}).isOk());
  MarkerBuilder builder("world", 10.0);
  const auto array = builder.build(world, ros::Time(1.0));
  std::map<int, int> types;
  for (const auto& m : array.markers) {
    if (m.ns == "colliders") ++types[m.type];
  }
  EXPECT_EQ(types[Marker::CUBE], 2);      // plane and box
  EXPECT_EQ(types[Marker::SPHERE], 3);    // sphere and the capsule's ends
  EXPECT_EQ(types[Marker::CYLINDER], 1);  // the capsule's body
  for (const auto& m : array.markers) {
    if (m.ns == "colliders" && m.type == Marker::SPHERE && m.pose.position.x == 1.0) {
      EXPECT_DOUBLE_EQ(m.scale.x, 1.0);
      EXPECT_DOUBLE_EQ(m.pose.position.z, 3.0);
    }
    if (m.ns == "colliders" && m.type == Marker::CUBE && m.scale.y == 4.0) {
      EXPECT_DOUBLE_EQ(m.scale.x, 2.0);
      EXPECT_DOUBLE_EQ(m.scale.z, 6.0);
    }
  }
}

}  // namespace
}  // namespace node
}  // namespace mass_aggregate_sim
