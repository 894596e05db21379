#pragma once
// The constitutive plug-in interface of the correspondence model and the per-point stress step that every
// law shares (Foster, Silling & Chen 2010, IJNME 81:1242):
//   L = Ḟ F⁻¹ (eq 14) → Flanagan–Taylor R, V and d = Rᵀ D R (eqs 15–18, flanagan_taylor.hpp)
//   → τ_{n+1} = law(τ_n, d, Δt, history) in the unrotated frame (eqs 19–22; the objective rate of eq 21)
//   → σ = R τ Rᵀ (eq 23) → P = det(F) σ F⁻ᵀ (eq 24) → P K⁻¹, from which T⟨ξ⟩ = ω P K⁻¹ ξ (eq 25, force.hpp).
// A law is a small struct (hypoelastic.hpp, j2_viscoplastic.hpp) with a per-point History type; a block
// holds one law and one History per point, and the block loop is instantiated per law, so nothing is
// virtual inside it (dispatch once per block, DESIGN.md "Kernels").
#include <cmath>
#include <concepts>
#include <cstdint>
#include <limits>
#include <utility>
#include <vector>

#include <fmt/format.h>

#include "peridot/core/error.hpp"
#include "peridot/correspondence/flanagan_taylor.hpp"
#include "peridot/correspondence/kinematics.hpp"
#include "peridot/geometry/discretize.hpp"

namespace peridot::correspondence {

/// A constitutive law in the unrotated frame: `update` returns τ_{n+1} (Pa) from τ_n (Pa), the unrotated
/// rate of deformation d (1/s) and Δt (s), and advances the point's History from n to n+1. It must not
/// throw (it runs inside OpenMP loops); a failure returns a non-finite stress, which the caller reports.
/// bulk_modulus() and shear_modulus() (Pa) serve the hourglass stiffness and the stable time step.
template <class Law>
concept ConstitutiveLaw = requires(const Law& law, const Mat3& tau, const Mat3& d, double dt,
                                   typename Law::History& history) {
  { law.update(tau, d, dt, history) } -> std::same_as<Mat3>;
  { law.bulk_modulus() } -> std::convertible_to<double>;
  { law.shear_modulus() } -> std::convertible_to<double>;
};

/// P = det(F) σ F⁻ᵀ (eq 24), first Piola–Kirchhoff stress (Pa).
inline Mat3 first_piola_kirchhoff(const Mat3& F, const Mat3& cauchy) {
  return F.determinant() * cauchy * F.inverse().transpose();
}

/// One material point through one step: F_end = F^{n+1}, F_rate = Ḟ^{n+1/2} (1/s). Updates R, V, τ and
/// the history; returns the Cauchy stress σ^{n+1} = R τ Rᵀ (Pa). The peridynamic block loop and the
/// material-point driver both call this, so a homogeneous peridynamic deformation reproduces the driver.
template <ConstitutiveLaw Law>
Mat3 material_point_step(const Law& law, const Mat3& F_end, const Mat3& F_rate, double dt, PolarState& polar,
                         Mat3& unrotated_stress, typename Law::History& history) {
  const Mat3 L = mid_step_velocity_gradient(F_end, F_rate, dt);
  const Mat3 d = flanagan_taylor_update(L, dt, polar);
  unrotated_stress = law.update(unrotated_stress, d, dt, history);
  return polar.rotation * unrotated_stress * polar.rotation.transpose();
}

/// Per-point stress state of the correspondence points (all blocks).
struct StressFields {
  TensorField rotation;          ///< R (-), starts as I
  TensorField left_stretch;      ///< V (-), starts as I
  TensorField unrotated_stress;  ///< τ (Pa)
  TensorField cauchy_stress;     ///< σ (Pa)
  TensorField force_tensor;      ///< P K⁻¹ (N/m⁷): T⟨ξ⟩ = ω (P K⁻¹) ξ
  void resize(std::size_t n) {
    rotation.assign(n, Mat3::Identity());
    left_stretch.assign(n, Mat3::Identity());
    unrotated_stress.assign(n, Mat3::Zero());
    cauchy_stress.assign(n, Mat3::Zero());
    force_tensor.assign(n, Mat3::Zero());
  }
};

/// One block of correspondence points: its law and one History per point (index i − range.begin).
template <ConstitutiveLaw Law>
struct CorrespondenceBlock {
  Law law;
  BlockRange range;
  std::vector<typename Law::History> history;
  CorrespondenceBlock(Law l, BlockRange r) : law(std::move(l)), range(r), history(r.end - r.begin) {}
};

/// The stress step for every point of the block, from the kinematics of this step (u^{n+1}, v^{n+1/2}).
/// Throws NumericalError naming the lowest-numbered point whose F is inverted (det F ≤ 0) or whose law
/// returned a non-finite stress.
template <ConstitutiveLaw Law>
void update_block_stress(const CorrespondenceContext& ctx, const KinematicFields& kin, double dt,
                         CorrespondenceBlock<Law>& block, StressFields& s) {
  constexpr std::size_t none = std::numeric_limits<std::size_t>::max();
  std::size_t first_inverted = none, first_nonfinite = none;
  const std::size_t begin = block.range.begin, end = block.range.end;
#pragma omp parallel for schedule(static) reduction(min : first_inverted, first_nonfinite)
  for (std::size_t i = begin; i < end; ++i) {
    const Mat3 F = kin.deformation_gradient.get(i);
    const Mat3 F_rate = kin.deformation_gradient_rate.get(i);
    // The mid-step F must be invertible too (L uses its inverse).
    if (!(F.determinant() > 0) || !((F - 0.5 * dt * F_rate).determinant() > 0)) {
      first_inverted = std::min(first_inverted, i);
      continue;
    }
    PolarState polar{s.rotation.get(i), s.left_stretch.get(i)};
    Mat3 tau = s.unrotated_stress.get(i);
    const Mat3 sigma = material_point_step(block.law, F, F_rate, dt, polar, tau, block.history[i - begin]);
    if (!sigma.allFinite()) {
      first_nonfinite = std::min(first_nonfinite, i);
      continue;
    }
    s.rotation.set(i, polar.rotation);
    s.left_stretch.set(i, polar.left_stretch);
    s.unrotated_stress.set(i, tau);
    s.cauchy_stress.set(i, sigma);
    s.force_tensor.set(i, first_piola_kirchhoff(F, sigma) * kin.shape_inverse.get(i));
  }
  const std::size_t bad = std::min(first_inverted, first_nonfinite);
  if (bad == none) return;
  const Discretization& disc = *ctx.disc;
  const std::uint32_t id = bad < disc.input_id.size() ? disc.input_id[bad] : static_cast<std::uint32_t>(bad);
  const std::string what = bad == first_inverted
                               ? fmt::format("has an inverted deformation gradient (det F = {:.3g})",
                                             kin.deformation_gradient.get(bad).determinant())
                               : std::string("got a non-finite stress from its constitutive law");
  throw NumericalError(fmt::format("correspondence model: point {} (input id {}) at ({:g}, {:g}, {:g}) m {}", bad,
                                   id, disc.x(bad, 0), disc.x(bad, 1), disc.x(bad, 2), what));
}

}  // namespace peridot::correspondence
