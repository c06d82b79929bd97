// An invalid config is refused, never silently replaced: the constructor throws InvalidConfig
// with the reason, World::create() returns it, setConfig() keeps the old config.
#include <gtest/gtest.h>

#include <string>

#include "mass_aggregate_sim/engine/world/world.h"

namespace mass_aggregate_sim {
namespace engine {
namespace {

WorldConfig oneSecondSteps() {
  WorldConfig config;
  config.dt = 1.0;  // valid alone, but longer than max_frame_time (0.25 s)
  config.integrator = Integrator::kRk4;
  return config;
}

TEST(WorldConfig, ConstructorThrowsOnAnInvalidConfig) {
  try {
    const World world(oneSecondSteps());
    FAIL() << "constructed a world with dt = 1 s and max_frame_time 0.25 s: dt "
           << world.config().dt;
  } catch (const InvalidConfig& e) {
    EXPECT_NE(std::string(e.what()).find("max_frame_time must be finite and >= dt"),
              std::string::npos)
        << e.what();
  }
  WorldConfig nan_gravity;
  nan_gravity.gravity.x() = std::nan("");
  EXPECT_THROW(World{nan_gravity}, InvalidConfig);
  WorldConfig substeps;
  substeps.substeps = 0;
  EXPECT_THROW(World{substeps}, InvalidConfig);
}

TEST(WorldConfig, CreateReturnsTheReasonOrTheWorld) {
  const Result<World> refused = World::create(oneSecondSteps());
  ASSERT_FALSE(refused);
  EXPECT_NE(refused.message().find("max_frame_time"), std::string::npos) << refused.message();

  WorldConfig config = oneSecondSteps();
  config.max_frame_time = 1.0;
  Result<World> made = World::create(config);
  ASSERT_TRUE(made) << made.message();
  const World world = std::move(made).take();
  EXPECT_EQ(world.config().dt, 1.0);
  EXPECT_EQ(world.config().integrator, Integrator::kRk4);
}

TEST(WorldConfig, SetConfigRefusesAndKeepsTheOldOne) {
  World world;
  const WorldConfig before = world.config();
  EXPECT_FALSE(world.setConfig(oneSecondSteps()));
  EXPECT_EQ(world.config().dt, before.dt);
  EXPECT_EQ(world.config().integrator, before.integrator);
}

}  // namespace
}  // namespace engine
}  // namespace mass_aggregate_sim
