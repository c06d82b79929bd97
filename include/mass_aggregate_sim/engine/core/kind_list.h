#pragma once

#include <cstddef>
#include <tuple>
#include <variant>
#include <vector>

namespace mass_aggregate_sim {
namespace engine {

// The kinds of one family (force generators, links, colliders), in the order the engine visits
// them. Adding a kind is one entry here plus the kind's own file; every place that handles the
// family visits the list, so a kind without its traits (ForceKind<K>, LinkKind<K>, ShapeKind<K>)
// does not compile.
template <typename... Kinds>
struct KindList {};

// Calls f(KindTag<Kind>{}) for every kind of a list, in order (visiting the kinds themselves,
// not a world's arrays of them).
template <typename Kind>
struct KindTag {
  using type = Kind;
};
template <typename... Kinds, typename F>
void forEachKind(KindList<Kinds...>, F&& f) {
  (f(KindTag<Kinds>{}), ...);
}

// How many kinds a list has.
template <typename... Kinds>
constexpr std::size_t kindCount(KindList<Kinds...>) {
  return sizeof...(Kinds);
}

// One value of any kind of a KindList: std::visit over it needs every kind.
template <typename List>
struct KindVariantOf;
template <typename... Kinds>
struct KindVariantOf<KindList<Kinds...>> {
  using type = std::variant<Kinds...>;
};
template <typename List>
using KindVariant = typename KindVariantOf<List>::type;

// One array per kind of a KindList, visited in the list's order.
template <typename List>
class KindArrays;

template <typename... Kinds>
class KindArrays<KindList<Kinds...>> {
 public:
  template <typename Kind>
  std::vector<Kind>& of() {
    return std::get<std::vector<Kind>>(arrays_);
  }
  template <typename Kind>
  const std::vector<Kind>& of() const {
    return std::get<std::vector<Kind>>(arrays_);
  }
  // f(std::vector<Kind>&) for every kind, in order.
  template <typename F>
  void forEach(F&& f) {
    (f(of<Kinds>()), ...);
  }
  template <typename F>
  void forEach(F&& f) const {
    (f(of<Kinds>()), ...);
  }
  // The first kind for which f(std::vector<Kind>&) returns true; false when none does.
  template <typename F>
  bool any(F&& f) {
    return (f(of<Kinds>()) || ...);
  }
  bool empty() const { return (of<Kinds>().empty() && ...); }
  std::size_t size() const { return (of<Kinds>().size() + ...); }
  void clear() { (of<Kinds>().clear(), ...); }

 private:
  std::tuple<std::vector<Kinds>...> arrays_;
};

}  // namespace engine
}  // namespace mass_aggregate_sim
