#pragma once

#include <algorithm>
#include <iterator>
#include <vector>

namespace mass_aggregate_sim {
namespace engine {

// Sorts items that come as a few sorted runs by merging the runs, in linear time a run (a
// quicksort of two sorted runs one after the other falls back to its heapsort); more than
// max_runs runs: a plain sort, so equal items may change places (meant for unique keys).
template <typename T, typename Less>
void sortRuns(std::vector<T>& items, const Less& less, const int max_runs = 4) {
  const auto run_end = [&](auto from) {
    if (from == items.end()) return from;
    for (auto next = std::next(from); next != items.end() && !less(*next, *from); ++next) {
      from = next;
    }
    return std::next(from);
  };
  auto sorted_end = run_end(items.begin());
  for (int runs = 1; sorted_end != items.end(); ++runs) {
    if (runs == max_runs) {
      std::sort(items.begin(), items.end(), less);
      return;
    }
    const auto next_end = run_end(sorted_end);
    std::inplace_merge(items.begin(), sorted_end, next_end, less);
    sorted_end = next_end;
  }
}

}  // namespace engine
}  // namespace mass_aggregate_sim
