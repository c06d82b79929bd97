#include "engine/bodies/particle_pair.h"

#include <algorithm>
#include <cstddef>

#include "engine/solver/contact_response.h"

namespace mass_aggregate_sim {
namespace engine {
namespace {

// f(pair, a, b, n, distance) for each pair whose centres do not coincide: its solver bodies, the
// unit normal from a to b now and the distance between the centres.
template <typename F>
void forEachPair(std::vector<ParticlePair>& pairs, std::vector<SolverBody>& bodies, F&& f) {
  for (ParticlePair& pair : pairs) {
    SolverBody& a = bodies[static_cast<std::size_t>(pair.a)];
    SolverBody& b = bodies[static_cast<std::size_t>(pair.b)];
    const Vec3 d = (pair.start_b + b.dp) - (pair.start_a + a.dp);
    const Real distance = d.norm();
    if (!(distance > 1e-12)) continue;
    f(pair, a, b, Vec3(d / distance), distance);
  }
}

}  // namespace

void warmStartParticlePairs(std::vector<ParticlePair>& pairs, std::vector<SolverBody>& bodies) {
  forEachPair(
      pairs, bodies,
      [](ParticlePair& pair, SolverBody& a, SolverBody& b, const Vec3& n, Real /*distance*/) {
        // The friction impulse acts on a, and the normal one along -n on a: a's total is f - j n.
        pair.friction_impulse = pair.alone
                                    ? response::eigen(response::warmFriction(
                                          response::lanes(pair.friction_impulse),
                                          response::lanes(n), pair.friction, pair.normal_impulse))
                                    : Vec3(Vec3::Zero());
        const Vec3 on_a = pair.friction_impulse - pair.normal_impulse * n;
        a.v += a.inverse_mass * on_a;
        b.v -= b.inverse_mass * on_a;
      });
}

void solveParticlePairs(std::vector<ParticlePair>& pairs, std::vector<SolverBody>& bodies,
                        const Real h) {
  forEachPair(
      pairs, bodies,
      [h](ParticlePair& pair, SolverBody& a, SolverBody& b, const Vec3& n, const Real distance) {
        const Real mass = 1.0 / (a.inverse_mass + b.inverse_mass);
        // C = |d| - (r_a + r_b) >= 0: a gap (C > 0) may close at C / h within the substep.
        const Real gap = distance - pair.touching;
        const Real bias = gap > 0.0 ? gap / h : 0.0;
        const Real closing = n.dot(b.v - a.v);
        const Real total = std::max(pair.normal_impulse - mass * (closing + bias), Real{0.0});
        const Vec3 push = (total - pair.normal_impulse) * n;
        pair.normal_impulse = total;
        a.v -= a.inverse_mass * push;
        b.v += b.inverse_mass * push;
        if (!pair.alone || pair.friction <= 0.0) return;
        const Vec3 next = response::eigen(response::coulomb(
            response::lanes(pair.friction_impulse), response::lanes(Vec3(a.v - b.v)),
            response::lanes(n), mass, pair.friction, total));
        const Vec3 change = next - pair.friction_impulse;
        pair.friction_impulse = next;
        a.v += a.inverse_mass * change;
        b.v -= b.inverse_mass * change;
      });
}

}  // namespace engine
}  // namespace mass_aggregate_sim
