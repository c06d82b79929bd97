#include "mass_aggregate_sim/engine/integrators/integrator.h"

#include <array>
#include <utility>

namespace mass_aggregate_sim {
namespace engine {
namespace {

constexpr std::array<std::pair<Integrator, const char*>, 6> kNames{{
    {Integrator::kExplicitEuler, "explicit_euler"},
    {Integrator::kSemiImplicitEuler, "semi_implicit_euler"},
    {Integrator::kPositionVerlet, "position_verlet"},
    {Integrator::kVelocityVerlet, "velocity_verlet"},
    {Integrator::kRk4, "rk4"},
    {Integrator::kImplicitEuler, "implicit_euler"},
}};

}  // namespace

const std::array<Integrator, 6>& allIntegrators() {
  static const std::array<Integrator, 6> all = [] {
    std::array<Integrator, 6> kinds{};
    for (std::size_t i = 0; i < kNames.size(); ++i) kinds[i] = kNames[i].first;
    return kinds;
  }();
  return all;
}

const char* integratorName(const Integrator integrator) {
  for (const auto& [kind, name] : kNames) {
    if (kind == integrator) return name;
  }
  return "unknown";
}

std::optional<Integrator> parseIntegrator(const std::string& name) {
  for (const auto& [kind, known] : kNames) {
    if (name == known) return kind;
  }
  return std::nullopt;
}

std::string integratorNames() {
  std::string names;
  for (const auto& entry : kNames) {
    if (!names.empty()) names += ", ";
    names += entry.second;
  }
  return names;
}

int integratorOrder(const Integrator integrator) {
  switch (integrator) {
    case Integrator::kPositionVerlet:
    case Integrator::kVelocityVerlet:
      return 2;
    case Integrator::kRk4:
      return 4;
    default:
      return 1;
  }
}

}  // namespace engine
}  // namespace mass_aggregate_sim
