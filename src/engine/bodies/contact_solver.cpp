#include "engine/bodies/contact_solver.h"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <utility>

#include "engine/bodies/point_block_inverse.h"

namespace mass_aggregate_sim {
namespace engine {
namespace {

using PointVector = Eigen::Matrix<Real, Manifold::kMaxPoints, 1>;
using SmallVector = Eigen::Matrix<Real, Eigen::Dynamic, 1, 0, Manifold::kMaxPoints, 1>;

// The two sides of a contact as the rows see them: their solver bodies, or a body at rest for a
// side that never moves (its impulses go nowhere), made only for such a side.
class Sides {
 public:
  Sides(const ContactConstraint& c, std::vector<SolverBody>& bodies)
      : a(c.a == kNoBody ? still_a_.emplace() : bodies[static_cast<std::size_t>(c.a)]),
        b(c.b == kNoBody ? still_b_.emplace() : bodies[static_cast<std::size_t>(c.b)]) {}
  Sides(SolverBody& side_a, SolverBody& side_b) : a(side_a), b(side_b) {}

 private:
  std::optional<SolverBody> still_a_;
  std::optional<SolverBody> still_b_;

 public:
  SolverBody& a;
  SolverBody& b;
};

// v_n = n.(v_b - v_a) + w_b.(r_b x n) - w_a.(r_a x n)
Real normalVelocity(const ContactConstraint& c, const ContactConstraintPoint& cp, const Sides& s) {
  return c.normal.dot(s.b.v - s.a.v) + s.b.w.dot(cp.r_b.cross(c.normal)) -
         s.a.w.dot(cp.r_a.cross(c.normal));
}
Real normalPseudoVelocity(const ContactConstraint& c, const ContactConstraintPoint& cp,
                          const Sides& s) {
  return c.normal.dot(s.b.pv - s.a.pv) + s.b.pw.dot(cp.r_b.cross(c.normal)) -
         s.a.pw.dot(cp.r_a.cross(c.normal));
}

// Impulses j[i] along the normal rows of the points index[0..count), at once: -n sum j on a's
// linear and I_a^-1 sum j (r_a x n) off its angular velocity (or pseudo-velocities), + on b.
template <bool kPseudo>
void pushNormals(const ContactConstraint& c, Sides& s, const int* index, const int count,
                 const Real* j) {
  Real total = 0.0;
  Vec3 turn_a = Vec3::Zero();
  Vec3 turn_b = Vec3::Zero();
  for (int i = 0; i < count; ++i) {
    const ContactConstraintPoint& cp = c.points[index[i]];
    total += j[i];
    turn_a += j[i] * cp.r_a.cross(c.normal);
    turn_b += j[i] * cp.r_b.cross(c.normal);
  }
  Vec3& v_a = kPseudo ? s.a.pv : s.a.v;
  Vec3& w_a = kPseudo ? s.a.pw : s.a.w;
  Vec3& v_b = kPseudo ? s.b.pv : s.b.v;
  Vec3& w_b = kPseudo ? s.b.pw : s.b.w;
  v_a -= (c.inverse_mass_a * total) * c.normal;
  w_a -= s.a.inverse_inertia * turn_a;
  v_b += (c.inverse_mass_b * total) * c.normal;
  w_b += s.b.inverse_inertia * turn_b;
}
// One impulse j along point k's normal row.
template <bool kPseudo>
void pushNormal(const ContactConstraint& c, Sides& s, const int k, const Real j) {
  pushNormals<kPseudo>(c, s, &k, 1, &j);
}

// How far the anchors of c's points have moved apart along n since the step began:
//   n.(d_b - d_a), d = dp + dq r - r the move of a point fixed to a body at r from its centre,
// and n.(dq r - r) = (dq^T n - n).r: the normal is taken back into each side's starting frame
// once for all the points, leaving a dot product per point and side.
// On a rounded side the fixed point is the core's, r - rho n on a (r + rho n on b), rho = the
// rounding + s / 2 (the point is midway across the gap s; a swept contact's anchors are the
// touching points themselves, rho = the rounding): the core's point turns, the offset
// rho n does not. So a ball's turn, which carries its surface's points up off the ground
// (r (1 - cos theta): almost half its radius at a radian a step), leaves its contact where it is.
// The correction on a is rho (dq^T n - n).n, and likewise on b: a dot product per side.
class NormalDisplacement {
 public:
  NormalDisplacement(const ContactConstraint& c, const Sides& s)
      : shift_(c.normal.dot(s.b.dp - s.a.dp)),
        back_a_(s.a.dq_matrix.transpose() * c.normal - c.normal),
        back_b_(s.b.dq_matrix.transpose() * c.normal - c.normal),
        turn_a_(c.rounding_a > 0.0 ? back_a_.dot(c.normal) : 0.0),
        turn_b_(c.rounding_b > 0.0 ? back_b_.dot(c.normal) : 0.0),
        rounding_a_(c.rounding_a),
        rounding_b_(c.rounding_b),
        swept_(c.swept) {}
  Real of(const ContactConstraintPoint& cp) const {
    const Real half_gap = swept_ ? 0.0 : 0.5 * cp.separation;
    return shift_ + back_b_.dot(cp.r_b) - back_a_.dot(cp.r_a) + (rounding_a_ + half_gap) * turn_a_ +
           (rounding_b_ + half_gap) * turn_b_;
  }

 private:
  Real shift_;
  Vec3 back_a_;
  Vec3 back_b_;
  Real turn_a_;
  Real turn_b_;
  Real rounding_a_;
  Real rounding_b_;
  bool swept_;
};

// The separation of point cp now: as prepared, moved on by the anchors' displacements since.
Real separationNow(const ContactConstraint& c, const ContactConstraintPoint& cp, const Sides& s) {
  return cp.separation + NormalDisplacement(c, s).of(cp);
}
// Every point's separation now, in ContactConstraintPoint::current.
void takeSeparations(ContactConstraint& c, const Sides& s) {
  const NormalDisplacement moved(c, s);
  for (int k = 0; k < c.count; ++k)
    c.points[k].current = c.points[k].separation + moved.of(c.points[k]);
}

// Whether point cp closes within this substep: v_n < -s / h for a gap s > 0, v_n < 0 for overlap.
bool closes(const Real vn, const Real s, const Real h) { return s > 0.0 ? vn < -s / h : vn < 0.0; }

// K of the points index[0..count): K_ij = m_a + m_b + (r_ai x n).I_a^-1 (r_aj x n) + (b's).
SmallBlock coupledMass(const ContactConstraint& c, const SolverBody& a, const SolverBody& b,
                       const int* index, const int count) {
  Vec3 rn_a[Manifold::kMaxPoints];
  Vec3 rn_b[Manifold::kMaxPoints];
  Vec3 turn_a[Manifold::kMaxPoints];
  Vec3 turn_b[Manifold::kMaxPoints];
  for (int i = 0; i < count; ++i) {
    const ContactConstraintPoint& cp = c.points[index[i]];
    rn_a[i] = cp.r_a.cross(c.normal);
    rn_b[i] = cp.r_b.cross(c.normal);
    turn_a[i] = a.inverse_inertia * rn_a[i];
    turn_b[i] = b.inverse_inertia * rn_b[i];
  }
  SmallBlock k(count, count);
  for (int i = 0; i < count; ++i) {
    for (int j = 0; j < count; ++j) {
      k(i, j) =
          c.inverse_mass_a + c.inverse_mass_b + rn_a[i].dot(turn_a[j]) + rn_b[i].dot(turn_b[j]);
    }
  }
  return k;
}

// K^+ of a manifold's four points through the space their rows span. They share the normal n, so
// a point's angular parts differ from the mean point's only by where it lies in the contact plane
// (d_i = x_i - mean, alpha_i = d_i.t0, beta_i = d_i.t1; t0 x n = -t1, t1 x n = t0):
//   r_i x n = r_mean x n - alpha_i t1 + beta_i t0   (for a and for b)
// so K = A D A^T with A_i = [1, alpha_i, beta_i] and D the 3x3 coupled mass of the mean point's
// row and the two turns, rank 3 at most. With A^T A = L L^T, Q = A L^-T has orthonormal columns
// and K = Q S Q^T, S = L^T D L: K's eigenvalues other than its structural zero are S's, and
// K^+ = Q S^+ Q^T with the same floor (point_block_inverse.h). False when the points are nearly on
// a line (A^T A near singular): the caller inverts K itself.
bool pseudoInverseInPlane(const ContactConstraint& c, const SolverBody& a, const SolverBody& b,
                          SmallBlock& inverse) {
  const Vec3& n = c.normal;
  const Vec3& t0 = c.tangent[0];
  const Vec3& t1 = c.tangent[1];
  Vec3 mean_a = Vec3::Zero();
  Vec3 mean_b = Vec3::Zero();
  for (int k = 0; k < 4; ++k) {
    mean_a += c.points[k].r_a;
    mean_b += c.points[k].r_b;
  }
  mean_a *= 0.25;
  mean_b *= 0.25;
  Eigen::Matrix<Real, 4, 3> span;
  for (int k = 0; k < 4; ++k) {
    const Vec3 d = c.points[k].r_a - mean_a;
    span.row(k) << 1.0, d.dot(t0), d.dot(t1);
  }
  const Vec3 turn_a[3] = {mean_a.cross(n), -t1, t0};
  const Vec3 turn_b[3] = {mean_b.cross(n), -t1, t0};
  Mat3 d;
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) {
      d(i, j) = turn_a[i].dot(a.inverse_inertia * turn_a[j]) +
                turn_b[i].dot(b.inverse_inertia * turn_b[j]);
    }
  }
  d(0, 0) += c.inverse_mass_a + c.inverse_mass_b;
  const Mat3 gram = span.transpose() * span;
  const Eigen::LLT<Mat3> llt(gram);
  const Mat3 l = llt.matrixL();
  if (llt.info() != Eigen::Success || l.diagonal().minCoeff() <= 1e-6 * l.diagonal().maxCoeff()) {
    return false;
  }
  const Mat3 l_inverse = l.triangularView<Eigen::Lower>().solve(Mat3::Identity());
  const Eigen::Matrix<Real, 4, 3> q = span * l_inverse.transpose();
  inverse = q * pseudoInverse(Mat3(l.transpose() * d * l)) * q.transpose();
  return true;
}

// Rows of contact c along its normal, solved at once: the points in index[0..count), each with
// its closing speed (normal velocity plus bias) from closing(k) and its accumulated impulse in
// totals[k]; j = -K^-1 closing (the precomputed block when every point takes part), applied by
// apply(index, count, j) when every total stays >= 0; else a point whose total would pull leaves
// and the rest are solved again (one that has lifted off, lifted(k), giving back all it carried
// first). False when the set ran down to one point (the caller goes point by point).
template <typename Closing, typename Lifted, typename Apply>
bool solveTogether(const ContactConstraint& c, const Sides& s, int* index, int count, Real* totals,
                   Closing&& closing, Lifted&& lifted, Apply&& apply) {
  for (int attempt = 0; attempt < Manifold::kMaxPoints && count > 1; ++attempt) {
    PointVector shared;
    if (count == c.count) {
      PointVector speed = PointVector::Zero();
      for (int i = 0; i < count; ++i) speed[i] = closing(index[i]);
      shared = c.normal_block * speed;
    } else {
      SmallVector speed(count);
      for (int i = 0; i < count; ++i) speed[i] = closing(index[i]);
      shared.head(count) = pseudoInverse(coupledMass(c, s.a, s.b, index, count)) * speed;
    }
    int kept = 0;
    for (int i = 0; i < count; ++i) kept += totals[index[i]] - shared[i] >= 0.0 ? 1 : 0;
    if (kept == count) {
      Real impulses[Manifold::kMaxPoints];
      for (int i = 0; i < count; ++i) {
        totals[index[i]] -= shared[i];
        impulses[i] = -shared[i];
      }
      apply(index, count, impulses);
      return true;
    }
    kept = 0;
    for (int i = 0; i < count; ++i) {
      const int k = index[i];
      if (totals[k] - shared[i] >= 0.0) {
        index[kept++] = k;
        continue;
      }
      // Lifted off, it gives back all it carried: else its warm start goes on pushing a point
      // in the air, and a tall box left on one edge rocks higher at every landing.
      if (totals[k] != 0.0 && lifted(k)) {
        const Real back = -totals[k];
        totals[k] = 0.0;
        apply(&k, 1, &back);
      }
    }
    count = kept;
  }
  return false;
}

// For the impacts and the push-out, whose totals start from zero each time: nothing to give back.
bool neverLifted(int /*point*/) { return false; }

// The impact of contact c: its closing points at once, so that each separates at e |v_n| (the
// speed it closed at), through their coupled mass (those that would pull left out).
void resolveImpact(ContactConstraint& c, Sides& s, const Real h) {
  int index[Manifold::kMaxPoints];
  Real target[Manifold::kMaxPoints];
  Real totals[Manifold::kMaxPoints] = {0.0, 0.0, 0.0, 0.0};
  int count = 0;
  Real touch = h;  // when within the substep the first point touches
  for (int k = 0; k < c.count; ++k) {
    const ContactConstraintPoint& cp = c.points[k];
    const Real vn = normalVelocity(c, cp, s);
    const Real gap = separationNow(c, cp, s);
    if (!closes(vn, gap, h)) continue;
    touch = std::min(touch, std::max(gap, 0.0) / -vn);
    index[count++] = k;
  }
  // The velocities are the substep's end (its kick applied); at the touch the bodies had
  // v - a (h - touch), and that is the speed a point closed at: each separates at e times it.
  const Real closing_acceleration = c.normal.dot(s.b.acceleration - s.a.acceleration);
  for (int i = 0; i < count; ++i) {
    const int k = index[i];
    const Real at_touch = normalVelocity(c, c.points[k], s) - closing_acceleration * (h - touch);
    target[k] = -c.restitution * at_touch + closing_acceleration * (h - touch);
  }
  const Vec3 v_a = s.a.v;
  const Vec3 v_b = s.b.v;
  const auto closing = [&](const int k) { return normalVelocity(c, c.points[k], s) - target[k]; };
  const auto push = [&](const int* points, const int n, const Real* j) {
    pushNormals<false>(c, s, points, n, j);
  };
  if (!solveTogether(c, s, index, count, totals, closing, neverLifted, push) && count == 1) {
    const int k = index[0];
    pushNormal<false>(c, s, k, std::max(-c.points[k].normal_mass * closing(k), 0.0));
  }
  // The bodies fly on to the touch before turning back. Over the substep, from v0 = v - a h,
  // they move v0 touch + a touch^2 / 2 + (v0 + a touch + dv)(h - touch) + a (h - touch)^2 / 2
  // = h (v + dv) - a h^2 / 2 - touch dv: the positions stage (h (v + dv)) is short by the rest.
  // The flight's -a h^2 / 2 is the body's once in the substep, however many impacts it takes
  // (a plate struck by 400 grains at once rose 400 times as much, 2.3 cm).
  const auto move = [&](SolverBody& body, const Vec3& before) {
    const Vec3 flight = body.flew ? Vec3::Zero() : Vec3(-0.5 * h * h * body.acceleration);
    body.flew = true;
    body.dp += flight - touch * (body.v - before);
  };
  if (c.a != kNoBody) move(s.a, v_a);
  if (c.b != kNoBody) move(s.b, v_b);
  // An impact acts once: its impulse is no substep's to warm start again, and the contact holds
  // nothing more this substep (nor friction, bounded by a normal impulse of 0).
  for (int k = 0; k < c.count; ++k) c.points[k].normal_impulse = 0.0;
  c.friction_impulse[0] = 0.0;
  c.friction_impulse[1] = 0.0;
  c.twist_impulse = 0.0;
  c.impact = true;
  c.impact_now = true;
}

// The normal rows of c. The velocities are held rigidly: a touching point may not close (the
// velocity rows carry the load from substep to substep, warm started, with no spring to sink
// under it), and a gap may close within the substep, no faster. Overlap beyond the slop is
// pushed out by pseudo-velocities (split impulses): they move the positions over the substep and
// are then dropped, so pushing out adds no momentum and cannot set a column of boxes bouncing,
// which a bias in the real velocities did (only one pass per substep takes it back out).
// Relaxing, the pseudo-velocities rest and a point with a gap may give back what it pushed with,
// never push more: that would slow a body in the air about to land, and its bounce with it.
void solveNormals(ContactConstraint& c, Sides& s, const ContactPass& pass, const Real inverse_h) {
  Real separation[Manifold::kMaxPoints];
  Real totals[Manifold::kMaxPoints];
  int index[Manifold::kMaxPoints];
  int count = 0;
  // A point further apart than the slop has lifted off (within the slop it touches: a face
  // landing flat must not split into points either side of zero).
  const auto lifted = [&](const int k) { return separation[k] > pass.slop; };
  for (int k = 0; k < c.count; ++k) {
    separation[k] = c.points[k].current;
    totals[k] = c.points[k].normal_impulse;
    // Relaxing, a lifted point counts as a gap.
    if (pass.use_bias || !lifted(k)) index[count++] = k;
  }
  const auto closing = [&](const int k) {
    return normalVelocity(c, c.points[k], s) + std::max(separation[k], 0.0) * inverse_h;
  };
  const auto push = [&](const int* points, const int n, const Real* j) {
    for (int i = 0; i < n; ++i) c.points[points[i]].normal_impulse += j[i];
    pushNormals<false>(c, s, points, n, j);
  };
  if (!solveTogether(c, s, index, count, totals, closing, lifted, push)) {
    for (int k = 0; k < c.count; ++k) {
      ContactConstraintPoint& cp = c.points[k];
      Real total = std::max(cp.normal_impulse - cp.normal_mass * closing(k), 0.0);
      if (!pass.use_bias && lifted(k)) total = std::min(total, cp.normal_impulse);
      const Real j = total - cp.normal_impulse;
      cp.normal_impulse = total;
      pushNormal<false>(c, s, k, j);
    }
  }
  if (!pass.use_bias) return;
  // Split impulses: an overlap beyond half the slop is pushed back to half of it, at the soft
  // bias rate, at most max_push_speed (so a resting overlap stays below the slop).
  count = 0;
  Real pseudo_totals[Manifold::kMaxPoints] = {0.0, 0.0, 0.0, 0.0};
  Real bias[Manifold::kMaxPoints];
  for (int k = 0; k < c.count; ++k) {
    const Real beyond = separation[k] + 0.5 * pass.slop;
    if (beyond >= 0.0) continue;
    bias[k] = std::max(c.softness.bias_rate * beyond, -pass.max_push_speed);
    index[count++] = k;
  }
  const auto pseudo_closing = [&](const int k) {
    return normalPseudoVelocity(c, c.points[k], s) + bias[k];
  };
  const auto pseudo_push = [&](const int* points, const int n, const Real* j) {
    pushNormals<true>(c, s, points, n, j);
  };
  if (count > 0 &&
      !solveTogether(c, s, index, count, pseudo_totals, pseudo_closing, neverLifted, pseudo_push)) {
    for (int i = 0; i < count; ++i) {
      const int k = index[i];
      const Real total =
          std::max(pseudo_totals[k] - c.points[k].normal_mass * pseudo_closing(k), 0.0);
      pushNormal<true>(c, s, k, total - pseudo_totals[k]);
      pseudo_totals[k] = total;
    }
  }
}

// Coulomb's cone on the manifold: the tangent impulse at the centre (both directions together) at
// most mu sum j_k, the twist about the normal at most mu sum j_k arm_k.
void solveFriction(ContactConstraint& c, Sides& s) {
  Real load = 0.0;
  Real twist_load = 0.0;
  for (int k = 0; k < c.count; ++k) {
    load += c.points[k].normal_impulse;
    twist_load += c.points[k].normal_impulse * c.points[k].arm;
  }
  // A contact that carries no load and holds no friction stays so: the cone is a point.
  if (load == 0.0 && c.friction_impulse[0] == 0.0 && c.friction_impulse[1] == 0.0 &&
      c.twist_impulse == 0.0) {
    return;
  }
  // The two sides' velocities in locals (the sides are two references the compiler cannot tell
  // apart, so every write through one would reload the other).
  Vec3 v_a = s.a.v;
  Vec3 w_a = s.a.w;
  Vec3 v_b = s.b.v;
  Vec3 w_b = s.b.w;
  const Mat3& inertia_a = s.a.inverse_inertia;
  const Mat3& inertia_b = s.b.inverse_inertia;
  // lambda' = lambda - K_t^-1 (t_i.dv at the centre), clamped to the disc of radius mu sum j_k.
  const Vec3 dv = (v_b + w_b.cross(c.center_b)) - (v_a + w_a.cross(c.center_a));
  const Eigen::Matrix<Real, 2, 1> old(c.friction_impulse[0], c.friction_impulse[1]);
  Eigen::Matrix<Real, 2, 1> total =
      old -
      c.friction_block * Eigen::Matrix<Real, 2, 1>(dv.dot(c.tangent[0]), dv.dot(c.tangent[1]));
  const Real limit = c.friction * load;
  const Real length_squared = total.squaredNorm();
  if (length_squared > limit * limit) total *= limit / std::sqrt(length_squared);
  c.friction_impulse[0] = total[0];
  c.friction_impulse[1] = total[1];
  // The impulse p at the centre: -p on a, +p on b (SolverBody::applyImpulse).
  const Vec3 p = (total[0] - old[0]) * c.tangent[0] + (total[1] - old[1]) * c.tangent[1];
  v_a -= c.inverse_mass_a * p;
  w_a -= inertia_a * c.center_a.cross(p);
  v_b += c.inverse_mass_b * p;
  w_b += inertia_b * c.center_b.cross(p);
  if (c.twist_mass > 0.0) {
    // tau' = tau - n.(w_b - w_a) / (n.I_a^-1 n + n.I_b^-1 n), within +-mu sum j_k arm_k.
    const Real twist_limit = c.friction * twist_load;
    const Real twist = std::clamp(c.twist_impulse - c.twist_mass * c.normal.dot(w_b - w_a),
                                  -twist_limit, twist_limit);
    const Vec3 turn = (twist - c.twist_impulse) * c.normal;
    c.twist_impulse = twist;
    w_a -= inertia_a * turn;
    w_b += inertia_b * turn;
  }
  s.a.v = v_a;
  s.a.w = w_a;
  s.b.v = v_b;
  s.b.w = w_b;
}

}  // namespace

void tangentBasis(const Vec3& n, Vec3& t0, Vec3& t1) {
  // Perpendicular to n from its two largest components (never near zero: |n| = 1).
  if (std::abs(n.x()) >= 0.57735026918962576) {
    t0 = Vec3(n.y(), -n.x(), 0.0).normalized();
  } else {
    t0 = Vec3(0.0, n.z(), -n.y()).normalized();
  }
  t1 = n.cross(t0);
}

namespace {

// The terms of a row that depend on its sides' masses, from its geometry (normal, tangents,
// anchors, patch centre, the sides' indices): the same geometry serves either side held still.
void prepareMasses(const std::vector<SolverBody>& bodies, BodyContact::InvertedMass& inverted,
                   ContactConstraint& c) {
  static const SolverBody still;
  const SolverBody& a = c.a == kNoBody ? still : bodies[static_cast<std::size_t>(c.a)];
  const SolverBody& b = c.b == kNoBody ? still : bodies[static_cast<std::size_t>(c.b)];
  c.inverse_mass_a = a.inverse_mass;
  c.inverse_mass_b = b.inverse_mass;
  for (int k = 0; k < c.count; ++k) {
    ContactConstraintPoint& cp = c.points[k];
    cp.normal_mass = effectiveMass(a, cp.r_a, b, cp.r_b, c.normal);
  }
  // K_t,ij = (m_a^-1 + m_b^-1) delta_ij + (c_a x t_i).I_a^-1 (c_a x t_j) + (c_b x t_i).I_b^-1 (...)
  Eigen::Matrix<Real, 3, 2> turn_a;
  Eigen::Matrix<Real, 3, 2> turn_b;
  for (int i = 0; i < 2; ++i) {
    turn_a.col(i) = c.center_a.cross(c.tangent[i]);
    turn_b.col(i) = c.center_b.cross(c.tangent[i]);
  }
  const Eigen::Matrix<Real, 2, 2> tangent_mass =
      (a.inverse_mass + b.inverse_mass) * Eigen::Matrix<Real, 2, 2>::Identity() +
      turn_a.transpose() * a.inverse_inertia * turn_a +
      turn_b.transpose() * b.inverse_inertia * turn_b;
  const Real det = tangent_mass.determinant();
  if (det > 0.0) {
    c.friction_block << tangent_mass(1, 1), -tangent_mass(0, 1), -tangent_mass(1, 0),
        tangent_mass(0, 0);
    c.friction_block /= det;
  } else {
    c.friction_block.setZero();
  }
  const Real twist = c.normal.dot((a.inverse_inertia + b.inverse_inertia) * c.normal);
  c.twist_mass = twist > 0.0 ? 1.0 / twist : 0.0;
  if (c.count > 1) {
    const int all[Manifold::kMaxPoints] = {0, 1, 2, 3};
    const auto mass = coupledMass(c, a, b, all, c.count);
    auto kept_mass = inverted.mass.topLeftCorner(c.count, c.count);
    // Only a K that has not changed (to rounding) keeps its inverse: the pseudo-inverse of a K
    // near a rank change (two points nearly one) is far from that of a K close to it, and a
    // kept one a thousandth off threw boxes of a random pile out at 100 m/s.
    constexpr Real kRefresh = 1e-12;
    if ((mass - kept_mass).cwiseAbs().maxCoeff() > kRefresh * mass.cwiseAbs().maxCoeff()) {
      kept_mass = mass;
      SmallBlock inverse;
      if (c.count < 4 || !pseudoInverseInPlane(c, a, b, inverse)) inverse = pseudoInverse(mass);
      inverted.inverse.topLeftCorner(c.count, c.count) = inverse;
    }
    c.normal_block.topLeftCorner(c.count, c.count) =
        inverted.inverse.topLeftCorner(c.count, c.count);
  }
}

}  // namespace

void prepareContact(const BodyContact& contact, const std::uint32_t index,
                    const ContactSides& sides, const std::vector<SolverBody>& bodies,
                    const Softness& softness, const Real min_twist_lever,
                    BodyContact::InvertedMass& inverted, ContactConstraint& c) {
  c.a = sides.a;
  c.b = sides.b;
  c.rounding_a = sides.rounding_a;
  c.rounding_b = sides.rounding_b;
  c.contact = index;
  c.normal = contact.manifold.normal;
  tangentBasis(c.normal, c.tangent[0], c.tangent[1]);
  c.friction = contact.friction;
  c.restitution = contact.restitution;
  c.softness = softness;
  c.count = contact.manifold.count;
  const ContactPatch patch = contactPatch(contact.manifold);
  // Each side's anchor of a point: a swept contact's are its sides' touching points
  // (Manifold::slide), which the friction turns about.
  const Vec3& slide = contact.manifold.slide;
  c.swept = !slide.isZero(0.0);
  const auto anchors = [&](const Vec3& point, Vec3& r_a, Vec3& r_b) {
    if (c.swept) {
      r_a = point - 0.5 * slide - sides.center_a;
      r_b = point + 0.5 * slide - sides.center_b;
    } else {
      r_a = point - sides.center_a;
      r_b = point - sides.center_b;
    }
  };
  for (int k = 0; k < c.count; ++k) {
    const ManifoldPoint& mp = contact.manifold.points[k];
    ContactConstraintPoint& cp = c.points[k];
    anchors(mp.point, cp.r_a, cp.r_b);
    cp.separation = mp.separation;
    cp.normal_impulse = contact.normal_impulses[k];
    cp.arm = std::max(patch.offsets[k].norm(), min_twist_lever);
  }
  anchors(patch.center, c.center_a, c.center_b);
  c.friction_impulse[0] = contact.friction_impulse.dot(c.tangent[0]);
  c.friction_impulse[1] = contact.friction_impulse.dot(c.tangent[1]);
  c.twist_impulse = contact.twist_impulse;
  prepareMasses(bodies, inverted, c);
}

void prepareHeldStill(const ContactConstraint& c, const bool a_still,
                      const std::vector<SolverBody>& bodies, BodyContact::InvertedMass& inverted,
                      ContactConstraint& held) {
  held = c;
  (a_still ? held.a : held.b) = kNoBody;
  prepareMasses(bodies, inverted, held);
}

void takeSeparations(std::vector<ContactConstraint>& constraints, std::vector<SolverBody>& bodies) {
  for (ContactConstraint& c : constraints) {
    takeSeparations(c, Sides(c, bodies));
  }
}

namespace {

// Whether the contact's impact was resolved now (which moves its bodies).
bool warmStart(ContactConstraint& c, Sides& s, const ContactPass& pass) {
  c.impact_now = false;
  // Impacts first, at the velocities the bodies arrive with (a warm start would change them).
  if (!c.impact && c.restitution > 0.0) {
    for (int k = 0; k < c.count; ++k) {
      const ContactConstraintPoint& cp = c.points[k];
      const Real vn = normalVelocity(c, cp, s);
      if (vn < -pass.restitution_threshold && closes(vn, separationNow(c, cp, s), pass.h)) {
        resolveImpact(c, s, pass.h);
        return true;
      }
    }
  }
  // The points' normal impulses P_k, the friction F at the centre and the twist tau together:
  // -(sum P + F) on a's momentum, -(sum r_a x P + c_a x F + tau n) on its angular momentum, +
  // on b.
  const Vec3 friction = c.friction_impulse[0] * c.tangent[0] + c.friction_impulse[1] * c.tangent[1];
  const Vec3 twist = c.twist_impulse * c.normal;
  Vec3 linear = friction;
  Vec3 angular_a = c.center_a.cross(friction) + twist;
  Vec3 angular_b = c.center_b.cross(friction) + twist;
  for (int k = 0; k < c.count; ++k) {
    const ContactConstraintPoint& cp = c.points[k];
    const Vec3 p = cp.normal_impulse * c.normal;
    linear += p;
    angular_a += cp.r_a.cross(p);
    angular_b += cp.r_b.cross(p);
  }
  s.a.v -= c.inverse_mass_a * linear;
  s.a.w -= s.a.inverse_inertia * angular_a;
  s.b.v += c.inverse_mass_b * linear;
  s.b.w += s.b.inverse_inertia * angular_b;
  return false;
}

}  // namespace

void warmStartContacts(std::vector<ContactConstraint>& constraints, std::vector<SolverBody>& bodies,
                       const ContactPass& pass) {
  bool moved = false;
  for (ContactConstraint& c : constraints) {
    Sides s(c, bodies);
    moved |= warmStart(c, s, pass);
    takeSeparations(c, s);
  }
  // An impact moves its bodies: the contacts taken before it on the same bodies are behind.
  if (moved) takeSeparations(constraints, bodies);
}

namespace {

// A support is level when its normal is within 10 degrees of gravity's line: the lever rule
// balances the moments of vertical loads, and a support tilted by theta also pushes sideways by
// tan(theta) of its load (0.18 at 10 degrees), a moment the rule leaves out.
constexpr Real kLevelSupport = 0.98480775301220802;  // cos(10 degrees)

// The point of c where it touches `side`, from side's centre: the mean of its points' anchors.
Vec3 supportCentre(const ContactConstraint& c, const std::int32_t side) {
  Vec3 sum = Vec3::Zero();
  for (int p = 0; p < c.count; ++p) sum += c.a == side ? c.points[p].r_a : c.points[p].r_b;
  return sum / static_cast<Real>(c.count);
}

// The lever rule for a load F acting at `at` (from body's centre) on two supports c0 and c1:
// each takes the share whose moment about that point cancels the other's,
//   s_1 = F t, s_0 = F (1 - t), t = (at - c_0).u / |c_1 - c_0|,
// c_i the supports' centres, u the unit vector from c_0 to c_1 across gravity's line (t within
// [0, 1]: a load beyond a support rests on it alone). Returns t; none when the two centres are
// one above the other. An even split leaves the body a moment to turn by: Box2D's 210-box
// pyramid, guessed so, rocked for good (0.2 to 1.4 mJ), and with no guess at all its passes
// bring it to rest.
std::optional<Real> leverFraction(const ContactConstraint& c0, const ContactConstraint& c1,
                                  const std::int32_t body, const Vec3& at, const Vec3& up) {
  const Vec3 centre = supportCentre(c0, body);
  Vec3 across = supportCentre(c1, body) - centre;
  across -= across.dot(up) * up;
  const Real span = across.squaredNorm();
  if (!(span > 0.0)) return std::nullopt;
  return std::clamp((at - centre).dot(across) / span, 0.0, 1.0);
}

}  // namespace

void guessRestingLoads(std::vector<ContactConstraint>& constraints,
                       const std::vector<SolverBody>& bodies, const std::vector<Real>& heights,
                       const Vec3& gravity, const Real h, const Real dt,
                       RestingLoadBuffers& buffers) {
  const Real g = gravity.norm();
  if (g == 0.0 || constraints.empty()) return;
  const Vec3 up = -gravity / g;
  const Real resting_speed = 2.0 * g * h;
  const Real resting_gap = resting_speed * dt + 0.5 * g * dt * dt;
  // The support a constraint gives: the body resting on it (kNoBody: none) and the side below.
  const auto support = [&](const std::size_t i) {
    const ContactConstraint& c = constraints[i];
    const Real vertical = c.normal.dot(up);
    if (std::abs(vertical) < std::sqrt(0.5)) return std::pair{kNoBody, kNoBody};
    // n points from a to b: down when a rests on b.
    return vertical < 0.0 ? std::pair{c.a, c.b} : std::pair{c.b, c.a};
  };
  // Per body the contacts it rests on, by a counting sort of the constraints (stable: each body's
  // in constraint order).
  std::vector<std::uint32_t>& first = buffers.first;
  first.assign(bodies.size() + 1, 0);
  for (std::size_t i = 0; i < constraints.size(); ++i) {
    const std::int32_t upper = support(i).first;
    if (upper != kNoBody) ++first[static_cast<std::size_t>(upper) + 1];
  }
  for (std::size_t k = 0; k < bodies.size(); ++k) first[k + 1] += first[k];
  std::vector<RestingLoadBuffers::Support>& supports = buffers.supports;
  supports.resize(first.back());
  for (std::size_t i = 0; i < constraints.size(); ++i) {
    const auto [upper, lower] = support(i);
    if (upper == kNoBody) continue;
    supports[first[static_cast<std::size_t>(upper)]++] =
        RestingLoadBuffers::Support{static_cast<std::uint32_t>(i), lower};
  }
  // Each first[k] now ends body k's supports, where body k + 1's begin: shift them back.
  for (std::size_t k = bodies.size(); k > 0; --k) first[k] = first[k - 1];
  first[0] = 0;
  std::vector<std::int32_t>& order = buffers.order;
  order.clear();
  for (std::size_t k = 0; k < bodies.size(); ++k) {
    if (first[k + 1] > first[k] && bodies[k].inverse_mass > 0.0) {
      order.push_back(static_cast<std::int32_t>(k));
    }
  }
  std::stable_sort(order.begin(), order.end(), [&](const std::int32_t x, const std::int32_t y) {
    return heights[static_cast<std::size_t>(x)] > heights[static_cast<std::size_t>(y)];
  });
  std::vector<Real>& load = buffers.load;
  std::vector<Vec3>& moment = buffers.moment;
  load.assign(bodies.size(), 0.0);
  moment.assign(bodies.size(), Vec3::Zero());
  for (std::size_t k = 0; k < bodies.size(); ++k) {
    if (bodies[k].inverse_mass > 0.0) load[k] = g * h / bodies[k].inverse_mass;
  }
  const SolverBody still;
  // Whether c starts from a guess: it carries nothing yet, and it is resting.
  const auto guessed = [&](const ContactConstraint& c) {
    if (c.count == 0) return false;
    for (int p = 0; p < c.count; ++p) {
      if (c.points[p].normal_impulse != 0.0) return false;
    }
    const SolverBody& a = c.a == kNoBody ? still : bodies[static_cast<std::size_t>(c.a)];
    const SolverBody& b = c.b == kNoBody ? still : bodies[static_cast<std::size_t>(c.b)];
    Real closing = 0.0;
    Real gap = std::numeric_limits<Real>::infinity();
    for (int p = 0; p < c.count; ++p) {
      const ContactConstraintPoint& cp = c.points[p];
      closing =
          std::max(closing, std::abs(c.normal.dot(b.velocityAt(cp.r_b) - a.velocityAt(cp.r_a))));
      gap = std::min(gap, cp.separation);
    }
    return closing <= resting_speed && gap <= resting_gap;
  };
  // Whether c is a support the lever rule shares a load over: level, and guessed.
  const auto level = [&](const ContactConstraint& c) {
    return std::abs(c.normal.dot(up)) >= kLevelSupport && guessed(c);
  };
  for (const std::int32_t k : order) {
    const auto begin = first[static_cast<std::size_t>(k)];
    const auto end = first[static_cast<std::size_t>(k) + 1];
    const Real total = load[static_cast<std::size_t>(k)];
    const Real even = total / static_cast<Real>(end - begin);
    std::optional<Real> lever;
    if (end - begin == 2) {
      const ContactConstraint& c0 = constraints[supports[begin].constraint];
      const ContactConstraint& c1 = constraints[supports[begin + 1].constraint];
      if (level(c0) && level(c1)) {
        lever = leverFraction(c0, c1, k, moment[static_cast<std::size_t>(k)] / total, up);
      }
    }
    for (std::uint32_t j = begin; j < end; ++j) {
      const RestingLoadBuffers::Support& support = supports[j];
      ContactConstraint& c = constraints[support.constraint];
      const Real share = !lever ? even : j == begin ? total * (1.0 - *lever) : total * *lever;
      const bool guess = guessed(c);
      if (guess) {
        for (int p = 0; p < c.count; ++p) {
          c.points[p].normal_impulse = share / static_cast<Real>(c.count);
        }
      }
      const Real carried = guess ? share : c.normalLoad();
      if (support.below == kNoBody) continue;
      const auto below = static_cast<std::size_t>(support.below);
      load[below] += carried;
      for (int p = 0; p < c.count; ++p) {
        const ContactConstraintPoint& cp = c.points[p];
        moment[below] += cp.normal_impulse * (c.a == support.below ? cp.r_a : cp.r_b);
      }
    }
  }
}

void solveContacts(std::vector<ContactConstraint>& constraints, std::vector<SolverBody>& bodies,
                   const ContactPass& pass) {
  const Real inverse_h = 1.0 / pass.h;
  const std::size_t n = constraints.size();
  for (std::size_t i = 0; i < n; ++i) {
    ContactConstraint& c = constraints[pass.top_down ? n - 1 - i : i];
    Sides s(c, bodies);
    if (!c.impact_now) solveNormals(c, s, pass, inverse_h);
    if (c.friction > 0.0) solveFriction(c, s);
  }
}

namespace {

// The shock row's contact, with its lower side in s; its friction too unless told not.
void solveShock(ContactConstraint& upper, Sides& s, const ContactPass& pass, const Real inverse_h,
                const bool with_friction) {
  takeSeparations(upper, s);
  if (!upper.impact_now) solveNormals(upper, s, pass, inverse_h);
  if (with_friction && upper.friction > 0.0) solveFriction(upper, s);
}

}  // namespace

void propagateShock(std::vector<ShockRow>& rows, const std::vector<ContactConstraint>& constraints,
                    std::vector<SolverBody>& bodies, const ContactPass& pass) {
  const Real inverse_h = 1.0 / pass.h;
  for (ShockRow& row : rows) {
    const ContactConstraint& c = constraints[row.constraint];
    ContactConstraint& upper = row.upper_alone;
    upper.impact_now = c.impact_now;
    for (int k = 0; k < c.count; ++k) upper.points[k].normal_impulse = c.points[k].normal_impulse;
    upper.friction_impulse[0] = c.friction_impulse[0];
    upper.friction_impulse[1] = c.friction_impulse[1];
    upper.twist_impulse = c.twist_impulse;
    if (row.carrier == kNoBody) {
      if (!row.base_on_still) continue;
      // Held in the ground's frame, the pile is braked by its friction: only while its base is
      // slow and gripped by static friction, so coming to rest too. A base that slides, pushed
      // along or gliding on frictionless ground, carries its pile on at any speed.
      const bool slides =
          !row.base_grips || bodies[static_cast<std::size_t>(row.base)].v.squaredNorm() >
                                 pass.still_speed * pass.still_speed;
      Sides s(upper, bodies);
      solveShock(upper, s, pass, inverse_h, !slides);
      continue;
    }
    // The lower side moves with the carrier (taking no impulse) where the lower body is; its
    // displacement since the step began is its own (the rows' geometry).
    const bool lower_is_a = upper.a == kNoBody;
    const SolverBody& carrier = bodies[static_cast<std::size_t>(row.carrier)];
    SolverBody held = bodies[static_cast<std::size_t>(lower_is_a ? c.a : c.b)];
    held.v = carrier.velocityAt(row.lower_from_carrier);
    held.w = carrier.w;
    held.pv = carrier.pseudoVelocityAt(row.lower_from_carrier);
    held.pw = carrier.pw;
    held.inverse_mass = 0.0;
    held.inverse_inertia = Mat3::Zero();
    SolverBody& moving = bodies[static_cast<std::size_t>(lower_is_a ? c.b : c.a)];
    Sides s(lower_is_a ? held : moving, lower_is_a ? moving : held);
    solveShock(upper, s, pass, inverse_h, true);
  }
}

void storeImpulses(const std::vector<ContactConstraint>& constraints,
                   std::vector<BodyContact>& contacts) {
  for (const ContactConstraint& c : constraints) {
    BodyContact& contact = contacts[c.contact];
    for (int k = 0; k < c.count; ++k) contact.normal_impulses[k] = c.points[k].normal_impulse;
    contact.friction_impulse =
        c.friction_impulse[0] * c.tangent[0] + c.friction_impulse[1] * c.tangent[1];
    contact.twist_impulse = c.twist_impulse;
  }
}

}  // namespace engine
}  // namespace mass_aggregate_sim
