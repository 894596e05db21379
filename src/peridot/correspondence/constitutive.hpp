#pragma once
// The constitutive plug-in interface of the correspondence model and the per-point stress step that every
// law shares (Foster, Silling & Chen 2010, IJNME 81:1242):
//   L = Ḟ F⁻¹ (eq 14) → Flanagan–Taylor R, V and d = Rᵀ D R (eqs 15–18, flanagan_taylor.hpp)
//   → τ_{n+1} = law(τ_n, d, Δt, history) in the unrotated frame (eqs 19–22; the objective rate of eq 21)
//   → σ = R τ Rᵀ (eq 23) → P = det(F) σ F⁻ᵀ (eq 24) → P K⁻¹, from which T⟨ξ⟩ = ω P K⁻¹ ξ (eq 25, force.hpp).
// A law is a small struct (hypoelastic.hpp, j2_viscoplastic.hpp) with a per-point History type; a block
// holds one law and one History per point, and the block loop is instantiated per law, so nothing is
// virtual inside it (dispatch once per block, docs/design.md "Kernels").
#include <algorithm>
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
/// When `rate_of_deformation` is given it receives the unrotated d of the step (1/s).
template <ConstitutiveLaw Law>
Mat3 material_point_step(const Law& law, const Mat3& F_end, const Mat3& F_rate, double dt, PolarState& polar,
                         Mat3& unrotated_stress, typename Law::History& history,
                         Mat3* rate_of_deformation = nullptr) {
  const Mat3 L = mid_step_velocity_gradient(F_end, F_rate, dt);
  const Mat3 d = flanagan_taylor_update(L, dt, polar);
  if (rate_of_deformation) *rate_of_deformation = d;
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

/// One block of correspondence points: its law and one History per point (index i − range.begin): the
/// committed one (`history`) and the one of the last trial stress update (`trial_history`, see
/// trial_block_stress).
template <ConstitutiveLaw Law>
struct CorrespondenceBlock {
  Law law;
  BlockRange range;
  std::vector<typename Law::History> history;
  std::vector<typename Law::History> trial_history;
  CorrespondenceBlock(Law l, BlockRange r)
      : law(std::move(l)), range(r), history(r.end - r.begin), trial_history(r.end - r.begin) {}
  /// Accepts the last trial_block_stress: its history becomes the committed one.
  void commit_history() { std::swap(history, trial_history); }
};

/// Inelastic work of one step per unit reference volume (J/m³): the work of the stress on the part of the
/// strain increment that the elastic law does not account for,
///   ΔW_in = J_{n+½} S_{n+½} : (dev(d) Δt − (S_{n+1} − S_n)/(2μ)),   S = dev τ, S_{n+½} = ½(S_n + S_{n+1}).
/// With the pressure update p_{n+1} = p_n + K tr(d) Δt of both laws, the trapezoidal stress work
/// J τ_{n+½} : d Δt is exactly ΔW_in plus the change of the elastic energy J (p²/(2K) + S:S/(4μ)), so the two
/// partition the work of the stress. For the hypoelastic law ΔW_in = 0; for J2 it is the plastic work.
inline double inelastic_work_increment(const Mat3& tau_old, const Mat3& tau_new, const Mat3& d, double dt,
                                       double shear_modulus, double mid_step_jacobian) {
  const Mat3 S_old = deviator(tau_old), S_new = deviator(tau_new);
  return mid_step_jacobian * double_contraction(0.5 * (S_old + S_new),
                                                deviator(d) * dt - (S_new - S_old) / (2 * shear_modulus));
}

/// Elastic energy per unit reference volume (J/m³) of an unrotated stress τ (Pa) and J = det F:
/// J (p²/(2K) + S:S/(4μ)), p = tr(τ)/3, S = dev τ.
inline double elastic_energy_density(const Mat3& tau, double jacobian, double bulk_modulus, double shear_modulus) {
  const double p = tau.trace() / 3;
  const Mat3 S = deviator(tau);
  return jacobian * (p * p / (2 * bulk_modulus) + double_contraction(S, S) / (4 * shear_modulus));
}

/// Bulk (artificial) viscosity of shocks, the von Neumann–Richtmyer quadratic term with Landshoff's linear
/// one as hydrocodes apply it (Wilkins 1980; LS-DYNA's Q1, Q2): a pressure
///   q = ℓ (b_q ℓ (tr D)² − b_l tr D)  while the point is compressed (tr D < 0), 0 otherwise,
/// b_q = C_q ρ, b_l = C_l ρ c (c the P-wave speed), ℓ the point's size (V^(1/3)), added to the law's stress as
/// −q I. It spreads a shock over a few points and damps the oscillation behind it; it acts only in compression,
/// so it does little for the ringing of a free surface after a release (docs/correspondence.md, "Not yet
/// done"). It is not part of the law's state (τ): its work
/// J q (−tr D) Δt per reference volume is dissipated. Returns q (Pa); tr D = tr d (d = Rᵀ D R).
inline double bulk_viscous_pressure(double trace_rate, double size, double linear, double quadratic) {
  if (!(trace_rate < 0)) return 0;
  return size * (quadratic * size * trace_rate * trace_rate - linear * trace_rate);
}

namespace detail {

/// The stress step of every point of a block from (R, V, τ) of `from` and the histories `from_history`
/// into `to` and `to_history` (the same objects for an update in place). `inelastic_work`, when given,
/// receives ΔW_in per point: added to it (accumulate) or stored.
template <ConstitutiveLaw Law>
void block_stress_step(const CorrespondenceContext& ctx, const KinematicFields& kin, double dt, const Law& law,
                       BlockRange range, const typename Law::History* from_history,
                       typename Law::History* to_history, const StressFields& from, StressFields& to,
                       double* inelastic_work, bool accumulate) {
  constexpr std::size_t none = std::numeric_limits<std::size_t>::max();
  std::size_t first_inverted = none, first_distorted = none, first_nonfinite = none;
  const std::size_t begin = range.begin, end = range.end;
  const bool failures = !ctx.failed_point.empty();
  const std::size_t own_block = begin < end ? static_cast<std::size_t>(ctx.disc->block[begin]) : 0;
  const double viscosity_linear =
      own_block < ctx.bulk_viscosity_linear.size() ? ctx.bulk_viscosity_linear[own_block] : 0.0;
  const double viscosity_quadratic =
      own_block < ctx.bulk_viscosity_quadratic.size() ? ctx.bulk_viscosity_quadratic[own_block] : 0.0;
  const bool viscous = viscosity_linear != 0 || viscosity_quadratic != 0;
#pragma omp parallel for schedule(static) reduction(min : first_inverted, first_distorted, first_nonfinite)
  for (std::size_t i = begin; i < end; ++i) {
    // A point without stress this step: its state stays as it was.
    const auto carry_no_stress = [&] {
      to_history[i - begin] = from_history[i - begin];
      if (inelastic_work && !accumulate) inelastic_work[i] = 0;
      to.rotation.set(i, from.rotation.get(i));
      to.left_stretch.set(i, from.left_stretch.get(i));
      to.unrotated_stress.set(i, from.unrotated_stress.get(i));
      to.cauchy_stress.set(i, Mat3::Zero());
      to.force_tensor.set(i, Mat3::Zero());
    };
    if (failures && ctx.failed_point[i]) {  // a free particle
      carry_no_stress();
      continue;
    }
    // With damage that breaks bonds, a point whose kinematics can no longer be followed has failed (D = 1: its
    // bonds break at the commit), as a finite element is eroded when it inverts; elsewhere it is an error.
    const auto kinematics_failed = [&](std::size_t& first_bad) {
      if constexpr (requires { law.damage.degrades_bonds(); from_history[0].damage; })
        if (law.damage.degrades_bonds()) {
          carry_no_stress();
          to_history[i - begin].damage = 1;
          return;
        }
      first_bad = std::min(first_bad, i);
    };
    const Mat3 F = kin.deformation_gradient.get(i);
    const Mat3 F_rate = kin.deformation_gradient_rate.get(i);
    // The mid-step F must be invertible too (L uses its inverse).
    if (!(F.determinant() > 0) || !((F - 0.5 * dt * F_rate).determinant() > 0)) {  // turned inside out
      kinematics_failed(first_inverted);
      continue;
    }
    PolarState polar{from.rotation.get(i), from.left_stretch.get(i)};
    const Mat3 tau_old = from.unrotated_stress.get(i);
    Mat3 tau = tau_old, d;
    typename Law::History history = from_history[i - begin];
    const Mat3 sigma = material_point_step(law, F, F_rate, dt, polar, tau, history, &d);
    to_history[i - begin] = history;
    if (!d.allFinite()) {  // the integrated stretch V lost positive definiteness (flanagan_taylor.hpp)
      kinematics_failed(first_distorted);
      continue;
    }
    if (!sigma.allFinite()) {
      first_nonfinite = std::min(first_nonfinite, i);
      continue;
    }
    const double q = viscous ? bulk_viscous_pressure(d.trace(), std::cbrt(ctx.disc->volume[i]), viscosity_linear,
                                                     viscosity_quadratic)
                             : 0.0;
    if (inelastic_work) {
      const double mid_jacobian = (F - 0.5 * dt * F_rate).determinant();
      double work = inelastic_work_increment(tau_old, tau, d, dt, law.shear_modulus(), mid_jacobian);
      if (q != 0) work -= mid_jacobian * q * d.trace() * dt;
      inelastic_work[i] = accumulate ? inelastic_work[i] + work : work;
    }
    to.rotation.set(i, polar.rotation);
    to.left_stretch.set(i, polar.left_stretch);
    to.unrotated_stress.set(i, tau);
    // Damage coupled to the local stress (johnson_cook_damage.hpp): the force carries (1 − D) σ.
    double integrity = 1;
    if constexpr (requires { law.damage.degrades_stress(); history.damage; })
      if (law.damage.degrades_stress()) integrity = 1 - history.damage;
    const Mat3 acting = integrity * (q != 0 ? Mat3(sigma - q * Mat3::Identity()) : sigma);
    to.cauchy_stress.set(i, acting);
    to.force_tensor.set(i, first_piola_kirchhoff(F, acting) * kin.shape_inverse.get(i));
  }
  const std::size_t bad = std::min({first_inverted, first_distorted, first_nonfinite});
  if (bad == none) return;
  const Discretization& disc = *ctx.disc;
  const std::uint32_t id = bad < disc.input_id.size() ? disc.input_id[bad] : static_cast<std::uint32_t>(bad);
  const std::string what =
      bad == first_inverted
          ? fmt::format("has an inverted deformation gradient (det F = {:.3g})", kin.deformation_gradient.get(bad).determinant())
      : bad == first_distorted
          ? std::string("has a non-finite rate of deformation: its stretch V, integrated over steps, is no longer "
                        "positive definite (a strain increment per step far too large; a shorter time step or "
                        "johnson_cook_damage lets such points fail)")
          : std::string("got a non-finite stress from its constitutive law");
  throw NumericalError(fmt::format("correspondence model: point {} (input id {}) at ({:g}, {:g}, {:g}) m {}", bad,
                                   id, disc.x(bad, 0), disc.x(bad, 1), disc.x(bad, 2), what));
}

}  // namespace detail

/// The stress step for every point of the block, from the kinematics of this step (u^{n+1}, v^{n+1/2}),
/// in place: R, V, τ of `s` and the block's history advance to n+1. When `inelastic_work` is given (one
/// entry per point of the problem), ΔW_in of every point of the block is added to it
/// (inelastic_work_increment). Throws NumericalError naming the lowest-numbered point whose F is inverted
/// (det F ≤ 0), whose rate of deformation is not finite or whose law returned a non-finite stress; with a law
/// whose damage breaks bonds, the first two make the point fail instead (D = 1).
template <ConstitutiveLaw Law>
void update_block_stress(const CorrespondenceContext& ctx, const KinematicFields& kin, double dt,
                         CorrespondenceBlock<Law>& block, StressFields& s, double* inelastic_work = nullptr) {
  detail::block_stress_step(ctx, kin, dt, block.law, block.range, block.history.data(), block.history.data(), s, s,
                            inelastic_work, true);
}

/// The same step as a trial that changes no committed state: from R, V, τ of `committed` and the block's
/// committed history into `trial` and block.trial_history, with ΔW_in of each point stored (not added) in
/// `inelastic_work`. A solver may run it any number of times for one step; accepting it is
/// block.commit_history() and swapping R, V, τ of trial and committed (the bits of update_block_stress).
template <ConstitutiveLaw Law>
void trial_block_stress(const CorrespondenceContext& ctx, const KinematicFields& kin, double dt,
                        CorrespondenceBlock<Law>& block, const StressFields& committed, StressFields& trial,
                        double* inelastic_work) {
  detail::block_stress_step(ctx, kin, dt, block.law, block.range, block.history.data(), block.trial_history.data(),
                            committed, trial, inelastic_work, false);
}

}  // namespace peridot::correspondence
