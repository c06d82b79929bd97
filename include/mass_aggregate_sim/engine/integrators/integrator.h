#pragma once

#include <array>
#include <optional>
#include <string>

namespace mass_aggregate_sim {
namespace engine {

enum class Integrator {
  kExplicitEuler,      // x' = x + v dt, v' = v + a dt                     (order 1)
  kSemiImplicitEuler,  // v' = v + a dt, x' = x + v' dt  (symplectic)       (order 1)
  kPositionVerlet,     // x' = 2x - x_prev + a dt^2                          (order 2)
  kVelocityVerlet,     // x' = x + v dt + a dt^2/2, v' = v + (a + a')dt/2   (order 2)
  kRk4,                // classical Runge-Kutta, forces at every stage       (order 4)
  kImplicitEuler,      // linearised backward Euler, one sparse solve a step (order 1)
};

// Every integrator, in declaration order.
const std::array<Integrator, 6>& allIntegrators();

// Names as used in scenes and parameters: explicit_euler, semi_implicit_euler, position_verlet,
// velocity_verlet, rk4, implicit_euler.
const char* integratorName(Integrator integrator);
std::optional<Integrator> parseIntegrator(const std::string& name);
// All names, comma separated, for error messages.
std::string integratorNames();
// The global order of accuracy in dt.
int integratorOrder(Integrator integrator);

}  // namespace engine
}  // namespace mass_aggregate_sim
