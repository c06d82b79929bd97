#include "engine/core/sort_runs.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <random>
#include <vector>

namespace mass_aggregate_sim {
namespace engine {
namespace {

const auto kLess = [](const int x, const int y) { return x < y; };

std::vector<int> sortedCopy(std::vector<int> items) {
  std::sort(items.begin(), items.end());
  return items;
}

TEST(SortRuns, EmptyAndSingleAndSortedStayAsTheyAre) {
  for (const std::vector<int>& items : {std::vector<int>{}, {7}, {1, 2, 3, 9}}) {
    std::vector<int> sorted = items;
    sortRuns(sorted, kLess);
    EXPECT_EQ(sorted, items);
  }
}

TEST(SortRuns, MergesUpToMaxRunsAndSortsBeyond) {
  // Runs as the narrowphase gives them: the tree's pairs, then the planes'.
  const std::vector<std::vector<int>> cases = {
      {5, 6, 7, 1, 2, 3},              // two runs
      {4, 8, 1, 9, 2, 3},              // three
      {9, 1, 8, 2, 7, 3, 6, 4, 5, 0},  // many (a plain sort)
      {3, 2, 1},                       // descending: runs of one
      {1, 1, 2, 0, 0, 3},              // repeats within a run
  };
  for (const std::vector<int>& items : cases) {
    std::vector<int> sorted = items;
    sortRuns(sorted, kLess);
    EXPECT_EQ(sorted, sortedCopy(items));
  }
}

TEST(SortRuns, SortsShuffledKeysForEveryRunLimit) {
  std::mt19937 random(3);
  for (int max_runs = 1; max_runs <= 6; ++max_runs) {
    for (int trial = 0; trial < 50; ++trial) {
      std::vector<int> items(static_cast<std::size_t>(random() % 40));
      for (int& item : items) item = static_cast<int>(random() % 100);
      // Some trials as a few sorted runs, the others shuffled.
      if (trial % 2 == 0) {
        const std::size_t cut = items.empty() ? 0 : random() % items.size();
        std::sort(items.begin(), items.begin() + static_cast<std::ptrdiff_t>(cut));
        std::sort(items.begin() + static_cast<std::ptrdiff_t>(cut), items.end());
      }
      std::vector<int> sorted = items;
      sortRuns(sorted, kLess, max_runs);
      EXPECT_EQ(sorted, sortedCopy(items)) << "max_runs " << max_runs << " trial " << trial;
    }
  }
}

}  // namespace
}  // namespace engine
}  // namespace mass_aggregate_sim
