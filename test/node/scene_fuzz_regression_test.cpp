// Replays every saved input of the scene fuzz target (test/fuzz/regressions/scene-*,
// test/fuzz/scene_corpus/) through the same interpreter; a broken promise aborts the binary.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <vector>

#include "../fuzz/scene_ops.h"

namespace {

namespace fs = std::filesystem;

TEST(SceneFuzzRegressions, SavedSceneInputsKeepThePromises) {
  const fs::path fuzz_dir = fs::path(__FILE__).parent_path().parent_path() / "fuzz";
  int replayed = 0;
  for (const char* folder : {"regressions", "scene_corpus"}) {
    if (!fs::exists(fuzz_dir / folder)) continue;
    for (const auto& entry : fs::directory_iterator(fuzz_dir / folder)) {
      if (!entry.is_regular_file() || entry.path().filename().string().rfind("scene", 0) != 0) {
        continue;
      }
      std::ifstream in(entry.path(), std::ios::binary);
      const std::vector<std::uint8_t> bytes((std::istreambuf_iterator<char>(in)),
                                            std::istreambuf_iterator<char>());
      mass_aggregate_sim::fuzz::scene::runSceneInput(bytes.data(), bytes.size());
      ++replayed;
    }
  }
  EXPECT_GT(replayed, 0) << "no saved scene fuzz inputs found under " << fuzz_dir;
}

}  // namespace
