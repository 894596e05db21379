#include "peridot/materials/thermoviscoelastic.hpp"

// KeySpecs are written with designated initializers that leave the other fields at their defaults on
// purpose; GCC 12 warns about every omitted field regardless.
#pragma GCC diagnostic ignored "-Wmissing-field-initializers"

#include <algorithm>
#include <cmath>
#include <numbers>

#include <fmt/format.h>

#include "peridot/deck/map_reader.hpp"
#include "peridot/materials/bond_loop.hpp"
#include "peridot/materials/maxwell_element.hpp"
#include "peridot/materials/model_context.hpp"

namespace peridot {

using namespace bond_loop;

namespace {

/// What the lattice-anisotropy weight needs of a bond direction n: the harmonic c(n) (2D cos 4φ = 1 − 8 n_x² n_y²,
/// 3D n_x⁴ + n_y⁴ + n_z⁴ − 3/5: the lowest that a square or cubic lattice's sums see and an isotropic family does
/// not), s²/ε² of the two shears (ε_xy: 4 n_x² n_y², ε_xx = −ε_yy: (n_x² − n_y²)², each averaged over the three
/// coordinate planes in 3D) and Σ_planes n_a² n_b² of the simple-shear calibration.
struct LatticeShears {
  double harmonic, xy, xx_yy, planes;
};
template <int Dim>
LatticeShears lattice_shears(const double n[3]) {
  const double x2 = n[0] * n[0], y2 = n[1] * n[1];
  if constexpr (Dim == 2) return {1 - 8 * x2 * y2, 4 * x2 * y2, (x2 - y2) * (x2 - y2), x2 * y2};
  const double z2 = n[2] * n[2];
  const double planes = x2 * y2 + y2 * z2 + z2 * x2;
  return {x2 * x2 + y2 * y2 + z2 * z2 - 0.6, 4 * planes / 3,
          ((x2 - y2) * (x2 - y2) + (y2 - z2) * (y2 - z2) + (z2 - x2) * (z2 - x2)) / 3, planes};
}

/// |β| at most: the weights 1 + β c stay positive (|c| ≤ 1).
constexpr double max_anisotropy_weight = 0.5;

/// The Madenci–Oterkus constants of (M1) for a shear modulus μ (in 1D Young's modulus E): b(μ) and a_μ(μ) are
/// linear in μ.
struct Calibration {
  double a_kappa = 0;         ///< a_κ
  double a_mu_per_mu = 0;     ///< a_μ / μ
  double b_per_mu = 0;        ///< b / μ
  double d = 0;
};

/// In 2D κ is the in-plane bulk modulus of the deck's K with the glassy μ0 (plane stress 9Kμ0/(3K + 4μ0), plane
/// strain K + μ0/3): the plate's instantaneous response is the 3D material's. The in-plane κ of a 3D solid with
/// an elastic K and a relaxing μ would relax too; the model keeps it elastic (docs/algorithms.md §13).
Calibration calibration(const ElasticConstants& elastic, double mu_glassy, double delta, const Problem& problem) {
  constexpr double pi = std::numbers::pi;
  if (problem.dimension == 3)
    return {elastic.bulk_modulus / 2, 5.0 / 6.0, 15 / (2 * pi * std::pow(delta, 5)), 9 / (4 * pi * std::pow(delta, 4))};
  if (problem.dimension == 1)  // the paper's eq 7c: a bar of area A, W = b δ Σ |ξ| s² V = Eε²/2
    return {0, 0, 1 / (2 * std::pow(delta, 3) * problem.area), 1 / (2 * delta * delta * problem.area)};
  const double h = problem.thickness;
  ElasticConstants glassy = elastic;
  glassy.shear_modulus = mu_glassy;
  return {planar_bulk_modulus(glassy, problem.plane) / 2, 1.0, 6 / (pi * h * std::pow(delta, 4)),
          2 / (pi * h * std::pow(delta, 3))};
}

}  // namespace

Thermoviscoelastic::Params Thermoviscoelastic::resolve(const MaterialSpec& spec, const Problem& problem,
                                                       MaterialParams& block) {
  const std::string path = "materials." + spec.name;
  // The constants of (M1) hold for Ω = δ/|ξ| only (the paper's eq 6): ModelInfo::influence.
  PERIDOT_REQUIRE(block.influence == InfluenceKind::inverse_distance, "thermoviscoelastic: the deck sets Ω = δ/|ξ|");
  const double delta = block.horizon;
  // In 1D the relaxing modulus is Young's: a bar has neither shear nor bulk response of its own.
  const bool bar = problem.dimension == 1;
  const std::string modulus = bar ? "youngs_modulus" : "shear_modulus";
  const double mu_relaxed = bar ? spec.elastic.youngs_modulus : spec.elastic.shear_modulus;
  Params p;
  double mu_glassy = mu_relaxed;
  for (int k = 0;; ++k) {  // μ_k (E_k) into bond_modulus until the calibration below makes them b_k
    const std::string item = fmt::format("prony_series[{}].", k);
    if (!spec.parameters.has(item + modulus)) break;
    PERIDOT_REQUIRE(k < max_terms, "the deck check limits the Prony series to max_terms");
    p.bond_modulus[k] = spec.parameters.number(item + modulus);
    p.relaxation_time[k] = spec.parameters.number(item + "relaxation_time");
    mu_glassy += p.bond_modulus[k];
    p.terms = k + 1;
  }
  const Calibration c = calibration(spec.elastic, mu_glassy, delta, problem);
  for (int k = 0; k < p.terms; ++k) p.bond_modulus[k] *= c.b_per_mu;
  p.horizon = delta;
  p.dilatation_constant = c.d;
  p.bond_relaxed = c.b_per_mu * mu_relaxed;
  p.bond_glassy = c.b_per_mu * mu_glassy;
  p.volumetric = c.a_kappa;
  p.shear_ratio = c.a_mu_per_mu / c.b_per_mu;
  p.shear_modulus_relaxed = mu_relaxed;
  p.surface_correction = spec.parameters.boolean("surface_correction");
  p.second_order = spec.parameters.text("time_integration") == "second_order";
  if (spec.parameters.has("wlf.c1")) {
    if (!problem.temperature)
      throw InputError(spec.pos, path + ".wlf: the WLF shift needs a temperature field (a `temperature` section)");
    p.wlf = true;
    p.wlf_c1 = spec.parameters.number("wlf.c1");
    p.wlf_c2 = spec.parameters.number("wlf.c2");
    p.wlf_reference = spec.parameters.number("wlf.reference_temperature");
  }
  // The stable time step and the relaxation's density bound the stiffness of a PMB solid; the glassy shear
  // stiffness enters as the P-wave modulus K + 4μ0/3 in place of K.
  ElasticConstants glassy = spec.elastic;
  glassy.bulk_modulus = spec.elastic.bulk_modulus + 4 * mu_glassy / 3;
  glassy.shear_modulus = mu_glassy;
  if (bar) glassy.youngs_modulus = mu_glassy;
  block.stable_micromodulus = bond_based_micromodulus(glassy, delta, InfluenceKind::constant, problem);
  return p;
}

double Thermoviscoelastic::shift_factor(const Params& p, double temperature) {
  if (!p.wlf) return 1;
  const double above = temperature - p.wlf_reference;
  if (!(p.wlf_c2 + above > 0))
    throw NumericalError(fmt::format("thermoviscoelastic: temperature {:g} K is at or below T0 − c2 = {:g} K, where the "
                                     "WLF shift is undefined",
                                     temperature, p.wlf_reference - p.wlf_c2));
  return std::pow(10.0, -p.wlf_c1 * above / (p.wlf_c2 + above));
}

void Thermoviscoelastic::step_factors(const Params& p, double dt, double shift, std::array<double, max_terms>& decay,
                                      std::array<double, max_terms>& ramp) {
  for (int k = 0; k < p.terms; ++k) {
    const double x = dt / (shift * p.relaxation_time[k]);
    if (p.second_order) {
      decay[k] = 1 - x;
      ramp[k] = 0.5 * x;
    } else {
      decay[k] = std::exp(-x);
      ramp[k] = dt > 0 ? 1 + std::expm1(-x) / x : 0.0;  // 1 − (1 − ε)/x
    }
  }
}

// The surface correction (after Madenci & Oterkus 2016: each point's constants from its own family under simple
// loadings), with the sums of the reference family, n the dimension:
//   isotropic strain ε (s = ε): θ = nε exactly           → d = n/(δ Σ V);
//   isotropic strain: the distortional part of W vanishes → r = δ Σ |ξ| V / n²  (b δ Σ |ξ| ε² V = a_μ θ²);
//   simple shears ε_ab (s = 2ε n_a n_b, θ = 0), averaged over the planes (xy, yz, zx in 3D; xy in 2D):
//     W = 2μ ε² → b = μ P/(2δ Σ |ξ| Σ_planes n_a² n_b² V), P the number of planes; g = b/b(full family).
// A full family of the continuum gives d, r and b of (M1) exactly; an interior lattice point gets its lattice's,
// a point near a surface those of its truncated family. Only ghosts' θ is read, never their constants.
void Thermoviscoelastic::calibrate(ModelContext& ctx, const MaterialParams&, const Params& p, BlockRange range) {
  const int n = ctx.disc->dimension;
  const double* x = ctx.disc->x.data();
  const BondList& bonds = *ctx.bonds;
  const double delta = p.horizon, b_full = p.bond_relaxed / p.shear_modulus_relaxed;  // b per unit μ
  with_dimension(n, [&](auto dim) {
    constexpr int Dim = decltype(dim)::value;
#pragma omp parallel for schedule(static)
    for (std::size_t i = range.begin; i < range.end; ++i) {
      double volume = 0;
      // Σ w ξ V, Σ w ξ (Σ_planes n_a² n_b²) V and the two shears' Σ w ξ s² V / ε², each as the part without β
      // and the part β multiplies (w = 1 + β c).
      double length_moment[2] = {0, 0}, shear_moment[2] = {0, 0}, shear_xy[2] = {0, 0}, shear_xx_yy[2] = {0, 0};
      for (std::uint64_t b = bonds.offsets[i]; b < bonds.offsets[i + 1]; ++b) {
        if (bonds.broken[b]) continue;  // pre-cracked: the family the point has
        const std::uint32_t j = bonds.neighbors[b];
        const double xi = bond_length<Dim>(x, i, j), V = neighbor_volume(ctx, i, j, xi);
        double c[3] = {0, 0, 0};
        for (int a = 0; a < Dim; ++a) c[a] = (x[3 * j + a] - x[3 * i + a]) / xi;
        const LatticeShears shears = lattice_shears<Dim>(c);
        const double parts[2] = {xi * V, shears.harmonic * xi * V};
        volume += V;
        for (int k = 0; k < 2; ++k) {
          length_moment[k] += parts[k];
          shear_moment[k] += shears.planes * parts[k];
          shear_xy[k] += shears.xy * parts[k];
          shear_xx_yy[k] += shears.xx_yy * parts[k];
        }
      }
      double d = p.dilatation_constant, g = 1, r = p.shear_ratio, beta = 0;
      if (n == 1 && p.surface_correction && volume > 0) {
        // A bar: θ = ε and W = b δ Σ |ξ| ε² V = Eε²/2 under a uniform strain ε (no distortional split, r = 0).
        d = 1 / (delta * volume);
        g = 1 / (2 * delta * length_moment[0]) / b_full;
      } else if (p.surface_correction && volume > 0 && shear_moment[0] > 0) {
        // Both shears store the same energy: Σ (1 + β c) ξ (s_xy² − s_xx_yy²) V = 0.
        const double difference = shear_xy[1] - shear_xx_yy[1];
        if (std::abs(difference) > 1e-6 * shear_xy[0]) beta = (shear_xx_yy[0] - shear_xy[0]) / difference;
        beta = std::clamp(beta, -max_anisotropy_weight, max_anisotropy_weight);
        d = n / (delta * volume);
        r = delta * (length_moment[0] + beta * length_moment[1]) / (n * n);
        g = (Dim == 3 ? 3.0 : 1.0) / (2 * delta * (shear_moment[0] + beta * shear_moment[1])) / b_full;
      }
      ctx.point_constants[0][i] = d;
      ctx.point_constants[1][i] = g;
      ctx.point_constants[2][i] = r;
      ctx.point_constants[3][i] = beta;
    }
  });
}

namespace {

/// The shift factor of each point of the range at the context's temperature (1 without WLF), checked before any
/// parallel loop uses it (a NumericalError cannot leave an OpenMP loop).
std::vector<double> shift_factors(const ModelContext& ctx, const Thermoviscoelastic::Params& p, BlockRange range) {
  std::vector<double> shift(range.end - range.begin, 1.0);
  if (!p.wlf) return shift;
  PERIDOT_REQUIRE(ctx.temperature.size() >= range.end, "the WLF shift needs the temperature of the step (update_temperature)");
  for (std::size_t i = range.begin; i < range.end; ++i) {
    try {
      shift[i - range.begin] = Thermoviscoelastic::shift_factor(p, ctx.temperature[i]);
    } catch (const NumericalError& e) {
      const Vec3 x = ctx.disc->x.get(i);
      throw NumericalError(fmt::format("{} (point {} at ({:g}, {:g}, {:g}) m)", e.what(), ctx.disc->input_id[i], x.x, x.y, x.z));
    }
  }
  return shift;
}

/// Σ_k r g b_k θ^v_k and Σ_k r g b_k (θ^v_k)² of a point into point[3], point[4], θ^v_k = d × viscous_sum[k]:
/// the committed branches' part of the point energy (M5).
void store_branch_dilatations(MaterialHistory& history, std::size_t i, const Thermoviscoelastic::Params& p, double d,
                              double g, double r, const std::array<double, Thermoviscoelastic::max_terms>& viscous_sum) {
  double sum = 0, square_sum = 0;
  for (int k = 0; k < p.terms; ++k) {
    const double theta_v = d * viscous_sum[k];
    sum += r * g * p.bond_modulus[k] * theta_v;
    square_sum += r * g * p.bond_modulus[k] * theta_v * theta_v;
  }
  history.point[3][i] = sum;
  history.point[4][i] = square_sum;
}

}  // namespace

void Thermoviscoelastic::start_step(const ModelContext& ctx, MaterialHistory& history, const MaterialParams&,
                                    const Params& p, BlockRange range, double dt) {
  const double* x = ctx.disc->x.data();
  const BondList& bonds = *ctx.bonds;
  const int n = p.terms;
  const double* previous = history.bond[2].data();
  double* branch_force = history.bond[0].data();  // w A
  double* anisotropy = history.bond[1].data();    // w
  const std::vector<double> shift = shift_factors(ctx, p, range);
  with_dimension(ctx.disc->dimension, [&](auto dim) {
    constexpr int Dim = decltype(dim)::value;
#pragma omp parallel for schedule(static)
    for (std::size_t i = range.begin; i < range.end; ++i) {
      const double d = ctx.point_constants[0][i], g = ctx.point_constants[1][i], r = ctx.point_constants[2][i];
      const double beta = ctx.point_constants[3][i];
      std::array<double, max_terms> decay{}, ramp{};
      step_factors(p, dt, shift[i - range.begin], decay, ramp);
      std::array<double, max_terms> viscous_sum{};  // δ Σ e^v_k/|ξ| V
      double previous_sum = 0;                      // δ Σ e_n/|ξ| V
      double B = 0;
      for (int k = 0; k < n; ++k) B += p.bond_modulus[k] * ramp[k];
      for (std::uint64_t b = bonds.offsets[i]; b < bonds.offsets[i + 1]; ++b) {
        if (bonds.broken[b]) continue;
        const std::uint32_t j = bonds.neighbors[b];
        const double xi = bond_length<Dim>(x, i, j);
        const double weight = p.horizon / xi * neighbor_volume(ctx, i, j, xi);
        double w = 1;
        if (beta != 0) {
          double c[3] = {0, 0, 0};
          for (int a = 0; a < Dim; ++a) c[a] = (x[3 * j + a] - x[3 * i + a]) / xi;
          w = 1 + beta * lattice_shears<Dim>(c).harmonic;
        }
        double A = 0;
        for (int k = 0; k < n; ++k) {
          const double ev = history.bond[3 + k][b];
          A += p.bond_modulus[k] * (decay[k] * ev + (1 - decay[k] - ramp[k]) * previous[b]);
          viscous_sum[k] += weight * ev;
        }
        anisotropy[b] = w;
        branch_force[b] = w * g * A;
        previous_sum += weight * previous[b];
      }
      double A_i = 0;
      for (int k = 0; k < n; ++k)
        A_i += p.bond_modulus[k] * (decay[k] * d * viscous_sum[k] + (1 - decay[k] - ramp[k]) * d * previous_sum);
      store_branch_dilatations(history, i, p, d, g, r, viscous_sum);  // as commit leaves them (a history set otherwise too)
      history.point[0][i] = g * (p.bond_glassy - B);
      history.point[1][i] = d * (p.volumetric - r * g * p.bond_glassy) + r * d * g * B;
      history.point[2][i] = r * d * g * A_i;
    }
  });
}

void Thermoviscoelastic::commit(const ModelContext& ctx, const VectorField& u, const std::vector<double>&,
                                MaterialHistory& history, const MaterialParams&, const Params& p, BlockRange range,
                                double dt) {
  const double* x = ctx.disc->x.data();
  const double* up = u.data();
  const BondList& bonds = *ctx.bonds;
  const int n = p.terms;
  double* previous = history.bond[2].data();
  const double* anisotropy = history.bond[1].data();  // w, as start_step left it
  const std::vector<double> shift = shift_factors(ctx, p, range);
  with_dimension(ctx.disc->dimension, [&](auto dim) {
    constexpr int Dim = decltype(dim)::value;
#pragma omp parallel for schedule(static)
    for (std::size_t i = range.begin; i < range.end; ++i) {
      const double a_T = shift[i - range.begin];
      std::array<double, max_terms> decay{}, ramp{}, tau{};
      std::array<MaxwellStep, max_terms> maxwell{};
      step_factors(p, dt, a_T, decay, ramp);
      for (int k = 0; k < n; ++k) {
        tau[k] = a_T * p.relaxation_time[k];
        maxwell[k] = MaxwellStep(tau[k], dt);
      }
      // Per term: δ Σ (∫x²dt)/|ξ| V, δ Σ x_n/|ξ| V (x = e − e^v_k) and δ Σ e^v_k,n+1/|ξ| V; δ Σ ρ/|ξ| V.
      std::array<double, max_terms> square{}, spring_sum{}, viscous_sum{};
      double rate_sum = 0;
      for (std::uint64_t b = bonds.offsets[i]; b < bonds.offsets[i + 1]; ++b) {
        if (bonds.broken[b]) continue;
        const std::uint32_t j = bonds.neighbors[b];
        const BondGeometry<Dim> g = bond_geometry<Dim>(x, up, i, j);
        const double e = mechanical_extension(ctx, i, g);
        const double weight = p.horizon / g.xi * neighbor_volume(ctx, i, j, g.xi);
        const double rate = dt > 0 ? (e - previous[b]) / dt : 0.0;
        rate_sum += weight * rate;
        for (int k = 0; k < n; ++k) {
          double& ev = history.bond[3 + k][b];
          const double spring = previous[b] - ev;
          if (dt > 0) square[k] += anisotropy[b] * weight * maxwell[k].integral(rate, spring);
          spring_sum[k] += weight * spring;
          ev = decay[k] * ev + (1 - decay[k] - ramp[k]) * previous[b] + ramp[k] * e;  // (M3)
          viscous_sum[k] += weight * ev;
        }
        previous[b] = e;
      }
      const double d = ctx.point_constants[0][i], g = ctx.point_constants[1][i], r = ctx.point_constants[2][i];
      double dissipated = 0;
      for (int k = 0; k < n && dt > 0; ++k) {  // (M6): (2 g b_k/τ_k)[δ Σ ∫x²/|ξ| V − r ∫θ(x)² dt], θ(x) = d × the sums
        const double theta_square =
            maxwell[k].integral(d * rate_sum, d * spring_sum[k]);
        dissipated += 2 * g * p.bond_modulus[k] / tau[k] * (square[k] - r * theta_square);
      }
      history.dissipation[i] += dissipated;
      store_branch_dilatations(history, i, p, d, g, r, viscous_sum);
    }
  });
}

namespace {

void check(const MapReader& material, const Parameters& parameters, DeckContext& ctx) {
  int terms = 0;
  while (parameters.has(fmt::format("prony_series[{}].shear_modulus", terms)) ||
         parameters.has(fmt::format("prony_series[{}].youngs_modulus", terms)))
    ++terms;
  if (terms > Thermoviscoelastic::max_terms)
    ctx.error(material["prony_series"].pos, material.path_of("prony_series"),
              fmt::format("{} Prony terms given; at most {} are supported", terms, Thermoviscoelastic::max_terms));
}

}  // namespace

// The page of `peridot info --model thermoviscoelastic` (docs/models/thermoviscoelastic.md). The equations
// restate the header comment; keep them in step with the code.
ModelInfo Thermoviscoelastic::info() {
  ModelDoc doc{
    .summary = R"(The ordinary state-based thermoviscoelastic solid of Madenci & Oterkus: their strain energy density
with a dilatational and a distortional part, the influence function δ/|ξ|, and a shear modulus that relaxes
as a Prony series μ(t) = μ∞ + Σ μ_k exp(−t/τ_k) while the bulk modulus stays elastic. The deck's elastic
constants give the bulk modulus κ and the equilibrium (long-time) shear modulus μ∞; `prony_series` adds the
relaxing terms μ_k, τ_k, so that the instantaneous (glassy) shear modulus is μ0 = μ∞ + Σ μ_k. Relaxation
times follow the temperature field through the WLF shift, and every bond carries the thermal stretch
α(T − T_ref). Each Prony term keeps one viscous extension per bond, advanced by the exact integral of its
evolution equation over a step (unconditionally stable), or by the paper's second-order form.)",
    .equations = R"(Per point, with s = e/|ξ| the stretch of the mechanical extension e (thermal stretch removed):

- (M1) θ = d δ Σ s V, W = (a_κ − a_μ)θ² + b δ Σ |ξ| s² V, t = (2δ/|ξ|)[d(a_κ − a_μ)θ + b e];
  3D: a_κ = κ/2, a_μ = 5μ/6, b = 15μ/(2πδ⁵), d = 9/(4πδ⁴); 2D (thickness h): a_κ = κ/2, a_μ = μ,
  b = 6μ/(πhδ⁴), d = 2/(πhδ³), κ the in-plane bulk modulus (plane stress E/(2(1 − ν))). An isotropic strain
  ε gives θ = 3ε (2ε) and W = 9κε²/2 (2κε²), a simple shear ε_xy gives W = 2μ ε_xy², as the classical solid.
  1D (a bar of area A, the paper's eq 7c): a_κ = a_μ = 0, b = E/(2δ³A), d = 1/(2δ²A): W = b δ Σ |ξ| s² V = Eε²/2
  under a uniform strain ε. The bar has no shear: what relaxes is Young's modulus, E(t) = E∞ + Σ E_k exp(−t/τ_k),
  and everything below holds with E for μ and r = 0.
- (M2) t = (2δ/|ξ|)[d(a_κ − a_μ∞)θ + b∞ e + Σ_k b_k((e − e^v_k) − r d θ(e − e^v_k))], r = a_μ/b,
  θ(x) = d δ Σ (x/|ξ|) V, b_k and b∞ the b of μ_k and μ∞
- (M3) ė^v_k = (e − e^v_k)/τ_k; exactly for e linear over the step, ε_k = exp(−Δt/τ_k),
  β_k = 1 − (τ_k/Δt)(1 − ε_k): e^v_k ← ε_k e^v_k + (1 − ε_k − β_k) e_n + β_k e_{n+1};
  `time_integration: second_order` (the paper's eq 24b): ε_k = 1 − Δt/τ_k, β_k = Δt/(2τ_k)
- WLF: τ_k(T) = a_T τ_k, log₁₀ a_T = −c1(T − T0)/(c2 + T − T0)
- (M5) W = (a_κ − a_μ∞)θ² + b∞ δ Σ e²/|ξ| V + Σ_k [b_k δ Σ (e − e^v_k)²/|ξ| V − r b_k θ(e − e^v_k)²]
- (M6) dissipation Σ_k (2/τ_k) ∫ W_k dt, W_k the k-th bracket of (M5), integrated exactly over each step

The paper's viscous stretch γ_k is the distortional stretch of e^v_k, e^v_k/|ξ| − r d θ(e^v_k)/|ξ|; (M3)
mapped through it is the paper's eq 23 (or 24b), so this is the paper's model with a history that is local
to each bond.)",
    .restrictions = R"(- 1D (a bar: the deck's youngs_modulus is E∞, the Prony terms give youngs_modulus E_k), 2D and 3D.
- The influence function is δ/|ξ| whatever the deck says (another value given is an error).
- The surface correction is per point (isotropic strain, the simple shears, and a weight 1 + β c(n) per bond
  that gives the shears ε_xy and ε_xx = −ε_yy the same energy on the lattice: docs/algorithms.md §13). It makes
  interior lattice points exact for these strains, but a point near a free surface is loaded differently along
  and across the surface and keeps part of its error. The plane-stress plate of examples/viscoelastic_plate
  (60 × 30 points, δ = 3Δx, on a roller, pulled by the body force σ0/Δx on its last row) creeps 1.2 % less than
  the closed form (7.3 % without the lattice weight). The directional energy-method factors that pmb and lps have
  (`surface_correction` there, docs/algorithms.md §15) are not applied to this model.
- 2D: the in-plane bulk modulus is held at its glassy value (from K and μ0); for a 3D solid with an elastic K it
  would relax with μ.
- The bulk modulus does not relax; the thermal expansion coefficient does not depend on temperature.
- The distortional part of (M1) is an indefinite quadratic form of the bond extensions (a uniform extension
  of every bond of a family gives b δ Σ e²/|ξ| V − a_μ θ² < 0): stored energy and dissipation of a branch are
  non-negative for homogeneous deformations, not for every nonlocal state. This is a property of the paper's
  model.
- At most 20 Prony terms. Memory per bond: (terms + 3) × 8 bytes of history and 4 bytes of partner-bond index;
  three point fields exchanged after each step's start.
- The second-order update is stable only for Δt < 2 a_T τ_k of every term.
- Damage, when given, uses the mechanical stretch; θ is not recomputed for the bonds that break. The paper's
  energy-based bond failure (the work on a bond reaching G_c/N_c) is `damage: {fracture_energy: Gc, criterion:
  energy}` (docs/algorithms.md §14).)",
    .further_references = {"Madenci & Oterkus, Peridynamic Theory and Its Applications, Springer (2014)",
                           "Williams, Landel & Ferry, J. Am. Chem. Soc. 77 (1955) 3701-3707"},
    .example = R"(materials:
  epoxy:
    model: thermoviscoelastic
    density: 1810 kg/m^3
    bulk_modulus: 583 MPa
    shear_modulus: 269 MPa
    thermal_expansion: 5e-5 1/K
    prony_series:
      - {shear_modulus: 77 MPa, relaxation_time: 1e-4 s}
      - {shear_modulus: 308 MPa, relaxation_time: 1e-3 s}
      - {shear_modulus: 577 MPa, relaxation_time: 1e-2 s})",
  };
  return {.name = name,
          .description = "thermoviscoelastic ordinary state-based solid (Madenci-Oterkus): Prony shear, WLF",
          .reference = "Madenci & Oterkus, J. Mech. Phys. Solids (2017), thermoviscoelastic deformation",
          .keys = {{.key = "prony_series", .type = ValueType::sequence,
                    .description = "relaxing shear terms μ_k exp(−t/τ_k) (see materials.<name>.prony_series[i]); "
                                   "omit for an elastic solid"},
                   {.key = "time_integration", .type = ValueType::choice, .default_yaml = "exact",
                    .description = "update of the viscous extensions: exact (exponential integrator) or "
                                   "second_order (the paper's eq 24b)",
                    .choices = {"exact", "second_order"}},
                   {.key = "surface_correction", .type = ValueType::boolean, .default_yaml = "true",
                    .description = "each point's d, b, a_μ/b and lattice weight from its own family under isotropic "
                                   "strain and the shears (corrects truncated families at surfaces and the lattice's "
                                   "sums); false: the constants of a full continuous family"},
                   {.key = "wlf", .type = ValueType::mapping,
                    .description = "WLF shift of the relaxation times (see materials.<name>.wlf); needs a temperature field"},
                   thermal_expansion_key()},
          .sections = {{"materials.<name>.prony_series[i]", "one relaxing shear term",
                        {{.key = "shear_modulus", .unit = Unit::pressure, .range = positive,
                          .description = "μ_k (Pa)", .required = true, .one_of = "modulus", .min_dimension = 2},
                         {.key = "youngs_modulus", .unit = Unit::pressure, .range = positive,
                          .description = "E_k (Pa) of a bar", .required = true, .one_of = "modulus", .dimension = 1},
                         {.key = "relaxation_time", .unit = Unit::time, .range = positive,
                          .description = "τ_k (s) at the WLF reference temperature", .required = true}}},
                       {"materials.<name>.wlf", "Williams–Landel–Ferry shift a_T of every relaxation time",
                        {{.key = "c1", .range = positive, .description = "c1 (-)", .required = true},
                         {.key = "c2", .unit = Unit::temperature, .range = positive, .description = "c2 (K)", .required = true},
                         {.key = "reference_temperature", .unit = Unit::temperature, .range = positive,
                          .description = "T0 (K), where a_T = 1", .required = true}}}},
          .doc = doc,
          .one_dimensional = true,
          .influence = "inverse_distance",
          .check = check};
}

}  // namespace peridot
