#pragma once
// Surface correction by the energy method (after Madenci & Oterkus 2016; docs/algorithms.md §15): a point
// whose family is cut by a free surface stores another energy than the classical one under a homogeneous
// strain. Per point i and axis d, g_d(i) = W_classical / W_d(i), W_d the point's energy under a uniaxial strain ε
// along d and W_classical = ½ M ε² (M = K + 4G/3 in 3D, K′ + G in 2D); a bond takes the ellipsoid
// interpolation of its ends' mean factors along its reference direction n,
//   G_ij = [Σ_d (n_d / ḡ_d)²]^(−1/2),  ḡ_d = (g_d(i) + g_d(j))/2,
// which the bond loops apply to its influence (the kernels see ω G: pmb's pair micromodulus, lps's sums).
// The factors come from the uncorrected energies, once, as the procedure prescribes. A point's corrected energies
// are then close to, not exactly, the classical ones: G mixes both ends' factors, and lps's θ² term is quadratic
// in G, so a stiff outer row of lps is over-corrected (measured in tests/verification/surface_correction_test.cpp:
// a 2D plane-stress LPS plate stores 4.9 % more than the classical energy of a uniaxial strain uncorrected and
// 3.2 % less corrected; pmb 14.6 % more and 1.2 %). Iterating the factors towards every point's classical energy
// was tried: it spreads non-uniform factors into the interior, one pass per δ, and does not converge on an
// irregular lattice (a point whose bonds barely reach along one axis has no factor that fixes its energy).
#include <cstddef>
#include <functional>
#include <vector>

#include "peridot/materials/model_context.hpp"
#include "peridot/parallel/communicator.hpp"
#include "peridot/state/fields.hpp"

namespace peridot {

/// The largest |W_d / W_classical − 1| over the corrected points and axes (all ranks), before and after.
struct SurfaceCorrectionResult {
  bool applied = false;
  double largest_uncorrected = 0;
  double largest_deviation = 0;
};

/// Fills ctx.bond_scale when a block has surface_correction (else leaves it empty and returns {}).
/// `owned`: the points of this rank (the rest are ghosts); `exchange` copies a per-point field to the ghosts.
/// The models must be calibrated (calibrate_models); a model whose constants read the bond factors
/// (lps: m̃/m) is calibrated again after it.
SurfaceCorrectionResult correct_surfaces(ModelContext& ctx, const Problem& problem, MaterialHistory& history,
                                         std::size_t owned,
                                         const std::function<void(std::vector<double>&)>& exchange,
                                         const Communicator& comm);

/// The classical energy density ½ M ε² of a uniaxial strain ε along one axis for a block (M = K + 4G/3 in
/// 3D, K′ + G in 2D; a bond-based model's with its implied Poisson ratio).
double uniaxial_strain_energy(const MaterialParams& p, const Problem& problem, double strain);

}  // namespace peridot
