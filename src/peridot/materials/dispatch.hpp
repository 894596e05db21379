#pragma once
// The one place that maps a ModelKind to its kernel type: adding a model adds one case here.
// Bond loops are instantiated per (dimension, model) pair, so no call inside a loop is virtual.
#include <array>
#include <stdexcept>
#include <type_traits>
#include <utility>

#include "peridot/materials/lps.hpp"
#include "peridot/materials/lps_plastic.hpp"
#include "peridot/materials/lps_viscoelastic.hpp"
#include "peridot/materials/pmb.hpp"

namespace peridot {

/// The correspondence model has no bond kernel: its force is a per-point tensor gathered over the bonds
/// (correspondence/force.hpp, driven by solvers/correspondence_blocks.hpp). The tag only lets the dispatch
/// name it; bond_loop::for_each_block skips its blocks.
struct CorrespondenceTag {
  static constexpr bool uses_dilatation = false;
  static constexpr int bond_history_arrays = 0;
  static constexpr std::array<std::vector<double> MaterialHistory::*, 0> partner_point_scratch{};
};

template <class F>
decltype(auto) with_model(ModelKind kind, F&& f) {
  switch (kind) {
    case ModelKind::pmb: return std::forward<F>(f)(Pmb{});
    case ModelKind::lps: return std::forward<F>(f)(Lps{});
    case ModelKind::lps_plastic: return std::forward<F>(f)(LpsPlastic{});
    case ModelKind::lps_viscoelastic: return std::forward<F>(f)(LpsViscoelastic{});
    case ModelKind::correspondence: return std::forward<F>(f)(CorrespondenceTag{});
  }
  return std::forward<F>(f)(Pmb{});
}

/// with_model for the models that have a bond kernel (force_scalar, bond_energy); calling it with the
/// correspondence model is a programming error.
template <class F>
decltype(auto) with_bond_model(ModelKind kind, F&& f) {
  return with_model(kind, [&](auto model) -> decltype(std::forward<F>(f)(Pmb{})) {
    if constexpr (std::is_same_v<decltype(model), CorrespondenceTag>)
      throw std::logic_error("with_bond_model: the correspondence model has no bond kernel");
    else
      return std::forward<F>(f)(model);
  });
}

template <class F>
decltype(auto) with_dimension(int dimension, F&& f) {
  if (dimension == 2) return std::forward<F>(f)(std::integral_constant<int, 2>{});
  return std::forward<F>(f)(std::integral_constant<int, 3>{});
}

}  // namespace peridot
