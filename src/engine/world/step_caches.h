#pragma once

#include <vector>

#include "engine/forces/force_stage.h"
#include "engine/forces/stiff_spring_stage.h"
#include "engine/integrators/implicit_euler.h"
#include "engine/world/particle_energies.h"
#include "mass_aggregate_sim/engine/integrators/integrator.h"
#include "mass_aggregate_sim/engine/world/stability.h"

namespace mass_aggregate_sim {
namespace engine {

// Per particle and substep length h (damping_flow.h): d^h for every integrator, and for the
// Verlets and RK4 also d^(h/2) and phi(h/2). Valid for this h and damping version.
struct DampingFactors {
  ScalarArray decay;
  ScalarArray half_decay;
  ScalarArray half_gain;
  Real h = 0.0;
  std::uint64_t version = ~std::uint64_t{0};
  bool halves = false;
};

// The stability report and what the energy guard takes with it, recomputed when what they depend
// on (the particles and their masses, the springs, dt, substeps, the integrator) may have changed.
struct StabilityCache {
  struct Inputs {
    std::size_t particles = 0;
    std::size_t generators = 0;
    std::uint64_t generators_version = 0;
    std::uint64_t damping_version = 0;
    Real dt = 0.0;
    int substeps = 0;
    Integrator integrator = Integrator::kSemiImplicitEuler;
    bool operator==(const Inputs& o) const {
      return particles == o.particles && generators == o.generators &&
             generators_version == o.generators_version && damping_version == o.damping_version &&
             dt == o.dt && substeps == o.substeps && integrator == o.integrator;
    }
  };
  bool valid = false;
  Inputs inputs;
  StabilityReport report;  // the particles' springs, undamped (what the energy guard allows for)
  StabilityReport damped;  // the same with the springs' damping (World::stabilityReport())
  StabilityReport drag;    // the particles' drags
  // With drags or generators on bodies: the binding one of damped, drag and the bodies' reports
  // (World::stabilityReport()), taken again every time (it depends on the bodies, whose masses
  // it reads).
  StabilityReport with_bodies;
  // Per-particle accelerations or a generator's uncounted work add work the energy omits.
  bool uncounted_work = false;
  Real movable_mass = 0.0;
  ScalarArray mass;  // 0 for immovable particles
};

// Everything the world derives from its state to save work: never state (a copied world starts
// without it and derives it again, to the same bits).
struct StepCaches {
  ForceStage forces;
  DampingFactors damping;
  StabilityCache stability;
  // The energy sums of the last semi-implicit Euler pass, when it made them this step.
  ParticleEnergies pass_energies;
  bool pass_energies_valid = false;
  // Whether the state the last semi-implicit Euler pass wrote is finite, when it probed it this
  // step (the step ends in that state and the energy guard does not judge it).
  bool pass_finite = true;
  bool pass_finite_valid = false;
  Vec3Array scratch_x;
  Vec3Array scratch_v;
  Vec3Array stage_a[3];
  ImplicitEulerSolver implicit;
  std::vector<StiffParticle> stiff;
};

}  // namespace engine
}  // namespace mass_aggregate_sim
