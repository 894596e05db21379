#pragma once
// The influence function ω(ξ) of a bond: 1, δ/ξ or exp(−ξ²/δ²), for a kind fixed at compile time (what a
// vectorised bond loop calls) or known only at run time. Every bond loop weighs its bonds with it: the
// models (materials/), the correspondence kinematics and mirror bonds (correspondence/).
#include <cmath>
#include <type_traits>

#include "peridot/deck/problem.hpp"

namespace peridot {

/// ω(ξ) = 1, δ/ξ or exp(−ξ²/δ²) for a kind fixed at compile time: what a vectorised bond loop calls (a
/// run-time switch, with its call to exp, keeps a loop scalar).
template <InfluenceKind Kind>
inline double influence_of(double xi, double horizon) {
  if constexpr (Kind == InfluenceKind::inverse_distance) return horizon / xi;
  else if constexpr (Kind == InfluenceKind::gaussian) return std::exp(-(xi * xi) / (horizon * horizon));
  else return 1.0;
}

/// Runs f(std::integral_constant<InfluenceKind, kind>) for a kind known only at run time.
template <class F>
decltype(auto) with_influence(InfluenceKind kind, F&& f) {
  using K = InfluenceKind;
  switch (kind) {
    case K::inverse_distance: return f(std::integral_constant<K, K::inverse_distance>{});
    case K::gaussian: return f(std::integral_constant<K, K::gaussian>{});
    case K::constant: break;
  }
  return f(std::integral_constant<K, K::constant>{});
}

/// ω(ξ) for a kind known only at run time.
inline double influence(InfluenceKind kind, double xi, double horizon) {
  return with_influence(kind, [&](auto k) { return influence_of<k.value>(xi, horizon); });
}

}  // namespace peridot
