// libFuzzer target: arbitrary scene YAML, arbitrary XmlRpc trees and arbitrary request fields
// through the node's scene loader and request checks, no ROS master (see scene_ops.h).
// scripts/fuzz.sh reads the fuzz-libraries and fuzz-flags lines whole, so they stay unwrapped.
// clang-format off
// fuzz-libraries: mass_aggregate_sim_ros
// fuzz-flags: -lyaml-cpp -lxmlrpcpp -lroscpp_serialization -lrostime -lcpp_common
// clang-format on
#include "scene_ops.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  mass_aggregate_sim::fuzz::scene::runSceneInput(data, size);
  return 0;
}
