#pragma once
// The one place that maps a ModelKind to its kernel type: adding a model adds one case here.
// Bond loops are instantiated per (dimension, model) pair, so no call inside a loop is virtual.
#include <type_traits>
#include <utility>

#include "peridot/materials/lps.hpp"
#include "peridot/materials/lps_plastic.hpp"
#include "peridot/materials/lps_viscoelastic.hpp"
#include "peridot/materials/pmb.hpp"

namespace peridot {

template <class F>
decltype(auto) with_model(ModelKind kind, F&& f) {
  switch (kind) {
    case ModelKind::pmb: return std::forward<F>(f)(Pmb{});
    case ModelKind::lps: return std::forward<F>(f)(Lps{});
    case ModelKind::lps_plastic: return std::forward<F>(f)(LpsPlastic{});
    case ModelKind::lps_viscoelastic: return std::forward<F>(f)(LpsViscoelastic{});
  }
  return std::forward<F>(f)(Pmb{});
}

template <class F>
decltype(auto) with_dimension(int dimension, F&& f) {
  if (dimension == 2) return std::forward<F>(f)(std::integral_constant<int, 2>{});
  return std::forward<F>(f)(std::integral_constant<int, 3>{});
}

}  // namespace peridot
