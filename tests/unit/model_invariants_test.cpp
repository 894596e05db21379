// Analytic invariants every model must satisfy (docs/design.md, "Tests every model passes"): zero force under rigid motion, Σ f V = 0 and
// zero net moment, and f = −∂W/∂u by finite differences of the total strain energy. Run for PMB and
// LPS, in 3D and in 2D (plane stress and plane strain), for the three influence functions, the 1D bars of the
// models that have one (pmb, thermoviscoelastic), and for the
// inelastic models with a random history: f = −∂W/∂u on the elastic branch (lps_plastic below yield,
// lps_viscoelastic and thermoviscoelastic with no time elapsed), momentum also while every point flows
// plastically.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <tuple>

#include "peridot/geometry/discretize.hpp"
#include "peridot/neighbor/neighborhood.hpp"
#include "peridot/solvers/simulation.hpp"
#include "support/problems.hpp"

namespace peridot {
namespace {

using testing::BlockSetup;

struct Case {
  const char* name;
  int dimension;
  PlaneKind plane;
  std::string model;
  InfluenceKind influence;
  bool surface_correction = false;
};

BlockSetup setup_for(const Case& c, double yield_stress = 1e12) {
  BlockSetup s;
  s.parameters.set_number("yield_stress", yield_stress);  // each model takes the keys it has
  s.parameters.set_number("relaxing_fraction", 0.5);
  s.parameters.set_number("relaxation_time", 1e-5);
  if (c.model == "thermoviscoelastic")  // two Prony terms; the elastic constants give κ and μ∞ (E∞ in 1D)
    for (int k = 0; k < 2; ++k) {
      const std::string modulus = c.dimension == 1 ? "].youngs_modulus" : "].shear_modulus";
      s.parameters.set_number("prony_series[" + std::to_string(k) + modulus, 20e9 * (k + 1));
      s.parameters.set_number("prony_series[" + std::to_string(k) + "].relaxation_time", 1e-5 * (k + 1));
    }
  s.dimension = c.dimension;
  s.plane = c.plane;
  s.model = c.model;
  s.influence = c.influence;
  s.parameters.set_boolean("surface_correction", c.surface_correction);
  if (c.dimension == 3) s.cells[0] = s.cells[1] = s.cells[2] = 7;
  else if (c.dimension == 2) s.cells[0] = s.cells[1] = 12;
  else s.cells[0] = 30;
  s.jitter = 0.1;  // irregular points: no symmetry helps the sums cancel
  return s;
}

struct Forces {
  std::vector<double> theta, force_times_volume;
  double energy = 0;
};

// Internal force (times volume) and total strain energy for displacement u (the history is not committed).
Forces evaluate(Simulation& sim, const VectorField& u) {
  const ModelContext& ctx = sim.model();
  State& s = sim.state();
  start_step(ctx, s.history, 0.0);
  compute_dilatation(ctx, u, s.dilatation, false, &s.history);
  prepare_history(ctx, u, s.dilatation, s.history);
  compute_internal_force(ctx, u, s.dilatation, s.force, false, &s.history);
  std::vector<double> W;
  compute_strain_energy_density(ctx, u, s.dilatation, W, &s.history);
  Forces out;
  const auto& V = sim.discretization().volume;
  for (std::size_t i = 0; i < W.size(); ++i) out.energy += W[i] * V[i];
  for (std::size_t i = 0; i < W.size(); ++i)
    for (int d = 0; d < 3; ++d) out.force_times_volume.push_back(s.force(i, d) * V[i]);
  return out;
}

VectorField random_displacement(const Discretization& disc, double amplitude, std::uint64_t seed) {
  VectorField u(disc.num_points());
  for (std::size_t i = 0; i < disc.num_points(); ++i)
    for (int d = 0; d < disc.dimension; ++d) u(i, d) = amplitude * (2 * uniform01(seed) - 1);
  return u;
}

/// A random per-bond history of the size of a bond extension at 1e-3 strain (plastic extension; back
/// extension and last deviatoric extension), made deviatoric as the models keep it (Σ_j ω ξ h V_j = 0 at
/// every point: the flow rules preserve it exactly, and W's gradient relies on it).
void randomize_history(Simulation& sim, std::uint64_t seed, bool deviatoric = true) {
  const Discretization& disc = sim.discretization();
  const BondList& bonds = sim.bonds();
  const MaterialParams& p = sim.model().params[0];
  for (auto& array : sim.state().history.bond) {
    if (array.empty()) continue;
    for (double& value : array) value = 1e-3 * 1e-3 * (2 * uniform01(seed) - 1);
    if (!deviatoric) continue;
    for (std::size_t i = 0; i < disc.num_points(); ++i) {
      double along = 0, length_moment = 0;
      std::vector<double> xi;
      for (std::uint64_t b = bonds.offsets[i]; b < bonds.offsets[i + 1]; ++b) {
        const std::uint32_t j = bonds.neighbors[b];
        xi.push_back(norm(disc.x.get(j) - disc.x.get(i)));
        const double w = influence(p.influence, xi.back(), p.horizon) * xi.back() * disc.volume[j];
        along += w * array[b];
        length_moment += w * xi.back();
      }
      for (std::uint64_t b = bonds.offsets[i]; b < bonds.offsets[i + 1]; ++b) array[b] -= along / length_moment * xi[b - bonds.offsets[i]];
    }
  }
}

double max_abs(const std::vector<double>& v) {
  double m = 0;
  for (double x : v) m = std::max(m, std::abs(x));
  return m;
}

class ModelInvariants : public ::testing::TestWithParam<Case> {};

TEST_P(ModelInvariants, RigidMotionGivesZeroForce) {
  Simulation sim(testing::box_problem(setup_for(GetParam())));
  const Discretization& disc = sim.discretization();
  const int dim = disc.dimension;
  // Scale: the force a 1e-3 strain-sized random field produces.
  const double scale = max_abs(evaluate(sim, random_displacement(disc, 1e-3 * 1e-3, 7)).force_times_volume);

  VectorField translation(disc.num_points()), rotation(disc.num_points());
  const double angle = 0.3;  // a large rotation: the models are geometrically nonlinear
  for (std::size_t i = 0; i < disc.num_points(); ++i) {
    const Vec3 x = disc.x.get(i);
    for (int d = 0; d < dim; ++d) translation(i, d) = 2e-3 * (d + 1);
    // Rotation about z (and, in 3D, then about x): u = R x − x.
    Vec3 r{std::cos(angle) * x.x - std::sin(angle) * x.y, std::sin(angle) * x.x + std::cos(angle) * x.y, x.z};
    if (dim == 3) r = {r.x, std::cos(angle) * r.y - std::sin(angle) * r.z, std::sin(angle) * r.y + std::cos(angle) * r.z};
    if (dim >= 2) rotation.set(i, r - x);  // a bar's points have x only
  }
  EXPECT_LT(max_abs(evaluate(sim, translation).force_times_volume), 1e-9 * scale);
  EXPECT_LT(max_abs(evaluate(sim, rotation).force_times_volume), 1e-6 * scale);
}

TEST_P(ModelInvariants, LinearAndAngularMomentumAreConserved) {
  // A yield stress of 1 MPa: every lps_plastic point is on its yield surface, with its own return r.
  Simulation sim(testing::box_problem(setup_for(GetParam(), 1e6)));
  randomize_history(sim, 5);
  const Discretization& disc = sim.discretization();
  const VectorField u = random_displacement(disc, 0.05 * 1e-3, 11);
  const Forces f = evaluate(sim, u);
  Vec3 net, moment;
  double magnitude = 0, moment_scale = 0;
  for (std::size_t i = 0; i < disc.num_points(); ++i) {
    const Vec3 fi{f.force_times_volume[3 * i], f.force_times_volume[3 * i + 1], f.force_times_volume[3 * i + 2]};
    const Vec3 y = disc.x.get(i) + u.get(i);  // moment about the origin, deformed configuration
    net = net + fi;
    moment = moment + cross(y, fi);
    magnitude += norm(fi);
    moment_scale += norm(y) * norm(fi);
  }
  EXPECT_LT(norm(net), 1e-12 * magnitude);
  EXPECT_LT(norm(moment), 1e-12 * moment_scale);
  if (GetParam().model == "lps_plastic") {
    const auto& r = sim.state().history.point[LpsPlastic::yield_scale];
    EXPECT_LT(*std::max_element(r.begin(), r.end()), 1.0) << "every point should be flowing plastically";
  }
}

/// f = −∂W/∂u by central differences at interior, edge and corner points (every sort of family).
void expect_force_is_minus_energy_gradient(Simulation& sim) {
  const Discretization& disc = sim.discretization();
  const VectorField u = random_displacement(disc, 2e-3 * 1e-3, 13);
  const Forces f = evaluate(sim, u);
  const double h = 1e-6 * 1e-3;  // central difference step (m)
  const double scale = max_abs(f.force_times_volume);
  for (std::size_t i : {std::size_t{0}, disc.num_points() / 2, disc.num_points() / 3, disc.num_points() - 1}) {
    for (int d = 0; d < disc.dimension; ++d) {
      VectorField plus = u, minus = u;
      plus(i, d) += h;
      minus(i, d) -= h;
      const double gradient = (evaluate(sim, plus).energy - evaluate(sim, minus).energy) / (2 * h);
      EXPECT_NEAR(f.force_times_volume[3 * i + d], -gradient, 1e-6 * scale) << "point " << i << " component " << d;
    }
  }
}

TEST_P(ModelInvariants, ForceIsMinusEnergyGradient) {
  Simulation sim(testing::box_problem(setup_for(GetParam())));
  randomize_history(sim, 3);
  expect_force_is_minus_energy_gradient(sim);
}

// With broken bonds (both directions of a random tenth of the pairs) and an arbitrary, not deviatoric,
// history: pmb and lps_plastic keep f = −∂W/∂u on a damaged family (lps_plastic.hpp (P6)). lps and
// lps_viscoelastic do not: with m over all bonds and θ over the intact ones, Σ ω ξ e^d V ≠ 0 on a damaged
// family, and their force lacks the term −(α_d/m) q ω ξ that lps_plastic has (as in Peridigm; see their pages).
class DamagedModelInvariants : public ::testing::TestWithParam<Case> {};

TEST_P(DamagedModelInvariants, ForceIsMinusEnergyGradientWithBrokenBonds) {
  Simulation sim(testing::box_problem(setup_for(GetParam())));
  randomize_history(sim, 3, false);
  BondList& bonds = const_cast<BondList&>(sim.bonds());
  std::uint64_t seed = 99;
  for (std::size_t i = 0; i < bonds.offsets.size() - 1; ++i)
    for (std::uint64_t b = bonds.offsets[i]; b < bonds.offsets[i + 1]; ++b) {
      const std::uint32_t j = bonds.neighbors[b];
      if (j < i || uniform01(seed) > 0.1) continue;
      bonds.broken[b] = 1;
      for (std::uint64_t c = bonds.offsets[j]; c < bonds.offsets[j + 1]; ++c)
        if (bonds.neighbors[c] == i) bonds.broken[c] = 1;
    }
  expect_force_is_minus_energy_gradient(sim);
}

const Case cases[] = {
    {"Pmb3d", 3, PlaneKind::none, "pmb", InfluenceKind::constant},
    {"Pmb3dInverseDistance", 3, PlaneKind::none, "pmb", InfluenceKind::inverse_distance},
    {"Pmb2dPlaneStress", 2, PlaneKind::stress, "pmb", InfluenceKind::constant},
    {"Pmb2dPlaneStrainGaussian", 2, PlaneKind::strain, "pmb", InfluenceKind::gaussian},
    {"Lps3d", 3, PlaneKind::none, "lps", InfluenceKind::constant},
    {"Lps3dGaussian", 3, PlaneKind::none, "lps", InfluenceKind::gaussian},
    {"Lps2dPlaneStress", 2, PlaneKind::stress, "lps", InfluenceKind::constant},
    {"Lps2dPlaneStrainInverseDistance", 2, PlaneKind::strain, "lps", InfluenceKind::inverse_distance},
    {"Pmb3dSurfaceCorrection", 3, PlaneKind::none, "pmb", InfluenceKind::constant, true},
    {"Pmb2dPlaneStressSurfaceCorrection", 2, PlaneKind::stress, "pmb", InfluenceKind::gaussian, true},
    {"Lps3dSurfaceCorrection", 3, PlaneKind::none, "lps", InfluenceKind::inverse_distance, true},
    {"Lps2dPlaneStressSurfaceCorrection", 2, PlaneKind::stress, "lps", InfluenceKind::constant, true},
    {"LpsPlastic3d", 3, PlaneKind::none, "lps_plastic", InfluenceKind::constant},
    {"LpsPlastic3dInverseDistance", 3, PlaneKind::none, "lps_plastic", InfluenceKind::inverse_distance},
    {"LpsPlastic2dPlaneStressGaussian", 2, PlaneKind::stress, "lps_plastic", InfluenceKind::gaussian},
    {"LpsViscoelastic3dGaussian", 3, PlaneKind::none, "lps_viscoelastic", InfluenceKind::gaussian},
    {"LpsViscoelastic2dPlaneStrain", 2, PlaneKind::strain, "lps_viscoelastic", InfluenceKind::constant},
    {"Thermoviscoelastic3d", 3, PlaneKind::none, "thermoviscoelastic", InfluenceKind::inverse_distance},
    {"Thermoviscoelastic2dPlaneStress", 2, PlaneKind::stress, "thermoviscoelastic", InfluenceKind::inverse_distance},
    {"Pmb1d", 1, PlaneKind::none, "pmb", InfluenceKind::constant},
    {"Pmb1dGaussianSurfaceCorrection", 1, PlaneKind::none, "pmb", InfluenceKind::gaussian, true},
    {"Thermoviscoelastic1d", 1, PlaneKind::none, "thermoviscoelastic", InfluenceKind::inverse_distance},
    {"Thermoviscoelastic1dSurfaceCorrection", 1, PlaneKind::none, "thermoviscoelastic", InfluenceKind::inverse_distance,
     true},
};

INSTANTIATE_TEST_SUITE_P(AllModels, ModelInvariants, ::testing::ValuesIn(cases),
                         [](const ::testing::TestParamInfo<Case>& info) { return std::string(info.param.name); });

const Case damaged_cases[] = {
    {"Pmb3d", 3, PlaneKind::none, "pmb", InfluenceKind::constant},
    {"Pmb2dPlaneStrainGaussian", 2, PlaneKind::strain, "pmb", InfluenceKind::gaussian},
    {"Pmb1d", 1, PlaneKind::none, "pmb", InfluenceKind::constant},
    {"LpsPlastic3d", 3, PlaneKind::none, "lps_plastic", InfluenceKind::constant},
    {"LpsPlastic3dInverseDistance", 3, PlaneKind::none, "lps_plastic", InfluenceKind::inverse_distance},
    {"LpsPlastic2dPlaneStressGaussian", 2, PlaneKind::stress, "lps_plastic", InfluenceKind::gaussian},
};
INSTANTIATE_TEST_SUITE_P(ConservativeOnDamagedFamilies, DamagedModelInvariants, ::testing::ValuesIn(damaged_cases),
                         [](const ::testing::TestParamInfo<Case>& info) { return std::string(info.param.name); });

}  // namespace
}  // namespace peridot

namespace peridot {
namespace {

// Two bodies in contact, PMB (δ = 3.015Δx) beside LPS (δ = 2.2Δx), jittered: the interface bonds mix
// the two kernels (t_ij from i's model, t_ji from j's) and the pair horizon is the larger one. Momentum
// and f = −∂W/∂u must hold across the interface too.
TEST(ModelInvariantsTwoBlocks, InterfaceConservesMomentumAndIsConsistentWithEnergy) {
  testing::BlockSetup s;
  s.cells[0] = 10, s.cells[1] = 6, s.cells[2] = 6;
  s.jitter = 0.1;
  Problem p = testing::box_problem(s);
  MaterialSpec lps = p.materials[0];
  lps.name = "soft";
  lps.model = "lps";
  lps.influence = InfluenceKind::gaussian;
  lps.elastic = {50e9, 20e9, 9 * 50e9 * 20e9 / (150e9 + 20e9), (150e9 - 40e9) / (2 * (150e9 + 20e9))};
  p.materials[0].model = "pmb";
  p.materials[0].elastic.shear_modulus = 0.6 * p.materials[0].elastic.bulk_modulus;  // PMB: ν = 1/4
  p.materials.push_back(lps);
  BodySpec right = p.bodies[0];
  right.name = "right";
  right.material = "soft";
  right.horizon = 2.2 * s.spacing;
  right.shape = testing::box_shape({5e-3, 0, 0}, {10e-3, 6e-3, 6e-3});
  p.bodies[0].shape = testing::box_shape({0, 0, 0}, {5e-3, 6e-3, 6e-3});
  p.bodies.push_back(right);
  Simulation sim(p);
  ASSERT_EQ(sim.model().ranges.size(), 2u);
  // Both blocks have families across the interface: the loops look each point's same-block run up.
  EXPECT_EQ(sim.model().family_in_block, (std::vector<std::uint8_t>{0, 0}));
  const Discretization& disc = sim.discretization();
  const VectorField u = random_displacement(disc, 2e-3 * 1e-3, 17);
  const Forces f = evaluate(sim, u);
  Vec3 net;
  double magnitude = 0;
  for (std::size_t i = 0; i < disc.num_points(); ++i) {
    const Vec3 fi{f.force_times_volume[3 * i], f.force_times_volume[3 * i + 1], f.force_times_volume[3 * i + 2]};
    net = net + fi;
    magnitude += norm(fi);
  }
  EXPECT_LT(norm(net), 1e-12 * magnitude);
  // Points on both sides of the interface.
  const double h = 1e-9, scale = max_abs(f.force_times_volume);
  int checked = 0;
  for (std::size_t i = 0; i < disc.num_points() && checked < 6; ++i) {
    if (std::abs(disc.x(i, 0) - 5e-3) > 1.2e-3 || i % 3 != 0) continue;
    for (int d = 0; d < 3; ++d) {
      VectorField plus = u, minus = u;
      plus(i, d) += h;
      minus(i, d) -= h;
      const double gradient = (evaluate(sim, plus).energy - evaluate(sim, minus).energy) / (2 * h);
      EXPECT_NEAR(f.force_times_volume[3 * i + d], -gradient, 1e-6 * scale) << "point " << i << " component " << d;
    }
    ++checked;
  }
  EXPECT_EQ(checked, 6);
}

}  // namespace
}  // namespace peridot

namespace peridot {
namespace {

// A lattice block's points share one volume, and the PMB loop then broadcasts V_j instead of reading it
// (ModelContext::uniform_volume): the same value, so the same bits as reading it. One point's volume
// changed makes the block non-uniform.
TEST(UniformVolume, BroadcastVolumeGivesTheBitsOfTheReadVolume) {
  for (const InfluenceKind influence : {InfluenceKind::constant, InfluenceKind::inverse_distance}) {
    Simulation sim(testing::box_problem(setup_for({"Pmb3d", 3, PlaneKind::none, "pmb", influence})));
    ModelContext& ctx = const_cast<ModelContext&>(sim.model());
    const Discretization& disc = sim.discretization();
    ASSERT_EQ(ctx.uniform_volume.size(), 1u);
    EXPECT_EQ(ctx.uniform_volume[0], disc.volume[0]);
    EXPECT_EQ(ctx.family_in_block, (std::vector<std::uint8_t>{1}));  // one block: whole families
    BondList& bonds = const_cast<BondList&>(sim.bonds());
    for (std::uint64_t b = 0; b < bonds.num_bonds(); b += 7) bonds.broken[b] = 1;  // the masked lanes too
    const VectorField u = random_displacement(disc, 2e-3 * 1e-3, 23);
    const Forces broadcast = evaluate(sim, u);
    ctx.uniform_volume.clear();
    const Forces read = evaluate(sim, u);
    ASSERT_EQ(broadcast.force_times_volume.size(), read.force_times_volume.size());
    for (std::size_t k = 0; k < read.force_times_volume.size(); ++k)
      ASSERT_EQ(broadcast.force_times_volume[k], read.force_times_volume[k]) << "component " << k;

    const_cast<Discretization&>(disc).volume[disc.num_points() / 2] *= 1.5;
    calibrate_models(ctx);
    EXPECT_EQ(ctx.uniform_volume[0], 0.0);
  }
}

// The failure check in the force pass (the AVX-512 PMB loop lists a run's intact bonds and writes the flags
// of those that break through their places in the run): exactly the bonds that were broken or are now
// stretched past s0 are broken after it, and the force is that of those bonds left out.
TEST(BondFailureInForcePass, BreaksExactlyTheOverstretchedBondsAndTheyCarryNoForce) {
  for (const std::string model : {"pmb", "lps"}) {
    Simulation sim(testing::box_problem(setup_for({"", 3, PlaneKind::none, model, InfluenceKind::inverse_distance})));
    ModelContext& ctx = const_cast<ModelContext&>(sim.model());
    const Discretization& disc = sim.discretization();
    BondList& bonds = const_cast<BondList&>(sim.bonds());
    for (std::uint64_t b = 0; b < bonds.num_bonds(); b += 5) bonds.broken[b] = 1;
    const std::vector<std::uint8_t> before = bonds.broken;
    const VectorField u = random_displacement(disc, 2e-3 * 1e-3, 31);
    // s0 splits the stretches of the intact bonds about in half.
    std::vector<double> stretch(bonds.num_bonds());
    std::vector<double> intact;
    for (std::size_t i = 0; i < disc.num_points(); ++i)
      for (std::uint64_t b = bonds.offsets[i]; b < bonds.offsets[i + 1]; ++b) {
        const std::uint32_t j = bonds.neighbors[b];
        const double xi = norm(disc.x.get(j) - disc.x.get(i));
        stretch[b] = (norm(disc.x.get(j) + u.get(j) - disc.x.get(i) - u.get(i)) - xi) / xi;
        if (!before[b]) intact.push_back(stretch[b]);
      }
    std::nth_element(intact.begin(), intact.begin() + intact.size() / 2, intact.end());
    const double s0 = intact[intact.size() / 2];
    ctx.params[0].critical_stretch = s0;
    State& s = sim.state();
    if (model == "lps") compute_dilatation(ctx, u, s.dilatation, true, &s.history);
    compute_internal_force(ctx, u, s.dilatation, s.force, true, &s.history);
    std::uint64_t broke_now = 0;
    for (std::uint64_t b = 0; b < bonds.num_bonds(); ++b) {
      if (std::abs(stretch[b] - s0) < 1e-9 * std::abs(s0)) continue;  // round-off decides
      ASSERT_EQ(bonds.broken[b] != 0, before[b] != 0 || stretch[b] > s0) << "bond " << b;
      broke_now += bonds.broken[b] && !before[b];
    }
    EXPECT_GT(broke_now, bonds.num_bonds() / 5);
    const VectorField with_check = s.force;
    if (model == "lps") compute_dilatation(ctx, u, s.dilatation, false, &s.history);
    compute_internal_force(ctx, u, s.dilatation, s.force, false, &s.history);
    // Equal to round-off only: the AVX-512 PMB loop's lanes hold other bonds once the broken ones are left out.
    double scale = 0;
    for (std::size_t i = 0; i < disc.num_points(); ++i)
      for (int d = 0; d < 3; ++d) scale = std::max(scale, std::abs(s.force(i, d)));
    for (std::size_t i = 0; i < disc.num_points(); ++i)
      for (int d = 0; d < 3; ++d)
        ASSERT_NEAR(with_check(i, d), s.force(i, d), 1e-13 * scale) << "point " << i << " model " << model;
  }
}


// The LPS bond loops (AVX-512 in 3D where the machine has it) against the sums written out bond by bond:
// θ_i = (3/m_i) Σ ω ξ e V_j and f_i = Σ (t_ij + t_ji) V_j Y/|Y| over the intact bonds, t of Lps::force_scalar,
// with broken bonds (the lists of intact bonds), partial volumes (the volume factor) and one volume changed
// (V_j read, not broadcast), for both influences the loops take.
TEST(LpsBondLoops, DilatationAndForceMatchTheBondByBondSums) {
  for (const InfluenceKind influence : {InfluenceKind::constant, InfluenceKind::inverse_distance})
    for (const bool partial_volume : {false, true})
      for (const bool uniform_volume : {true, false}) {
        BlockSetup setup = setup_for({"", 3, PlaneKind::none, "lps", influence});
        setup.partial_volume = partial_volume;
        Simulation sim(testing::box_problem(setup));
        ModelContext& ctx = const_cast<ModelContext&>(sim.model());
        Discretization& disc = const_cast<Discretization&>(sim.discretization());
        if (!uniform_volume) {
          disc.volume[disc.num_points() / 2] *= 1.5;
          calibrate_models(ctx);
          ASSERT_EQ(ctx.uniform_volume[0], 0.0);
        }
        BondList& bonds = const_cast<BondList&>(sim.bonds());
        for (std::uint64_t b = 0; b < bonds.num_bonds(); b += 7) bonds.broken[b] = 1;
        const VectorField u = random_displacement(disc, 2e-3 * 1e-3, 41);
        State& s = sim.state();
        compute_dilatation(ctx, u, s.dilatation, false, &s.history);
        compute_internal_force(ctx, u, s.dilatation, s.force, false, &s.history);

        const MaterialParams& p = ctx.params[0];
        const Lps::Params& lps = ctx.model_params_of<Lps>(0);
        const std::size_t n = disc.num_points();
        const double r = ctx.partial_volume_radius;
        ASSERT_EQ(r > 0, partial_volume);
        struct Bond { double xi, e, omega, volume; Vec3 y; };
        auto bond = [&](std::size_t i, std::uint64_t b) {
          const std::uint32_t j = bonds.neighbors[b];
          Bond out;
          out.xi = norm(disc.x.get(j) - disc.x.get(i));
          out.y = disc.x.get(j) + u.get(j) - disc.x.get(i) - u.get(i);
          out.e = norm(out.y) - out.xi;
          out.omega = peridot::influence(p.influence, out.xi, p.horizon);
          out.volume = disc.volume[j] * partial_volume_factor(out.xi, p.horizon, r);
          return out;
        };
        std::vector<double> theta(n);
        double theta_scale = 0;
        for (std::size_t i = 0; i < n; ++i) {
          double sum = 0;
          for (std::uint64_t b = bonds.offsets[i]; b < bonds.offsets[i + 1]; ++b)
            if (!bonds.broken[b]) {
              const Bond g = bond(i, b);
              sum += g.omega * g.xi * g.e * g.volume;
            }
          theta[i] = 3 * sum * ctx.inverse_weighted_volume[i];
          theta_scale = std::max(theta_scale, std::abs(theta[i]));
        }
        for (std::size_t i = 0; i < n; ++i) ASSERT_NEAR(s.dilatation[i], theta[i], 1e-12 * theta_scale) << "point " << i;
        auto t = [&](std::size_t k, const Bond& g) {
          const double a = ctx.inverse_weighted_volume[k];
          return g.omega * a * (lps.alpha_volumetric * theta[k] * g.xi + lps.alpha_deviatoric * (g.e - theta[k] * g.xi / 3));
        };
        std::vector<Vec3> force(n);
        double force_scale = 0;
        for (std::size_t i = 0; i < n; ++i) {
          for (std::uint64_t b = bonds.offsets[i]; b < bonds.offsets[i + 1]; ++b)
            if (!bonds.broken[b]) {
              const Bond g = bond(i, b);
              force[i] = force[i] + ((t(i, g) + t(bonds.neighbors[b], g)) * g.volume / norm(g.y)) * g.y;
            }
          for (int d = 0; d < 3; ++d) force_scale = std::max(force_scale, std::abs(force[i][d]));
        }
        for (std::size_t i = 0; i < n; ++i)
          for (int d = 0; d < 3; ++d)
            ASSERT_NEAR(s.force(i, d), force[i][d], 1e-12 * force_scale)
                << "point " << i << " influence " << int(influence) << " partial " << partial_volume;
      }
}

}  // namespace
}  // namespace peridot
