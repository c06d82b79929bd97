// dynamic_reconfigure: a change is checked, applied by the world thread at the next step boundary,
// recorded on ~commands, and written back to the reconfigure server and the parameter server.
#include <ros/serialization.h>
#include <std_srvs/SetBool.h>

#include "mass_aggregate_sim/node/reconfigure.h"
#include "mass_aggregate_sim/node/sim_node.h"

namespace mass_aggregate_sim {
namespace node {

void SimNode::syncReconfigure(const std::function<void(LiveSettings&)>& change) {
  const boost::recursive_mutex::scoped_lock lock(reconfigure_mutex_);
  change(reconfigured_);
  reconfigure_->updateConfig(toSimConfig(reconfigured_));
  nh_.setParam("gravity", std::vector<double>{reconfigured_.gravity.x(), reconfigured_.gravity.y(),
                                              reconfigured_.gravity.z()});
}

void SimNode::onReconfigure(SimConfig& config, const std::uint32_t /*level*/) {
  // Called with reconfigure_mutex_ held, on the spinner thread.
  const LiveSettings wanted = fromSimConfig(config);
  if (sameSettings(wanted, reconfigured_)) return;
  std::string refusal;
  LiveSettings now;
  std::uint64_t step = 0;
  const bool ran = queue_.run([&] {
    step = sim_.world().stepCount();
    const PhysicsSettings before = sim_.settings();
    const auto physics = applyLiveSettings(wanted, before);
    if (!physics) {
      refusal = physics.message();
      return;
    }
    const LiveSettings current = liveSettingsOf(before, publish_rate_, paused_);
    if (!samePhysics(wanted, current)) {
      const dynamic_reconfigure::Config recorded = toRecordedConfig(wanted);
      const std::uint32_t size = ros::serialization::serializationLength(recorded);
      std::vector<std::uint8_t> bytes(size);
      ros::serialization::OStream stream(bytes.data(), size);
      ros::serialization::serialize(stream, recorded);
      recordBytes("reconfigure", std::move(bytes));
      const engine::Status applied = sim_.configure(*physics);
      if (!applied) {
        refusal = applied.message();
        return;
      }
      rate_ = wanted.rate;
      configurationChanged();
    }
    // Not recorded: it changes what is published, not the world.
    publish_rate_ = wanted.publish_rate;
    if (wanted.paused != paused_) {
      std_srvs::SetBool::Request pause;
      pause.data = wanted.paused;
      recordCommand("pause", pause);
      paused_ = wanted.paused;
    }
    now = liveSettingsOf(sim_.settings(), publish_rate_, paused_);
  });
  if (!ran) refusal = "the node is shutting down";
  if (!refusal.empty()) {
    ROS_WARN("reconfigure refused, nothing changed: %s", refusal.c_str());
    config = toSimConfig(reconfigured_);
    return;
  }
  ROS_INFO("reconfigured at step %lu", static_cast<unsigned long>(step));
  reconfigured_ = now;
  config = toSimConfig(now);
  nh_.setParam("gravity", std::vector<double>{now.gravity.x(), now.gravity.y(), now.gravity.z()});
}

}  // namespace node
}  // namespace mass_aggregate_sim
