#pragma once

#include <dynamic_reconfigure/Config.h>

#include "mass_aggregate_sim/SimConfig.h"
#include "mass_aggregate_sim/node/settings.h"

namespace mass_aggregate_sim {
namespace node {

// Between the generated reconfigure type (cfg/Sim.cfg) and the node's settings.
SimConfig toSimConfig(const LiveSettings& settings);
LiveSettings fromSimConfig(const SimConfig& config);
// The physics settings as a dynamic_reconfigure/Config, without `paused` (a pause is recorded as
// a pause) and `publish_rate` (it changes no state): what ~commands records for a "reconfigure"
// and what a replay sends to the target's ~set_parameters.
dynamic_reconfigure::Config toRecordedConfig(const LiveSettings& settings);
bool sameSettings(const LiveSettings& a, const LiveSettings& b);
bool samePhysics(const LiveSettings& a, const LiveSettings& b);

}  // namespace node
}  // namespace mass_aggregate_sim
