#pragma once

#include <array>
#include <cmath>
#include <cstdint>
#include <utility>
#include <vector>

#include "engine/core/state_hash.h"
#include "engine/solver/constraint_row.h"
#include "engine/solver/contact.h"
#include "engine/solver/contact_response.h"
#include "engine/solver/isolated_contact_batch.h"
#include "engine/solver/link_blocks.h"
#include "mass_aggregate_sim/engine/collision/collision_settings.h"
#include "mass_aggregate_sim/engine/core/types.h"

namespace mass_aggregate_sim {
namespace engine {

// Which contacts resolve() takes as isolated (see ContactResolver).
enum class IsolatedContacts : std::uint8_t {
  kNone,  // none: every contact is a row (cheaper where few are isolated, as in a pile)
  kFind,  // those whose particles are in no other contact, found by counting each particle's
  kAll,   // every contact: the caller knows no particle is in two (and there are no links)
};

// Iterative impulse resolver. Velocities first, then positions, each by Gauss-Seidel passes over
// the contacts in order until a pass changes less than the tolerance or max_iterations is reached:
// O(passes x contacts), no search for the worst contact.
//
// Velocity pass, per contact: v_sep = (v_a - v_b).n; a closing contact (v_sep < 0) gets the
// impulse j = (v_target - v_sep) / (w_a + w_b), shared by inverse mass w. The target is
// -e v_impact, where v_impact is v_sep less what the forces (the substep's accelerations) built up
// along n while the particles were already in contact during the substep. A contact whose closing
// speed, less all the forces built over the substep, is below two more substeps of it is resting
// and aims at touching (v_target = 0 when overlapping), which keeps resting contacts still without
// bouncing. Friction then removes tangential velocity, bounded by mu j. Rods are bilateral
// (target 0, either sign); cables pull only and reflect with their restitution. Every constraint
// keeps its total normal and friction impulse and starts the next substep from it (warm
// starting), so a pile or a loaded structure does not rebuild its support from zero every substep.
//
// Then resting contacts move their particles with their impulses (see resolve()).
//
// Position pass, per contact: overlap beyond the slop is removed down to half the slop, moving a
// and b by w_a/(w_a+w_b) and w_b/(w_a+w_b) of it (dp_a = m_b/(m_a+m_b) d n). Links are recomputed
// from the current positions and corrected to their exact length. A contact between two particles
// (given their radii) sheds at most half the smaller radius of the overlap it was made with in one
// substep (kPairCorrectionShare): these moves change no velocity, so pushing a deep overlap apart
// at once lifts a pile against gravity for free, and in a pile struck by fast spheres that energy
// kept it seething (a drop of 8,000 spheres never settled). Deeper overlaps take a few substeps.
// Colliders are solid: theirs is removed at once. Position-only contacts
// (Contact::position_only) take part in this pass only.
//
// Isolated contacts (a contact, not a link, whose particles are in no other constraint of the
// substep: a ball on the ground) take all of these steps at once in the set-up pass, with the same
// formulas: a lone row's Gauss-Seidel converges in one pass, and nothing else moves its particles.
// Only the others go through the passes above.
class ContactResolver {
 public:
  // acceleration: each particle's acceleration over the last substep of length h.
  // position_weight: beta of the integrator's position update x' = x + v h + beta a h^2 (1 for
  // semi-implicit and implicit Euler, 1/2 for the Verlets and RK4, 0 for explicit Euler). After the
  // velocity phase each particle moves by beta h w J for the impulses J of its resting contacts, as
  // if those impulses had been forces inside the step: a resting particle then ends where it
  // started instead of sinking by beta g h^2 for the position passes to push back up.
  // links: the geometry of link constraints, by Contact::link.
  // radius: each particle's, for the bound on a pair's position correction (none without it).
  // isolated: which contacts are solved whole in the set-up pass.
  // The velocity phase: set-up (isolated contacts solved whole), warm starts and the passes; then
  // resting contacts' particles follow their impulses, here, before the body solver changes the
  // same particles' velocities: it moves them for its own impulses.
  void solveVelocities(std::vector<Contact>& contacts, const std::vector<LinkGeometry>& links,
                       Vec3Map x, Vec3Map v, const ConstScalarMap& inverse_mass,
                       const Eigen::Ref<const Vec3Array>& acceleration, Real h,
                       const CollisionSettings& settings, Real position_weight, ContactStats& stats,
                       IsolatedContacts isolated = IsolatedContacts::kFind,
                       const Real* radius = nullptr);
  // The position phase after solveVelocities() or finishPartsVelocities() on the same contacts:
  // overlaps and link lengths are corrected; the impulses are kept for the next substep and the
  // stats finished.
  void correctPositions(const std::vector<Contact>& contacts, Vec3Map x, Vec3Map v,
                        const ConstScalarMap& inverse_mass, Real h,
                        const CollisionSettings& settings, ContactStats& stats);
  // Both phases at once.
  void resolve(std::vector<Contact>& contacts, const std::vector<LinkGeometry>& links, Vec3Map x,
               Vec3Map v, const ConstScalarMap& inverse_mass,
               const Eigen::Ref<const Vec3Array>& acceleration, Real h,
               const CollisionSettings& settings, Real position_weight, ContactStats& stats,
               IsolatedContacts isolated = IsolatedContacts::kFind, const Real* radius = nullptr) {
    solveVelocities(contacts, links, x, v, inverse_mass, acceleration, h, settings, position_weight,
                    stats, isolated, radius);
    correctPositions(contacts, x, v, inverse_mass, h, settings, stats);
  }
  // resolve() with the contacts handed over in parts as they are made, so each part is solved
  // while it is still in the cache: beginParts(), addPart() for each part, finishPartsVelocities(),
  // then correctPositions(). No links, and no particle in the contacts of two parts; a part may be
  // overwritten once added. The same results as resolve() on all the parts' contacts in order.
  void beginParts(Eigen::Index particle_count, Real h, Real position_weight);
  void addPart(std::vector<Contact>& part, Vec3Map x, Vec3Map v, const ConstScalarMap& inverse_mass,
               const Eigen::Ref<const Vec3Array>& acceleration, Real h, Real slop,
               IsolatedContacts isolated);
  // Collider contacts made and solved in vector lanes without a Contact (solveColliderGroups()):
  // `in` names the colliders and particles [in.begin, in.end), taken four at a time while they
  // qualify; the resolver fills in its warm starts and settings. Returns the first particle not
  // handled, whose contacts the caller adds with addPart().
  std::size_t addColliderGroups(ColliderGroupInputs in, bool any_friction, Vec3Map x, Vec3Map v,
                                const ConstScalarMap& inverse_mass,
                                const Eigen::Ref<const Vec3Array>& acceleration);
  // Contacts added since beginParts().
  std::size_t partsContactCount() const { return parts_size_; }
  // The velocity phase of the parts' rows, resting contacts' particles followed as in
  // solveVelocities(); correctPositions() with no contacts then finishes.
  void finishPartsVelocities(Vec3Map x, Vec3Map v, const ConstScalarMap& inverse_mass,
                             const Eigen::Ref<const Vec3Array>& acceleration,
                             const CollisionSettings& settings, ContactStats& stats);
  const std::vector<Contact>& noContacts() const { return no_contacts_; }
  // Dense indices of the particles whose position or velocity the last resolve() changed.
  const std::vector<std::uint32_t>& touched() const { return touched_; }
  // How many contacts of the last resolve() were isolated (solved in the set-up pass).
  std::size_t isolatedContacts() const { return isolated_count_; }
  // Forgets the impulses kept for warm starting (a removed particle's slot may be reused).
  void clearWarmStart() {
    warm_key_.clear();
    warm_normal_.clear();
    warm_friction_.clear();
    warm_by_key_.clear();
  }
  // The total normal impulse the contact named `key` ended the last substep with (the impulse
  // kept for warm starting; 0 when it did not act), and that substep's length (0 before any).
  Real lastImpulse(std::uint64_t key) const;
  // The normal impulse and the friction impulse on particle a the contact named `key` ended the
  // last substep with; false when it was not among that substep's contacts.
  bool lastImpulses(std::uint64_t key, Real& normal, Vec3& friction) const;
  Real lastSubstep() const { return last_substep_; }
  // Replaces the impulses kept for warm starting from contact `index` of the last substep, named
  // `key` (nothing when it is not that contact): a contact whose velocities another solver took
  // (Contact::body_solved) hands over what that solver ended with, so that this one starts from
  // it when the contact is its own again.
  void keepImpulses(std::size_t index, std::uint64_t key, Real normal, const Vec3& friction);
  // Adds the impulses kept for warm starting the next substep (part of the world's state).
  void addToHash(StateHasher& hasher) const {
    for (std::size_t k = 0; k < warm_key_.size(); ++k) {
      const bool friction = !warm_friction_.empty() && !warm_friction_[k].isZero(0.0);
      if (warm_normal_[k] == 0.0 && !friction) continue;
      hasher.add(warm_key_[k]);
      hasher.add(warm_normal_[k]);
      if (friction) hasher.add(warm_friction_[k]);
    }
  }

  // A particle moved outside the resolver after the velocity phase (by the body solver): the
  // positions stage measures its rows' depths after the move.
  void addMove(const std::uint32_t i, const Vec3& move) {
    if (static_cast<std::size_t>(i) >= touched_flag_.size()) return;
    displacement_.col(i) += move;
    touch(i);
  }

 private:
  using Row = ParticleRow;

  void touch(const std::uint32_t i) {
    if (touched_flag_[i]) return;
    touched_flag_[i] = 1;
    ++flagged_count_;
    touched_.push_back(i);
  }
  // Keeps v_i before its first warm start or impulse (targets and the follow are measured on it).
  void keepInitialVelocity(const std::uint32_t i, const Vec3Map& v) {
    if (rows_dense_ || initial_stamp_[i] == stamp_) return;  // dense: all copied
    initial_stamp_[i] = stamp_;
    initial_velocity_.col(i) = v.col(i);
  }
  // |a_i|: from the table when rows_dense_ (the same value: both are correctly rounded).
  Real accelerationNorm(const Eigen::Ref<const Vec3Array>& acceleration,
                        const std::uint32_t i) const {
    return rows_dense_ ? acceleration_norm_[i] : std::sqrt(acceleration.col(i).squaredNorm());
  }
  // Marks which particles take part in more than one contact (see isShared()), any_shared_.
  void countParticleUses(const std::vector<Contact>& contacts);
  bool isShared(const std::uint32_t i) const { return uses_[i] != (std::uint64_t{stamp_} << 1); }
  // Set-up, velocity solve, follow, position correction, warm start kept and stats of contact k,
  // whose particles are in no other constraint. `previous_impulse` / `previous_friction` (may be
  // null): its warm start.
  template <bool kWithB>
  void solveIsolated(std::size_t k, const Contact& c, Vec3Map& x, Vec3Map& v,
                     const ConstScalarMap& inverse_mass,
                     const Eigen::Ref<const Vec3Array>& acceleration, Real h, Real slop,
                     Real previous_impulse, const Vec3* previous_friction);
  // Solves the isolated contacts gathered in batch_contact_ (a multiple of four of them) with
  // solveIsolatedBatch() and empties the batch.
  void flushIsolatedBatch(const std::vector<Contact>& contacts, Vec3Map& x, Vec3Map& v,
                          const ConstScalarMap& inverse_mass,
                          const Eigen::Ref<const Vec3Array>& acceleration, Real h, Real slop);
  // Index into the warm starts of the entry named `key`, or -1; `cursor` follows the contacts.
  std::ptrdiff_t findWarm(std::uint64_t key, std::size_t& cursor);
  // What every substep starts with, before any contact.
  void beginSubstep(Eigen::Index n, Real h, Real position_weight,
                    const std::vector<LinkGeometry>& links);
  // Before the first contact of the substep; dense: see rows_dense_.
  void beginPrepare(const Vec3Map& v, const Eigen::Ref<const Vec3Array>& acceleration, bool dense);
  // beginPrepare() for the parts, at the first of them (few rows among them: not dense).
  void preparePartsOnce(const Vec3Map& v, const Eigen::Ref<const Vec3Array>& acceleration);
  // Sets up contacts (the substep's from index `base` on): isolated ones are solved, the others
  // become rows.
  void prepare(std::vector<Contact>& contacts, std::size_t base, Vec3Map& x, Vec3Map& v,
               const ConstScalarMap& inverse_mass, const Eigen::Ref<const Vec3Array>& acceleration,
               Real h, Real slop, IsolatedContacts isolated);

  int resolveVelocities(Vec3Map& v, const ConstScalarMap& inverse_mass,
                        const CollisionSettings& settings);
  // One velocity pass over the rows (kFriction: some row has friction); returns the largest
  // change.
  template <bool kBackward, bool kFriction>
  Real velocityPass(Vec3Map& v, const ConstScalarMap& inverse_mass);
  // Moves each particle with its resting contacts' impulses (see resolve()).
  void followRestingImpulses(Vec3Map& x, const Vec3Map& v, const ConstScalarMap& inverse_mass);
  void indexWarmByKey() const;
  // Also, in its first pass, keeps the impulses for the next substep and measures the closing
  // speed left (velocities are final by then).
  int resolvePositions(const std::vector<Contact>& contacts, Vec3Map& x, Vec3Map& v,
                       const ConstScalarMap& inverse_mass, Real h,
                       const CollisionSettings& settings, ContactStats& stats);
  // For a link: the normal (from a towards b) and length error between its ends, each at
  // x - lead v_initial (lead 0: where they are; beta h: where they move from this substep); false
  // when degenerate.
  bool linkState(const Contact& c, const Vec3Map& x, Real lead, Vec3& normal, Real& error) const;
  // A link row's position correction where its ends are now, as one pass makes it: false when it
  // needs none (within rod_tolerance of its length, a slack cable, coincident ends).
  bool linkCorrection(const Row& row, const Contact& link, const Vec3Map& x,
                      const CollisionSettings& settings, Vec3& normal, Real& correction,
                      Real& max_penetration) const;
  // Moves a row's ends by `correction` along normal, shared by their inverse masses. Inline: the
  // position sweep calls it for every corrected contact.
  inline void applyCorrection(const Row& row, const Vec3& normal, Real correction, Vec3Map& x,
                              const ConstScalarMap& inverse_mass);

  // Links that hang together solved as blocks (link_blocks.h; link_block_passes.cpp): found and
  // their velocity systems factored once a substep, solved after each velocity pass's sweep and
  // each position pass's sweep, which leave their rows alone.
  void prepareLinkBlocks(const ConstScalarMap& inverse_mass,
                         const Eigen::Ref<const Vec3Array>& acceleration);
  // Scales block c's turn parts of its targets so its block adds no kinetic energy.
  void limitBlockTurn(std::size_t c);
  // A block with more rows than moving knots (a rope tied between two points, a ladder, a ring)
  // or a knot in three links or more (a Y) is solved as SHAKE solves it: without the turn parts of
  // its targets, and with its position corrections' moves given back to its knots as velocity at
  // the end of the position phase (feedBlockMoves).
  void prepareFedBlock(std::size_t c, const Eigen::Ref<const Vec3Array>& acceleration);
  // Adds sign * x of fed block c's knots to what its corrections moved them by.
  void noteFedMoves(std::size_t c, const Vec3Map& x, Real sign);
  void feedBlockMoves(Vec3Map& v, const ConstScalarMap& inverse_mass, Real h);
  Real solveLinkBlockVelocities(Vec3Map& v, const ConstScalarMap& inverse_mass);
  bool correctLinkBlockPositions(const std::vector<Contact>& contacts, Vec3Map& x,
                                 const ConstScalarMap& inverse_mass,
                                 const CollisionSettings& settings, Real& max_penetration);
  // Brings block c to its lengths for one pass: its Newton step, else row by row. `worst` is its
  // worst strain now.
  void correctLinkBlock(std::size_t c, const std::vector<Contact>& contacts, Vec3Map& x,
                        const ConstScalarMap& inverse_mass, const CollisionSettings& settings,
                        Real worst, Real& max_penetration);
  // The share of its length block entry e is off by in the way a correction would fix (a rod
  // either way, a cable stretched), with its direction and error; negative for coincident ends.
  Real blockStrain(std::size_t e, const std::vector<Contact>& contacts, const Vec3Map& x,
                   Vec3& normal, Real& error) const;
  // Moves block c's knots by `scale` times the impulses its position block solved for (in
  // blocks_.rhs).
  void applyLinkBlockPositions(std::size_t c, Real scale, Vec3Map& x,
                               const ConstScalarMap& inverse_mass);
  void saveBlockKnots(std::size_t c, const Vec3Map& x);
  void restoreBlockKnots(std::size_t c, Vec3Map& x);
  // Row k's velocity update by itself (Gauss-Seidel), as velocityPass makes it.
  Real solveRowVelocity(std::size_t k, Vec3Map& v, const ConstScalarMap& inverse_mass);
  // Applies impulse j along a row; returns |j| (w_a + w_b), the pass's measure of change.
  Real applyRowImpulse(const Row& row, Real j, Vec3Map& v, const ConstScalarMap& inverse_mass);
  // (v_a - v_b).n, as the sweep measures it. Inline: the position phase's first pass measures it
  // for every row.
  inline Real separatingVelocity(const Row& row, const Eigen::Ref<const Vec3Array>& v) const;
  // How far a link is off its length the way a correction fixes it: a rod either way (|error|),
  // a cable only stretched (error, negative when slack).
  static Real linkOverlap(const Row& row, const Real error) {
    return row.kind == ContactKind::kRod ? std::abs(error) : error;
  }
  Real rowMobility(const Row& row, const ConstScalarMap& inverse_mass) const;  // w_a + w_b
  // The least of w_a and w_b that is not 0.
  Real leastMobility(const Row& row, const ConstScalarMap& inverse_mass) const;
  // K_ij's part through one shared knot: s_i s_j w_p n_i.n_j.
  Real couplingValue(const LinkBlocks::Coupling& coupling, const Vec3& first, const Vec3& second,
                     const ConstScalarMap& inverse_mass) const;
  // The least overlap the position correction may leave this substep to the contact of particles
  // a and b made with `penetration` (see the class comment); -inf without the radii.
  Real leastPairDepth(std::uint32_t a, std::uint32_t b, Real penetration) const;

  const std::vector<LinkGeometry>* links_ = nullptr;  // during resolve()
  const Real* radius_ = nullptr;                      // per particle, during resolve() when given

  std::vector<Row> rows_;  // the constraints that are not isolated: [0, row_count_)
  std::size_t row_count_ = 0;
  std::vector<std::uint32_t> row_contact_;  // per row: its index in the contacts
  std::vector<Real> row_turn_;  // per active link row: the part of its target that turns it
  LinkBlocks blocks_;
  std::vector<std::uint8_t> block_factored_;  // per block: its velocity factors kept
  std::vector<std::uint8_t> block_newton_;    // per block: its Newton step tried this substep
  // Per block entry, in the position passes: its direction and whether it is in the block.
  std::vector<Vec3> block_normal_;
  std::vector<std::uint8_t> block_included_;
  std::vector<Vec3> block_saved_;  // a block's knots' positions and displacements before a step
  // The knots of the fed blocks, each block's together.
  struct FedKnot {
    std::uint32_t knot;
    std::uint32_t block;
    Vec3 acceleration;  // over the substep: the forces that work against its moves
    Vec3 moved;         // by its block's corrections in this position phase
  };
  static constexpr std::size_t kNotFed = ~std::size_t{0};
  std::vector<FedKnot> fed_knots_;
  std::vector<std::size_t> fed_begin_;  // per block: its first fed knot, or kNotFed
  // Row k's index in the contacts (k itself when isolated contacts were not looked for).
  std::size_t rowContact(const std::size_t k) const {
    return rows_are_contacts_ ? k : row_contact_[k];
  }
  bool rows_are_contacts_ = false;
  // Per particle: (stamp_ << 1) when in one contact this substep, | 1 when in more.
  std::vector<std::uint64_t> uses_;
  bool any_shared_ = false;        // some particle is in more than one contact
  bool rows_dense_ = false;        // |a| and initial velocities of every particle, not per row
  ScalarArray acceleration_norm_;  // per particle, when rows_dense_
  Vec3Array initial_velocity_;     // per particle of a row, before the warm starts
  std::vector<std::uint32_t> initial_stamp_;  // per particle: == stamp_ when kept this substep
  // Per particle: == stamp_ when one of its active rows is not a resting contact.
  std::vector<std::uint32_t> mixed_stamp_;
  // Per particle, marked by followRestingImpulses when some particle is mixed: == stamp_ when it
  // rests on an active contact that pushes, and when it is in an active link's row.
  std::vector<std::uint32_t> rests_stamp_;
  std::vector<std::uint32_t> linked_stamp_;
  std::uint32_t stamp_ = 0;
  bool any_mixed_ = false;
  // The isolated contacts' share of the stats (their particles are in touched_ without a
  // touched_flag_ or a displacement_ entry: no row meets them).
  std::size_t isolated_count_ = 0;
  Real isolated_max_penetration_ = 0.0;
  Real isolated_max_closing_ = 0.0;
  bool isolated_corrected_ = false;
  // Isolated contacts without b waiting to be solved four at a time: their index and warm start
  // (the friction one xyz at 3e, zero when none), and whether one of them has friction.
  static constexpr std::size_t kBatchSize = 64;
  std::array<std::uint32_t, kBatchSize> batch_contact_{};
  std::array<Real, kBatchSize> batch_previous_{};
  std::array<Real, 3 * kBatchSize> batch_previous_friction_{};
  bool batch_rubs_ = false;
  std::size_t batch_count_ = 0;
  std::size_t batch_base_ = 0;          // the batch's contacts are the substep's from this index on
  std::size_t warm_cursor_ = 0;         // where the next contact's warm start is looked for first
  std::size_t prepared_count_ = 0;      // contacts set up this substep (warm start entries)
  std::size_t parts_size_ = 0;          // contacts added by addPart() this substep
  bool parts_prepared_ = false;         // beginPrepare() ran for this substep's parts
  std::vector<LinkGeometry> no_links_;  // always empty
  std::vector<Contact> no_contacts_;    // always empty
  std::vector<Real> friction_coefficient_;
  std::vector<Vec3> friction_total_;  // per row: accumulated friction impulse
  // Warm starts: what each contact of the last substep ended it with (key, normal impulse,
  // friction impulse in the world frame; no friction entries when no contact had friction), in
  // that substep's contact order, so a settled scene finds each at the cursor; warm_by_key_
  // (key, index) sorted by key for the others, built when needed.
  std::vector<std::uint64_t> warm_key_;
  std::vector<Real> warm_normal_;
  std::vector<Vec3> warm_friction_;
  std::vector<std::uint64_t> next_warm_key_;
  std::vector<Real> next_warm_normal_;
  std::vector<Vec3> next_warm_friction_;
  bool any_friction_ = false;  // some row of this substep has friction
  mutable std::vector<std::pair<std::uint64_t, std::uint32_t>> warm_by_key_;
  Real last_substep_ = 0.0;
  Real follow_scale_ = 0.0;  // beta h of the last resolve()
  Real inverse_follow_scale_ = 0.0;
  Vec3Array displacement_;
  std::vector<std::uint8_t> touched_flag_;
  std::size_t flagged_count_ = 0;  // particles of touched_ with a touched_flag_ (met by a row)
  std::vector<std::uint32_t> touched_;
};

inline Real ContactResolver::separatingVelocity(const Row& row,
                                                const Eigen::Ref<const Vec3Array>& v) const {
  Vec3 relative = v.col(row.a.particleIndex());
  if (row.flags & Row::kHasB) relative -= v.col(row.b.particleIndex());
  return relative.dot(row.normal);
}

inline void ContactResolver::applyCorrection(const Row& row, const Vec3& normal,
                                             const Real correction, Vec3Map& x,
                                             const ConstScalarMap& inverse_mass) {
  // dp_a = w_a / (w_a + w_b) d n,  dp_b = -w_b / (w_a + w_b) d n
  const bool b = row.flags & Row::kHasB;
  const Real wa = inverse_mass[row.a.particleIndex()];
  const Real w_sum =
      wa + (b ? inverse_mass[row.b.particleIndex()] : 0.0);  // as prepare() summed them
  const Vec3 move_a = response::share(correction, wa, w_sum) * normal;
  x.col(row.a.particleIndex()) += move_a;
  displacement_.col(row.a.particleIndex()) += move_a;
  if (wa > 0.0) touch(row.a.particleIndex());
  if (b) {
    const Real wb = inverse_mass[row.b.particleIndex()];
    const Vec3 move_b = response::share(-correction, wb, w_sum) * normal;
    x.col(row.b.particleIndex()) += move_b;
    displacement_.col(row.b.particleIndex()) += move_b;
    if (wb > 0.0) touch(row.b.particleIndex());
  }
}

}  // namespace engine
}  // namespace mass_aggregate_sim
