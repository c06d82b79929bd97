#pragma once
// A contact the body solver keeps from step to step: a body shape (side a) against another body
// shape, a particle or a static collider (side b), its manifold, and the impulses it ended the
// last step with (warm starting): each point's normal impulse, carried over by the point's feature
// id, and the manifold's friction, carried over while the contact lasts.

#include <array>
#include <cstdint>
#include <tuple>

#include "engine/collision/narrowphase/manifold.h"
#include "mass_aggregate_sim/engine/bodies/body_store.h"

namespace mass_aggregate_sim {
namespace engine {

// In this order in the solver: contacts with static colliders first (they carry what rests on
// them), then between bodies, then particles.
enum class ContactOther : std::uint8_t { kCollider, kShape, kParticle };

// Orders contacts (and so the solver's rows): by kind of side b, then shape a, then side b.
struct ContactKey {
  ContactOther other = ContactOther::kShape;
  ShapeIndex shape = 0;
  std::uint64_t b = 0;  // a ShapeIndex, a ColliderId, or a particle's packed id

  friend bool operator<(const ContactKey& x, const ContactKey& y) {
    return std::tie(x.other, x.shape, x.b) < std::tie(y.other, y.shape, y.b);
  }
  friend bool operator==(const ContactKey& x, const ContactKey& y) {
    return x.other == y.other && x.shape == y.shape && x.b == y.b;
  }
};

struct BodyContact {
  ContactKey key;
  Manifold manifold;  // normal from a to b
  std::array<Real, Manifold::kMaxPoints> normal_impulses{};
  // The friction impulse at the points' centre (world frame: a turning normal takes its tangents
  // with it) and the twist impulse about the normal (contact_constraint.h).
  Vec3 friction_impulse = Vec3::Zero();
  Real twist_impulse = 0.0;
  Real friction = 0.0;
  Real restitution = 0.0;
  // The points' coupled mass when last inverted, and its pseudo-inverse: a resting contact's
  // mass does not change from step to step, and inverting it is most of preparing the contact.
  // One for both sides moving, one for the upper side alone (the shock pass). Kept apart from
  // the contact (KeptMassPool), so that a contact is light to copy and to scan.
  struct InvertedMass {
    Eigen::Matrix<Real, Manifold::kMaxPoints, Manifold::kMaxPoints> mass =
        Eigen::Matrix<Real, Manifold::kMaxPoints, Manifold::kMaxPoints>::Zero();
    Eigen::Matrix<Real, Manifold::kMaxPoints, Manifold::kMaxPoints> inverse =
        Eigen::Matrix<Real, Manifold::kMaxPoints, Manifold::kMaxPoints>::Zero();
  };
  struct KeptMasses {
    InvertedMass coupled;
    InvertedMass upper_alone;
  };
  static constexpr std::uint32_t kNoKeptMasses = ~std::uint32_t{0};
  // Its slot in the KeptMassPool, from the first time it has more than one point.
  std::uint32_t kept_masses = kNoKeptMasses;
};

// A manifold as the narrowphase finds it, before it takes over what its pair's contact carried.
struct FoundContact {
  ContactKey key;
  Manifold manifold;
  Real friction = 0.0;
  Real restitution = 0.0;
};

// Where a manifold's friction acts: the centre of its points, and each point from it in the
// contact plane (the normal part taken out).
struct ContactPatch {
  Vec3 center = Vec3::Zero();
  std::array<Vec3, Manifold::kMaxPoints> offsets{};
};
ContactPatch contactPatch(const Manifold& manifold);

}  // namespace engine
}  // namespace mass_aggregate_sim
