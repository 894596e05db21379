#include "peridot/neighbor/quadrature.hpp"

#include <cmath>

#include "peridot/neighbor/influence.hpp"
#include "peridot/neighbor/neighborhood.hpp"

namespace peridot {

namespace {

/// ∫ n_x⁴ over the directions of the unit sphere (3D: 4π/5), circle (2D: 2π · 3/8) or the two of a line.
double direction_integral_of_nx4(int dimension) {
  if (dimension == 3) return 4.0 * M_PI / 5.0;
  if (dimension == 2) return 0.75 * M_PI;
  return 2.0;
}

/// ∫_0^δ ω(r) rᵖ r^(dim−1) dr by the midpoint rule on 20 000 intervals (ω is smooth inside the horizon; the
/// rule's error, below 1e-8 relative, is far under what the weights correct).
double radial_integral(const QuadratureLattice& q) {
  constexpr int intervals = 20000;
  const double h = q.horizon / intervals;
  double sum = 0;
  for (int k = 0; k < intervals; ++k) {
    const double r = (k + 0.5) * h;
    sum += influence(q.influence, r, q.horizon) * std::pow(r, q.moment_power + q.dimension - 1);
  }
  return sum * h;
}

}  // namespace

IsotropicQuadrature fit_isotropic_quadrature(const QuadratureLattice& q) {
  IsotropicQuadrature fit;
  fit.on = true;
  fit.offset = q.dimension == 3 ? 0.6 : q.dimension == 2 ? 0.75 : 1.0;
  const double reach = q.horizon + (q.bond_beyond_horizon ? q.partial_volume_radius : 0.0);
  const int n = static_cast<int>(std::ceil(reach / q.spacing));
  const int ny = q.dimension >= 2 ? n : 0, nz = q.dimension == 3 ? n : 0;
  const double cell = std::pow(q.spacing, q.dimension);
  // Sums over the family of W = ω ξᵖ (partial volume) V with D(n) = n_x⁴ − 3 n_x² n_y² (zero for an isotropic
  // fourth moment) and A(n): the fourth moment is isotropic when Σ W (1 + a A) D = 0.
  double s_d = 0, s_ad = 0, s_x4 = 0, s_ax4 = 0;
  for (int i = -n; i <= n; ++i)
    for (int j = -ny; j <= ny; ++j)
      for (int k = -nz; k <= nz; ++k) {
        if (i == 0 && j == 0 && k == 0) continue;
        const double d0 = i * q.spacing, d1 = j * q.spacing, d2 = k * q.spacing;
        const double xi = std::sqrt(d0 * d0 + d1 * d1 + d2 * d2);
        if (xi > reach) continue;
        const double pv = partial_volume_factor(xi, q.horizon, q.partial_volume_radius);
        if (pv <= 0) continue;
        const double w = influence(q.influence, xi, q.horizon) * std::pow(xi, q.moment_power) * pv * cell;
        const double n0 = d0 / xi, n1 = d1 / xi, n2 = d2 / xi;
        const double x4 = n0 * n0 * n0 * n0;
        const double a = x4 + n1 * n1 * n1 * n1 + n2 * n2 * n2 * n2 - fit.offset;
        const double d = x4 - 3.0 * n0 * n0 * n1 * n1;
        s_d += w * d, s_ad += w * a * d, s_x4 += w * x4, s_ax4 += w * a * x4;
      }
  fit.anisotropy = q.dimension >= 2 && s_ad != 0 ? -s_d / s_ad : 0.0;
  fit.scale = direction_integral_of_nx4(q.dimension) * radial_integral(q) / (s_x4 + fit.anisotropy * s_ax4);
  return fit;
}

}  // namespace peridot
