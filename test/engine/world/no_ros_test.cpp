// The engine must stay a plain C++/Eigen library: no ROS header in its sources or headers.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <regex>
#include <string>

namespace {

namespace fs = std::filesystem;

// The package root, from this file's location at build time (test/engine/world/no_ros_test.cpp).
fs::path packageRoot() {
  return fs::path(__FILE__).parent_path().parent_path().parent_path().parent_path();
}

TEST(EngineIsolation, NoRosHeaderInEngineSources) {
  const std::regex ros_include(
      R"(#\s*include\s*[<"](ros/|tf2|geometry_msgs|std_msgs|visualization_msgs|sensor_msgs|xmlrpcpp|XmlRpc|mass_aggregate_sim/(node|[A-Z])))");
  int files = 0;
  for (const char* dir : {"include/mass_aggregate_sim/engine", "src/engine"}) {
    for (const auto& entry : fs::recursive_directory_iterator(packageRoot() / dir)) {
      if (!entry.is_regular_file()) continue;
      ++files;
      std::ifstream in(entry.path());
      std::string line;
      int number = 0;
      while (std::getline(in, line)) {
        ++number;
        EXPECT_FALSE(std::regex_search(line, ros_include))
            << entry.path() << ":" << number << ": " << line;
      }
    }
  }
  EXPECT_GT(files, 10);
}

}  // namespace
