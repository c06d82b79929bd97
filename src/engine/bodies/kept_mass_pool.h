#pragma once
// The coupled masses the body contacts keep inverted (BodyContact::KeptMasses, 512 bytes), in
// slots apart from the contacts: a contact takes a slot the first time it has more than one point
// and gives it back when it ends. The slots are taken and given back in the contacts' order, so
// the same steps use the same slots.

#include <cstdint>
#include <vector>

#include "engine/bodies/body_contact.h"
#include "engine/core/prefetch.h"

namespace mass_aggregate_sim {
namespace engine {

class KeptMassPool {
 public:
  // The contact's kept masses, a slot taken (zeroed, as a new contact's) when it first has more
  // than one point. A contact of one point or none never reads them (prepareMasses): those share
  // one scratch.
  BodyContact::KeptMasses& of(BodyContact& contact) {
    if (contact.kept_masses == BodyContact::kNoKeptMasses) {
      if (contact.manifold.count <= 1) return scratch_;
      contact.kept_masses = take();
    }
    return slots_[contact.kept_masses];
  }
  // What the contact keeps: zero before it takes a slot.
  const BodyContact::KeptMasses& of(const BodyContact& contact) const {
    static const BodyContact::KeptMasses none;
    return contact.kept_masses == BodyContact::kNoKeptMasses ? none : slots_[contact.kept_masses];
  }
  // Asks for the lines of one of the contact's kept coupled masses (`which`: coupled or
  // upper_alone), if it has a slot: the contacts are prepared in height order, not in the
  // pool's, and each reads its kept mass first thing.
  void prefetch(const BodyContact& contact,
                BodyContact::InvertedMass BodyContact::KeptMasses::*which) const {
    if (contact.kept_masses == BodyContact::kNoKeptMasses) return;
    const BodyContact::InvertedMass& kept = slots_[contact.kept_masses].*which;
    prefetchBytes(&kept.mass, sizeof(kept.mass));
  }
  // Gives back the slots of the contacts in `before` that `after` does not hold.
  void keepOnly(const std::vector<BodyContact>& before, const std::vector<BodyContact>& after) {
    held_.resize(slots_.size(), 0);
    for (const BodyContact& c : after) {
      if (c.kept_masses != BodyContact::kNoKeptMasses) held_[c.kept_masses] = 1;
    }
    for (const BodyContact& c : before) {
      if (c.kept_masses != BodyContact::kNoKeptMasses && !held_[c.kept_masses]) {
        free_.push_back(c.kept_masses);
      }
    }
    for (const BodyContact& c : after) {
      if (c.kept_masses != BodyContact::kNoKeptMasses) held_[c.kept_masses] = 0;
    }
  }
  void giveBack(const BodyContact& contact) {
    if (contact.kept_masses != BodyContact::kNoKeptMasses) free_.push_back(contact.kept_masses);
  }
  // Slots in use, for tests.
  std::size_t taken() const { return slots_.size() - free_.size(); }

 private:
  std::uint32_t take() {
    if (free_.empty()) {
      slots_.emplace_back();
      return static_cast<std::uint32_t>(slots_.size() - 1);
    }
    const std::uint32_t slot = free_.back();
    free_.pop_back();
    slots_[slot] = BodyContact::KeptMasses{};
    return slot;
  }

  std::vector<BodyContact::KeptMasses> slots_;
  std::vector<std::uint32_t> free_;
  std::vector<std::uint8_t> held_;  // by slot, during keepOnly
  BodyContact::KeptMasses scratch_;
};

}  // namespace engine
}  // namespace mass_aggregate_sim
