#pragma once
// What every block's material has whatever its model, what a kernel may read, and the influence function.
// The models (materials/NAME.{hpp,cpp}, listed in materials/models.hpp) say what a bond force and a bond
// energy are; the bond loops that call them live in solvers/internal_force.cpp.
#include <cmath>
#include <limits>
#include <string_view>
#include <type_traits>
#include <vector>

#include "peridot/deck/problem.hpp"
#include "peridot/neighbor/influence.hpp"
#include "peridot/neighbor/quadrature.hpp"

namespace peridot {

/// What every block has, whatever its model, in SI units, computed once at set-up. The model's own
/// constants are its Params (materials/NAME.hpp), held beside these in ModelContext::model_params.
struct MaterialParams {
  int model = 0;  ///< index of the block's model in MaterialModels (materials/models.hpp)
  InfluenceKind influence = InfluenceKind::constant;
  int dimension = 3;
  double density = 0;  ///< ρ (kg/m³)
  double horizon = 0;  ///< δ (m)
  ElasticConstants elastic;
  /// α (1/K) of a model whose bonds carry thermal strain (thermal_expansion_key), 0 otherwise.
  double thermal_expansion = 0;
  /// The deck's `surface_correction` of a model that applies the energy method's bond factors
  /// (ModelBase::corrects_surfaces); false for the others.
  bool surface_correction = false;
  /// discretization.quadrature: isotropic: the direction weight of this block's bonds (neighbor/quadrature.hpp);
  /// off by default. The sums at a point use the weights of the point's own block.
  IsotropicQuadrature quadrature;
  /// Bond fails when its stretch exceeds this; +∞ without damage.
  double critical_stretch = std::numeric_limits<double>::infinity();
  /// Gc (J/m²) of the energy criterion (damage criterion: energy, damage/energy_failure.hpp), 0 without it;
  /// such a block has no critical stretch.
  double fracture_energy = 0;
  /// A correspondence law's damage breaks this block's bonds (johnson_cook_damage, coupling
  /// influence_function: correspondence/johnson_cook_damage.hpp), set by the model's resolve.
  bool damage_breaks_bonds = false;
  /// Constant PMB micromodulus of the same bulk response (18K/(πδ⁴) in 3D, 12K′/(πhδ³) in 2D), used by
  /// the Silling–Askari stable time step estimate and the relaxation's fictitious density; a model may
  /// raise it in its resolve (correspondence: the P-wave modulus and the hourglass springs).
  double stable_micromodulus = 0;
  /// Bond dashpot of the same sums (N s/m⁶), 0 unless the model has one (correspondence hourglass
  /// damping). It shortens the stable time step (stable_time_step in solvers/internal_force.hpp).
  double stable_damping = 0;
  /// Linear bulk viscosity C_l (-), 0 unless the model has one (correspondence): the damping ratio it gives
  /// the highest mode, which shortens the stable time step by √(1 + C_l²) − C_l (stable_time_step).
  double stable_bulk_viscosity = 0;
};

/// Most per-point and per-bond arrays a model may declare (static_assert in materials/models.hpp), and how many
/// of each the kernels see through KernelFields: the bond loops keep a private copy of KernelFields, which GCC
/// keeps in registers only while it is small (at 43 pointers the lps_plastic force loop ran 40 % slower). A
/// model with more bond arrays reads the rest through KernelFields::history.
inline constexpr int max_point_arrays = 8;
inline constexpr int max_bond_arrays = 24;
inline constexpr int kernel_bond_arrays = 4;
inline constexpr int kernel_point_constant_arrays = 4;

/// What a kernel may read besides its bond: per-point fields indexed by the point, per-bond history by
/// the bond of that point's family (the partner's bond through BondList::reverse). `point[k]` and
/// `bond[k]` are the arrays of MaterialHistory, whose meaning the point's own model declares
/// (point_arrays, bond_history_arrays); null where no model of the problem has them.
struct KernelFields {
  const double* theta = nullptr;        ///< θ
  const double* inverse_m = nullptr;    ///< 1/m
  /// α (T − T_ref) per point (ModelContext::thermal_stretch), null without: the kernels receive the
  /// extension less this stretch times ξ already; a model reads it only for what else it needs.
  const double* thermal_stretch = nullptr;
  /// The surface correction's factor G per bond (ModelContext::bond_scale), null without: the bond loops pass
  /// ω G as the influence; a model reads it only where it has its own influence (thermoviscoelastic).
  const double* bond_scale = nullptr;
  const double* point[max_point_arrays] = {};
  const double* bond[kernel_bond_arrays] = {};  ///< the history's first bond arrays
  /// ModelContext::point_constants[k] (point_constant_arrays), null where no model of the problem has them.
  const double* point_constant[kernel_point_constant_arrays] = {};
  /// All of the history (for the energy of a model with more bond arrays than `bond` holds); null without.
  const struct MaterialHistory* history = nullptr;
};

/// A per-point array a model declares: its name (for messages and restart) and its value before the first
/// step.
struct PointArray {
  std::string_view name;
  double initial = 0;
};

/// The PMB micromodulus c0 of the same response to isotropic strain (materials/pmb.hpp (4), (5)).
double bond_based_micromodulus(const ElasticConstants& c, double horizon, InfluenceKind influence, const Problem& problem);
/// The critical stretch s0 of a fracture energy G0 (J/m²): docs/models/pmb.md, damage (D1), (D2).
double critical_stretch_from_energy(double fracture_energy, const MaterialSpec& spec, double horizon,
                                    const Problem& problem);

/// The 2D bulk modulus K′ = λ′ + G of the in-plane problem: plane strain K + G/3, plane stress
/// 9KG/(3K + 4G) = E/(2(1 − ν)). (docs/algorithms.md §3)
double planar_bulk_modulus(const ElasticConstants& c, PlaneKind plane);

/// ∫₀^δ ω(ξ) ξ^p dξ in closed form, for the calibration of the constants (p = 2, 3, 4).
double influence_moment(InfluenceKind kind, double horizon, int p);

}  // namespace peridot
