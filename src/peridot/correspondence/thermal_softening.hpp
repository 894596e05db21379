#pragma once
// Adiabatic heating with Johnson–Cook thermal softening, shared by the laws that offer it (j2_viscoplastic,
// johnson_cook; the deck section materials.<name>.thermal_softening): the flow stress is multiplied by
//   Θ(T) = 1 − T*^q,  T* = (T − T_r)/(T_m − T_r) clamped to [0, 1],
// and the point heats by the plastic work it dissipates, ΔT += β σ_y Δεp/(ρ c), with no conduction (an impact is
// over long before heat diffuses a horizon). The laws use T of the step before (explicit in temperature).
#include <algorithm>
#include <cmath>

#include "peridot/deck/problem.hpp"

namespace peridot::correspondence {

struct ThermalSoftening {
  bool enabled = false;
  double specific_heat = 0;          ///< c (J/(kg K))
  double reference_temperature = 0;  ///< T_r (K), the initial temperature
  double melting_temperature = 0;    ///< T_m (K)
  double exponent = 1;               ///< q (-)
  double taylor_quinney = 0.9;       ///< β (-)

  /// T* (-) of a point heated by `temperature_rise` (K) above T_r; 0 when off.
  double homologous(double temperature_rise) const {
    if (!enabled) return 0;
    return std::clamp(temperature_rise / (melting_temperature - reference_temperature), 0.0, 1.0);
  }
  /// Θ (-): 1 when off, 0 at and above melting.
  double factor(double temperature_rise) const {
    return enabled ? 1 - std::pow(homologous(temperature_rise), exponent) : 1.0;
  }
  /// The section of a material's parameters; off when the material has none.
  static ThermalSoftening from_parameters(const Parameters& q) {
    ThermalSoftening t;
    if (!q.has("thermal_softening.taylor_quinney_coefficient")) return t;  // defaulted: there when the section is
    t.enabled = true;
    t.specific_heat = q.number("thermal_softening.specific_heat");
    t.reference_temperature = q.number("thermal_softening.reference_temperature");
    t.melting_temperature = q.number("thermal_softening.melting_temperature");
    t.exponent = q.number("thermal_softening.exponent");
    t.taylor_quinney = q.number("thermal_softening.taylor_quinney_coefficient");
    return t;
  }
  /// The temperature rise (K) of plastic work σ_y Δεp per volume at density ρ.
  double heating(double flow_stress, double eqps_increment, double density) const {
    return enabled ? taylor_quinney * flow_stress * eqps_increment / (density * specific_heat) : 0.0;
  }
};

}  // namespace peridot::correspondence
