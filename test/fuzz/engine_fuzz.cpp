// libFuzzer target: arbitrary World calls with arbitrary fields (see engine_ops.h).
#include "engine_ops.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  mass_aggregate_sim::fuzz::runEngineOps(data, size);
  return 0;
}
