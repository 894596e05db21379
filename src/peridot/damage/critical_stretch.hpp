#pragma once
// Critical-stretch bond failure (Silling & Askari 2005; papers/003 "Bond fails when stretch too large"):
// a bond breaks, irreversibly, once s = (|Y| − |ξ|)/|ξ| exceeds s0; compression never breaks a bond.
// s0 is given, or follows from the fracture energy G0 (materials/material.cpp). Damage φ is the
// volume-weighted fraction of broken bonds of a point.
#include <cstdint>
#include <vector>

#include "peridot/solvers/internal_force.hpp"

namespace peridot {

/// Breaks every intact bond whose stretch exceeds the critical stretch (min of its two blocks'),
/// unless it touches a no-fail point. Returns the number of directed bonds broken now.
std::uint64_t break_bonds(const ModelContext& ctx, const VectorField& u);

/// φ_i = 1 − (intact neighbour volume)/(all neighbour volume).
void compute_damage(const ModelContext& ctx, std::vector<double>& damage);

}  // namespace peridot
