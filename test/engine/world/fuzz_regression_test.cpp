// Replays every saved fuzz input (test/fuzz/regressions/, test/fuzz/engine_corpus/) through the
// same interpreter as the libFuzzer target; a broken promise aborts the test binary.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <vector>

#include "../../fuzz/engine_ops.h"

namespace {

namespace fs = std::filesystem;

TEST(FuzzRegressions, SavedEngineInputsKeepThePromises) {
  const fs::path fuzz_dir = fs::path(__FILE__).parent_path().parent_path().parent_path() / "fuzz";
  int replayed = 0;
  for (const char* folder : {"regressions", "engine_corpus"}) {
    if (!fs::exists(fuzz_dir / folder)) continue;
    for (const auto& entry : fs::directory_iterator(fuzz_dir / folder)) {
      if (!entry.is_regular_file() || entry.path().filename().string().rfind("engine", 0) != 0) {
        continue;
      }
      std::ifstream in(entry.path(), std::ios::binary);
      const std::vector<std::uint8_t> bytes((std::istreambuf_iterator<char>(in)),
                                            std::istreambuf_iterator<char>());
      mass_aggregate_sim::fuzz::runEngineOps(bytes.data(), bytes.size());
      ++replayed;
    }
  }
  EXPECT_GT(replayed, 0) << "no saved fuzz inputs found under " << fuzz_dir;
}

}  // namespace
