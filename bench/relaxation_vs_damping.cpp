// Adaptive dynamic relaxation against explicit dynamics with mass-proportional damping, on the same static
// problem: a 3D LPS bar (E = 200 GPa, ν = 0.3, ρ = 7800 kg/m³, δ = 3.015Δx with partial volumes), whose
// grips impose the classical field of uniaxial stress (ε = 1e-3). Both run until the relative force
// residual of solvers/dynamic_relaxation.hpp (‖F V‖ on the free dofs over the largest of the reaction,
// the body force and the starting residual) is at most --tolerance. Explicit: velocity Verlet at 0.8 ×
// the stable Δt, from rest with the grips displaced at t = 0, for several damping coefficients c, given
// as multiples of 2ω₁ (ω₁ = π c₀/L, c₀ = √(E/ρ): the bar's first axial mode, which the load excites).
// Prints one line per run: iterations or steps, seconds, residual.
//
//   relaxation_vs_damping [--n 60 15] [--tolerance 1e-8] [--damping 0.25,0.5,1,2] [--max-steps 200000]
#include <chrono>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <sstream>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "peridot/deck/deck.hpp"
#include "peridot/solvers/dynamic_relaxation.hpp"
#include "peridot/solvers/simulation.hpp"

namespace {

using namespace peridot;

constexpr double E = 200e9, nu = 0.3, rho = 7800, spacing = 1.5e-3, strain = 1e-3;

std::string bar_deck(int nx, int n, const std::string& solver) {
  const double L = nx * spacing, H = n * spacing, grip = 3 * spacing;
  return fmt::format(R"(discretization:
  dimension: 3
  spacing: {dx}
  horizon_factor: 3.015
  partial_volume: extended
  lattice_origin: [{x0}, {y0}, {y0}]
materials:
  steel: {{model: lps, density: {rho}, youngs_modulus: {E}, poisson_ratio: {nu}}}
bodies:
  bar: {{material: steel, shape: {{box: {{min: [{x0}, {y0}, {y0}], max: [{x1}, {y1}, {y1}]}}}}}}
node_sets:
  grips:
    shape:
      union:
        - box: {{min: [-1, -1, -1], max: [{gl}, 1, 1]}}
        - box: {{min: [{gr}, -1, -1], max: [1, 1, 1]}}
boundary_conditions:
  - {{node_set: grips, displacement: {{x: "{e} * x", y: "{c} * y", z: "{c} * z"}}}}
solver: {solver}
output: {{progress: false}}
)",
                     fmt::arg("dx", spacing), fmt::arg("x0", -L / 2), fmt::arg("y0", -H / 2), fmt::arg("x1", L / 2),
                     fmt::arg("y1", H / 2), fmt::arg("rho", rho), fmt::arg("E", E), fmt::arg("nu", nu),
                     fmt::arg("gl", -L / 2 + grip), fmt::arg("gr", L / 2 - grip), fmt::arg("e", strain),
                     fmt::arg("c", -nu * strain), fmt::arg("solver", solver));
}

/// The relaxation solver's relative residual for the current explicit state (its start norm given).
double residual(const Simulation& sim, double start, double* norm_out = nullptr) {
  const State& s = sim.state();
  const auto& kind = sim.loads().dof_kinds();
  const double* volume = sim.discretization().volume.data();
  double free = 0, reaction = 0;
  for (std::size_t k = 0; k < 3 * sim.num_owned(); ++k) {
    const double f = s.force.data()[k] * volume[k / 3];
    (kind[k] == DofKind::free ? free : reaction) += f * f;
  }
  if (norm_out) *norm_out = std::sqrt(free);
  const double reference = std::max(std::sqrt(reaction), start);
  return std::sqrt(free) / reference;
}

}  // namespace

int main(int argc, char** argv) {
  int nx = 60, n = 15;
  double tolerance = 1e-8;
  std::int64_t max_steps = 200000;
  std::vector<double> damping = {0.25, 0.5, 1, 2};
  for (int k = 1; k < argc; ++k) {
    const std::string a = argv[k];
    if (a == "--n") nx = std::stoi(argv[++k]), n = std::stoi(argv[++k]);
    else if (a == "--tolerance") tolerance = std::stod(argv[++k]);
    else if (a == "--max-steps") max_steps = std::stoll(argv[++k]);
    else if (a == "--damping") {
      damping.clear();
      std::istringstream list(argv[++k]);
      for (std::string item; std::getline(list, item, ',');) damping.push_back(std::stod(item));
    } else {
      std::fprintf(stderr, "usage: relaxation_vs_damping [--n NX N] [--tolerance T] [--damping a,b,…] [--max-steps S]\n");
      return 2;
    }
  }
  using Clock = std::chrono::steady_clock;
  {
    const Problem p = parse_deck(bar_deck(nx, n, fmt::format("{{type: relaxation, tolerance: {}}}", tolerance)), "bar.yaml", ".");
    Simulation sim(p);
    sim.initialize();
    const auto start = Clock::now();
    sim.step();
    const double seconds = std::chrono::duration<double>(Clock::now() - start).count();
    const auto& adr = dynamic_cast<const DynamicRelaxation&>(sim.integrator());
    std::printf("points %zu, tolerance %.0e\n", sim.discretization().num_points(), tolerance);
    std::printf("relaxation: %lld iterations, %.2f s, residual %.3e\n", static_cast<long long>(adr.iterations()),
                seconds, adr.residual());
  }
  const double L = nx * spacing, omega = std::numbers::pi / L * std::sqrt(E / rho);
  for (double factor : damping) {
    const double c = factor * 2 * omega;
    const Problem p = parse_deck(bar_deck(nx, n, fmt::format("{{num_steps: {}, damping: {}}}", max_steps, c)), "bar.yaml", ".");
    Simulation sim(p);
    sim.initialize();
    double start = 0;
    residual(sim, 0, &start);
    const auto t0 = Clock::now();
    double r = residual(sim, start);
    std::int64_t steps = 0;
    while (r > tolerance && steps < max_steps) {
      sim.step();
      ++steps;
      r = residual(sim, start);
    }
    const double seconds = std::chrono::duration<double>(Clock::now() - t0).count();
    std::printf("explicit, damping %.3g × 2ω₁ = %.4g 1/s: %lld steps, %.2f s, residual %.3e%s\n", factor, c,
                static_cast<long long>(steps), seconds, r, r > tolerance ? " (not converged)" : "");
  }
  return 0;
}
