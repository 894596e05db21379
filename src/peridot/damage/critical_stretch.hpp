#pragma once
// Critical-stretch bond failure (Silling & Askari, Comput. Struct. 83 (2005) 1526–1535):
// a bond breaks, irreversibly, once s = (|Y| − |ξ|)/|ξ| exceeds s0; compression never breaks a bond.
// s0 is given, or follows from the fracture energy G0 (materials/material.cpp). Damage φ is the
// volume-weighted fraction of broken bonds of a point.
#include <cstdint>
#include <vector>

#include "peridot/materials/model_context.hpp"

namespace peridot {

/// The failure rule as the bond loops apply it. It is checked in the first pass of a step that computes
/// each bond's extension (the dilatation when a state-based model is present, else the force), so no
/// separate pass is needed. The decision is symmetric (the same stretch bits from either end, the smaller
/// critical stretch of the two blocks, either end no-fail), so bond j → i breaks in the same step as
/// i → j without any communication.
struct BondFailure {
  const std::uint8_t* no_fail = nullptr;  ///< per point, or null when no point is protected

  explicit BondFailure(const ModelContext& ctx) : no_fail(ctx.no_fail.empty() ? nullptr : ctx.no_fail.data()) {}
  /// s = e/ξ > s0 (never for s0 = ∞), unless an end is protected.
  bool fails(std::size_t i, std::size_t j, double e, double xi, double critical_stretch) const {
    return e > critical_stretch * xi && !(no_fail && (no_fail[i] || no_fail[j]));
  }
};

/// φ_i = 1 − (intact neighbour volume)/(all neighbour volume).
void compute_damage(const ModelContext& ctx, std::vector<double>& damage);

}  // namespace peridot
