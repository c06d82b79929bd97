#pragma once
// What every part of the accuracy study shares: the CPU clock it times runs with and the CSV files
// it writes.

#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <string>

namespace mass_aggregate_sim {
namespace study {

// Runs are repeated until at least this much CPU time (s) is measured.
constexpr double kMinimumCpuSeconds = 0.02;

inline double cpuSeconds() { return static_cast<double>(std::clock()) / CLOCKS_PER_SEC; }

// Opens dir/name for writing with its header line; exits when it cannot.
inline FILE* openCsv(const std::string& dir, const std::string& name, const char* header) {
  const std::string path = dir + "/" + name;
  FILE* file = std::fopen(path.c_str(), "w");
  if (!file) {
    std::fprintf(stderr, "cannot write %s\n", path.c_str());
    std::exit(1);
  }
  std::fprintf(file, "%s\n", header);
  return file;
}

}  // namespace study
}  // namespace mass_aggregate_sim
