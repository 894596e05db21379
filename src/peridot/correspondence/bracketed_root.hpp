#pragma once
// Brent's method for a root of a scalar function bracketed by [a, b] (f(a) and f(b) of opposite signs):
// inverse quadratic interpolation or secant steps when they stay inside the bracket and shrink it fast
// enough, bisection otherwise, so convergence is guaranteed (Brent, "Algorithms for Minimization without
// Derivatives", 1973, ch. 4). Foster, Silling & Chen (2010) §6 suggest it for Δλ of eq 48/60, where the
// residual is monotone but Newton's method can fail.
#include <cmath>
#include <limits>
#include <utility>

namespace peridot::correspondence {

struct RootResult {
  double x = std::numeric_limits<double>::quiet_NaN();
  bool converged = false;
  int evaluations = 0;  ///< calls of f, beyond the two end values given
};

/// Root of f in [a, b] to within x_tolerance (same unit as x), given fa = f(a), fb = f(b) of opposite signs
/// (or one of them zero). Returns converged = false (x = NaN) when the root is not bracketed.
template <class Function>
RootResult brent_root(Function&& f, double a, double b, double fa, double fb, double x_tolerance,
                      int max_evaluations = 200) {
  RootResult result;
  if (fa == 0) return {a, true, 0};
  if (fb == 0) return {b, true, 0};
  if ((fa > 0) == (fb > 0) || !std::isfinite(fa) || !std::isfinite(fb)) return result;
  constexpr double eps = std::numeric_limits<double>::epsilon();
  // b: best estimate; a: previous b; c: the other end of the bracket [b, c].
  double c = a, fc = fa;
  double step = b - a, previous_step = step;
  for (int k = 0; k <= max_evaluations; ++k) {
    if ((fb > 0) == (fc > 0)) {  // keep the root between b and c
      c = a;
      fc = fa;
      step = previous_step = b - a;
    }
    if (std::abs(fc) < std::abs(fb)) {  // b must be the better end
      a = b;
      b = c;
      c = a;
      fa = fb;
      fb = fc;
      fc = fa;
    }
    const double tol = 2 * eps * std::abs(b) + 0.5 * x_tolerance;
    const double half = 0.5 * (c - b);
    if (std::abs(half) <= tol || fb == 0) return {b, true, k};
    if (k == max_evaluations) break;
    if (std::abs(previous_step) >= tol && std::abs(fa) > std::abs(fb)) {
      double p, q;
      const double s = fb / fa;
      if (a == c) {  // two points: secant
        p = 2 * half * s;
        q = 1 - s;
      } else {  // three points: inverse quadratic interpolation
        const double qa = fa / fc, r = fb / fc;
        p = s * (2 * half * qa * (qa - r) - (b - a) * (r - 1));
        q = (qa - 1) * (r - 1) * (s - 1);
      }
      if (p > 0) q = -q;
      p = std::abs(p);
      // Accept the interpolation only when it lands well inside the bracket and shrinks faster than
      // half the step before last; otherwise bisect.
      if (2 * p < std::min(3 * half * q - std::abs(tol * q), std::abs(previous_step * q))) {
        previous_step = step;
        step = p / q;
      } else {
        step = half;
        previous_step = step;
      }
    } else {
      step = half;
      previous_step = step;
    }
    a = b;
    fa = fb;
    b += std::abs(step) > tol ? step : std::copysign(tol, half);
    fb = f(b);
  }
  result.evaluations = max_evaluations;
  return result;
}

}  // namespace peridot::correspondence
