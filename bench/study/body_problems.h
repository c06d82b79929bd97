#pragma once
// The rigid-body problems of the accuracy study (issue 14): scenes with analytic answers, run at
// given solver settings, each measuring how far it strays from its answer.

#include <functional>
#include <string>
#include <vector>

#include "mass_aggregate_sim/engine/world/world.h"

namespace mass_aggregate_sim {
namespace study {

using engine::Real;

// The body solver's knobs the study turns (engine::BodySettings): substeps per 1/60 s step,
// passes per substep, and a factor on both soft-constraint frequencies (contact_hertz 30 Hz and
// joint_hertz 60 Hz by default; the engine caps each at a quarter of the substep rate).
struct BodyKnobs {
  int substeps = 4;
  int iterations = 2;
  Real stiffness = 1.0;
};

// One quantity a problem measures, and the error levels the recommendations are made for.
struct BodyMetric {
  std::string name;
  std::string description;
  std::vector<Real> tolerances;
};

// A run's measurements, in the order of its problem's metrics.
struct BodyRun {
  std::vector<Real> values;
  bool diverged = false;  // the world reported a divergence or a value is not finite
};

struct BodyProblem {
  std::string name;
  std::string description;
  Real duration = 0.0;  // simulated s
  std::vector<BodyMetric> metrics;
  std::function<BodyRun(const BodyKnobs&)> run;
};

// The study's step: the engine's 60 Hz default; the substeps divide it.
constexpr Real kBodyDt = 1.0 / 60.0;

// The engine's soft-constraint frequencies at these knobs: the defaults times the factor, capped
// at a quarter of the substep rate (body_stages.cpp).
Real contactHertz(const BodyKnobs& knobs);
Real jointHertz(const BodyKnobs& knobs);

// Each defined in its own file (pendulum_problems.cpp, tumble_problem.cpp, stack_problems.cpp,
// bounce_problem.cpp), with its scene, its metrics and how they are measured.

// A 1 m, 1 kg rod (1 cm square) on a hinge at its top end, released at 5 degrees, 20 s: its
// period against the exact one, 4 sqrt(I / (m g d)) K(sin(theta0 / 2)); its amplitude; its anchor.
BodyProblem hingedPendulum();
// The same rod as four 25 cm segments welded by fixed joints: the welds must keep it rigid.
BodyProblem weldedPendulum();
// A free body of principal inertia (1, 2, 3) kg m^2 spun at w = (0.01, 2, 0.01) rad/s (about its
// intermediate axis, so it tumbles over and back), no gravity, 20 s: energy and L must hold.
BodyProblem torqueFreeTumble();
// Ten unit cubes on the ground, 10 s: placed touching (1 kg each); placed 1 cm apart, off-centre
// and turned, falling into place; the same placed touching; touching, alternately 1 and 100 kg.
// The top must not move.
BodyProblem cubeStack();
BodyProblem droppedStack();
BodyProblem turnedStack();
BodyProblem heavyLightStack();
// A 1 kg unit cube dropped flat from 1 m onto the ground, restitution 0.5 on both: it leaves at
// e sqrt(2 g h) = 2.215 m/s.
BodyProblem cubeBounce();

}  // namespace study
}  // namespace mass_aggregate_sim
