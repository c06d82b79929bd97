#pragma once
// What the service handlers of SimNode share (sim_node_*.cpp).

#include <sstream>
#include <string>

#include "mass_aggregate_sim/engine/world/world.h"

namespace mass_aggregate_sim {
namespace node {

inline std::string describeTime(const engine::World& world) {
  std::ostringstream out;
  out.precision(9);
  out << "step " << world.stepCount() << ", t = " << world.time() << " s";
  return out.str();
}

template <typename Response>
bool answer(Response& res, const bool success, const std::string& message) {
  res.success = success;
  res.message = message;
  return true;
}

}  // namespace node
}  // namespace mass_aggregate_sim
