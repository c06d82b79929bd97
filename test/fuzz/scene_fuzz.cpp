// libFuzzer target: arbitrary scene YAML, arbitrary XmlRpc trees and arbitrary request fields
// through the node's scene loader and request checks, no ROS master (see scene_ops.h).
// scripts/fuzz.sh reads the fuzz-sources and fuzz-flags lines whole, so they stay unwrapped.
// clang-format off
// fuzz-sources: src/node/scene_loader.cpp src/node/scene_contacts.cpp src/node/xmlrpc_reader.cpp src/node/links.cpp src/node/simulation.cpp src/node/conversions.cpp src/node/input_limits.cpp src/node/scene_bodies.cpp src/node/body_requests.cpp src/node/joint_requests.cpp src/node/simulation_bodies.cpp
// fuzz-flags: -lyaml-cpp -lxmlrpcpp -lroscpp_serialization -lrostime -lcpp_common
// clang-format on
#include "scene_ops.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  mass_aggregate_sim::fuzz::scene::runSceneInput(data, size);
  return 0;
}
