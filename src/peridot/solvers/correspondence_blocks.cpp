// The correspondence blocks inside the explicit solver: set-up from the resolved materials, the per-step
// kinematics → stress → force sequence, and the energy and field outputs (correspondence_blocks.hpp).
#include "peridot/solvers/correspondence_blocks.hpp"

#include <algorithm>
#include <cmath>
#include <exception>
#include <string>
#include <utility>
#include <variant>

#include <fmt/format.h>

#include "peridot/correspondence/force.hpp"
#include "peridot/correspondence/kinematics.hpp"
#include "peridot/correspondence/laws.hpp"
#include "peridot/materials/models.hpp"
#include "peridot/solvers/simulation.hpp"

namespace peridot {

using namespace correspondence;

namespace {

/// One block type per listed law (correspondence/laws.hpp).
template <class>
struct BlocksOf;
template <class... Laws>
struct BlocksOf<std::variant<Laws...>> {
  using type = std::variant<CorrespondenceBlock<Laws>...>;
};
using AnyBlock = BlocksOf<AnyLaw>::type;

AnyBlock make_block(const CorrespondenceModel::Params& p, BlockRange range) {
  return std::visit([&](const auto& law) -> AnyBlock { return CorrespondenceBlock<std::decay_t<decltype(law)>>(law, range); },
                    p.law);
}

/// Refuses a bond between a correspondence block and a block of another model (see the header).
void check_interfaces(const Problem& problem, const ModelContext& model) {
  const Discretization& disc = *model.disc;
  const BondList& bonds = *model.bonds;
  for (std::size_t b = 0; b < model.ranges.size(); ++b) {
    if (!is_model<CorrespondenceModel>(model.params[b])) continue;
    for (std::size_t i = model.ranges[b].begin; i < model.ranges[b].end; ++i)
      for (std::uint64_t k = bonds.offsets[i]; k < bonds.offsets[i + 1]; ++k) {
        const std::size_t other = static_cast<std::size_t>(disc.block[bonds.neighbors[k]]);
        if (is_model<CorrespondenceModel>(model.params[other])) continue;
        const BodySpec& body = problem.bodies[b];
        throw InputError(body.pos, fmt::format(
            "bodies.{}: this correspondence body is bonded to body '{}' (material {}, model {}), at its point "
            "({:g}, {:g}, {:g}) m; "
            "bonds between a correspondence body and a body of another model are not supported: keep the bodies "
            "more than a horizon apart or give both the correspondence model",
            body.name, problem.bodies[other].name, problem.material_of(problem.bodies[other]).name,
            model_name(model.params[other].model), disc.x(i, 0),
            disc.x(i, 1), disc.x(i, 2)));
      }
  }
}

// Symmetric tensors in the order of correspondence_output_names(): xx yy zz xy yz zx.
const int symmetric_index[6][2] = {{0, 0}, {1, 1}, {2, 2}, {0, 1}, {1, 2}, {2, 0}};

}  // namespace

struct CorrespondenceBlocks::Impl {
  const ModelContext* model = nullptr;
  CorrespondenceContext ctx;
  KinematicFields kin;
  StressFields stress;     ///< the last evaluate(): trial R, V, τ, and σ and P K⁻¹ (what the force reads)
  StressFields committed;  ///< R, V, τ at the last commit() (σ and P K⁻¹ left empty)
  std::vector<double> inelastic_work;  ///< per point: ΔW_in of the last evaluate() (J/m³)
  std::vector<AnyBlock> blocks;
  std::vector<std::size_t> block_index;  ///< the ModelContext block of each entry of `blocks`
  const Halo* halo = nullptr;
  VectorField hourglass_force, previous_hourglass_force, previous_u;
  bool have_previous = false;
  std::vector<double> hourglass_work;  ///< per point (J)
  bool damped = false;                 ///< some block has hourglass damping: the gather reads partners' Ḟ
  VectorField mirror_force;            ///< per point: the force density of its mirror bonds (N/m³)
  Communicator comm;                   ///< the ranks that share the symmetry planes' release decision
  std::size_t owned = 0;               ///< this rank's points (the ghosts follow)
  // Damage through the influence function (johnson_cook_damage.hpp); empty without it.
  bool bond_damage = false;
  std::vector<double> undamaged_weight;          ///< per bond: ω V_j of the context before any damage
  std::vector<double> undamaged_mirror_weight;   ///< per mirror bond: ω_i, ω_j
  std::vector<double> undamaged_mirror_partner;
  std::vector<double> point_damage;              ///< per point (owned and ghost): D acting on the bonds

  void update_damaged_bonds(double* dissipation);
};

CorrespondenceBlocks::CorrespondenceBlocks(const Problem& problem, const ModelContext& model, const Halo* halo,
                                           Communicator comm)
    : impl_(std::make_unique<Impl>()) {
  Impl& m = *impl_;
  m.model = &model;
  m.halo = halo;
  m.comm = comm;
  m.owned = model.ranges.empty() ? 0 : model.ranges.back().end;
  std::vector<BlockGeometry> geometry;
  for (std::size_t b = 0; b < model.params.size(); ++b) {
    const MaterialParams& p = model.params[b];
    geometry.push_back({p.horizon, p.influence});
    // A block with no point on this rank still takes part: its ghosts' exchange is collective.
    if (!is_model<CorrespondenceModel>(p)) continue;
    m.blocks.push_back(make_block(model.model_params_of<CorrespondenceModel>(b), model.ranges[b]));
    m.block_index.push_back(b);
  }
  if (m.blocks.empty()) return;
  check_interfaces(problem, model);
  const std::size_t n = model.disc->num_points();
  m.ctx = make_correspondence_context(*model.disc, *model.bonds, geometry, model.partial_volume_radius);
  for (std::size_t b : m.block_index) {
    const MaterialParams& p = model.params[b];
    const CorrespondenceModel::Params& own = model.model_params_of<CorrespondenceModel>(b);
    m.ctx.hourglass_stiffness[b] = hourglass_stiffness(own.hourglass_coefficient, p.elastic.bulk_modulus, p.horizon);
    m.ctx.hourglass_damping[b] = p.stable_damping;  // hourglass_damping(C_HV, ρ, K, δ): CorrespondenceModel::resolve
    const double wave_speed = std::sqrt((p.elastic.bulk_modulus + 4 * p.elastic.shear_modulus / 3) / p.density);
    m.ctx.bulk_viscosity_linear[b] = own.bulk_viscosity_linear * p.density * wave_speed;
    m.ctx.bulk_viscosity_quadratic[b] = own.bulk_viscosity_quadratic * p.density;
  }
  // Symmetry planes (mirror_bonds.hpp): the walls with contact: symmetry (check_symmetry_walls has
  // vetted them).
  std::vector<MirrorPlane> planes;
  for (std::size_t w = 0; w < problem.rigid_walls.size(); ++w)
    if (problem.rigid_walls[w].contact == WallContactKind::symmetry)
      planes.push_back({problem.rigid_walls[w].point, problem.rigid_walls[w].normal, w, true, {}});
  if (!planes.empty()) {
    MirrorBondOptions options;
    for (const MaterialParams& p : model.params) {
      options.horizon_of_block.push_back(p.horizon);
      options.influence_of_block.push_back(p.influence);
      options.block_is_mirrored.push_back(is_model<CorrespondenceModel>(p) ? 1 : 0);
    }
    options.partial_volume_radius = model.partial_volume_radius;
    options.bond_beyond_horizon = problem.partial_volume == PartialVolumeKind::extended;
    m.ctx.mirror = build_mirror_bonds(*model.disc, *model.bonds, m.owned, planes, options);
    // Distributed, a block touches a plane if it does on some rank; the planes stay active on every rank
    // even where this rank has no mirror bonds, so that every rank takes part in the release decision.
    for (MirrorPlane& plane : m.ctx.mirror.planes)
      for (std::uint8_t& touches : plane.block_touches) touches = m.comm.any(touches != 0) ? 1 : 0;
    m.ctx.mirror.active = true;
    m.mirror_force.resize(n);
  }
  m.damped = std::any_of(m.ctx.hourglass_damping.begin(), m.ctx.hourglass_damping.end(), [](double c) { return c != 0; });
  m.stress.resize(n);
  // Only R, V and τ are committed: σ and P K⁻¹ follow from them in every evaluate().
  m.committed.rotation.assign(n, Mat3::Identity());
  m.committed.left_stretch.assign(n, Mat3::Identity());
  m.committed.unrotated_stress.assign(n, Mat3::Zero());
  m.inelastic_work.assign(n, 0.0);
  m.kin.shape_inverse = TensorField(n);
  m.kin.deformation_gradient.assign(n, Mat3::Identity());
  m.kin.deformation_gradient_rate = TensorField(n);
  m.hourglass_force.resize(n);
  m.previous_hourglass_force.resize(n);
  m.hourglass_work.assign(n, 0.0);
  m.bond_damage = std::any_of(m.block_index.begin(), m.block_index.end(),
                              [&](std::size_t b) { return model.params[b].damage_breaks_bonds; });
  if (m.bond_damage) {
    m.undamaged_weight = m.ctx.weighted_volume;
    m.undamaged_mirror_weight = m.ctx.mirror.weight;
    m.undamaged_mirror_partner = m.ctx.mirror.partner_weight;
    m.ctx.bond_integrity.assign(m.ctx.weighted_volume.size(), 1.0);
    m.ctx.failed_point.assign(n, 0);
    m.point_damage.assign(n, 0.0);
  }
}

// The bonds after a commit, from the committed damage (johnson_cook_damage.hpp): every bond i–j of a block
// whose law degrades bonds gets ω0 (1 − max(D_i, D_j)) and breaks when that is 0; a point whose remaining
// family can no longer form K (fewer than three non-coplanar bonds of weight) fails too (D = 1, all its bonds
// break), repeated until no point fails: the failure of one point may isolate the next. A point that fails
// releases its stored elastic energy, which is added to `dissipation` (null: not counted, at a restore), and
// its stress is zeroed. Bonds touching a no_fail point keep their weight. Collective: the ghosts' damage is
// exchanged, and every rank repeats while one has a new failure.
void CorrespondenceBlocks::Impl::update_damaged_bonds(double* dissipation) {
  BondList& bonds = *model->bonds;
  const std::vector<std::uint8_t>& no_fail = model->no_fail;
  std::fill(point_damage.begin(), point_damage.end(), 0.0);
  for (const AnyBlock& any : blocks)
    std::visit([&](const auto& block) {
      if constexpr (requires { block.law.damage.degrades_bonds(); block.history[0].damage; })
        if (block.law.damage.degrades_bonds())
          for (std::size_t i = block.range.begin; i < block.range.end; ++i)
            point_damage[i] = block.history[i - block.range.begin].damage;
    }, any);
  const auto protected_point = [&](std::size_t i) { return !no_fail.empty() && no_fail[i] != 0; };
  while (true) {
    if (halo) halo->exchange(point_damage);
    for (const AnyBlock& any : blocks) {
      const BlockRange range = std::visit([](const auto& block) { return block.range; }, any);
#pragma omp parallel for schedule(static)
      for (std::size_t i = range.begin; i < range.end; ++i) {
        ctx.failed_point[i] = point_damage[i] >= 1 && !protected_point(i) ? 1 : 0;
        for (std::uint64_t b = bonds.offsets[i]; b < bonds.offsets[i + 1]; ++b) {
          const std::size_t j = bonds.neighbors[b];
          const double integrity = protected_point(i) || protected_point(j)
                                       ? 1.0
                                       : 1 - std::max(point_damage[i], point_damage[j]);
          if (!(integrity > 0)) bonds.broken[b] = 1;
          ctx.bond_integrity[b] = bonds.broken[b] ? 0.0 : integrity;
          ctx.weighted_volume[b] = undamaged_weight[b] * ctx.bond_integrity[b];
        }
        MirrorBonds& mirror = ctx.mirror;
        if (!mirror.offsets.empty())
          for (std::uint64_t b = mirror.offsets[i]; b < mirror.offsets[i + 1]; ++b) {
            const double integrity = 1 - std::max(point_damage[i], point_damage[mirror.source[b]]);
            mirror.weight[b] = undamaged_mirror_weight[b] * std::max(integrity, 0.0);
            mirror.partner_weight[b] = undamaged_mirror_partner[b] * std::max(integrity, 0.0);
          }
      }
    }
    // Points whose family can no longer form K.
    std::vector<std::size_t> isolated;
    for (const AnyBlock& any : blocks)
      std::visit([&](const auto& block) {
        if constexpr (requires { block.law.damage.degrades_bonds(); })
          if (block.law.damage.degrades_bonds())
            for (std::size_t i = block.range.begin; i < block.range.end; ++i)
              if (!ctx.failed_point[i] && !protected_point(i) && !shape_tensor_well_conditioned(ctx, i)) isolated.push_back(i);
      }, any);
    for (std::size_t i : isolated) point_damage[i] = 1;
    for (AnyBlock& any : blocks)
      std::visit([&](auto& block) {
        if constexpr (requires { block.history[0].damage; })
          for (std::size_t i : isolated)
            if (i >= block.range.begin && i < block.range.end) block.history[i - block.range.begin].damage = 1;
      }, any);
    if (!comm.any(!isolated.empty())) break;
  }
  // Newly failed points: their stored energy is released, their stress gone.
  for (std::size_t k = 0; k < blocks.size(); ++k)
    std::visit([&](const auto& block) {
      const MaterialParams& p = model->params[block_index[k]];
      for (std::size_t i = block.range.begin; i < block.range.end; ++i) {
        if (!ctx.failed_point[i] || committed.unrotated_stress.get(i).isZero(0.0)) continue;
        const double released = elastic_energy_density(committed.unrotated_stress.get(i),
                                                       kin.deformation_gradient.get(i).determinant(),
                                                       p.elastic.bulk_modulus, p.elastic.shear_modulus);
        if (dissipation) dissipation[i] += released;
        committed.unrotated_stress.set(i, Mat3::Zero());
      }
    }, blocks[k]);
}

CorrespondenceBlocks::~CorrespondenceBlocks() = default;

void CorrespondenceBlocks::restored() {
  if (impl_->bond_damage) impl_->update_damaged_bonds(nullptr);
}

bool CorrespondenceBlocks::empty() const { return impl_->blocks.empty(); }

void CorrespondenceBlocks::evaluate(const VectorField& u, const VectorField& v, double dt, VectorField& f) {
  Impl& m = *impl_;
  std::exception_ptr failure;
  try {
    for (AnyBlock& any : m.blocks)
      std::visit([&](auto& block) { compute_kinematics(m.ctx, u, v, m.kin, block.range); }, any);
    for (AnyBlock& any : m.blocks)
      std::visit([&](auto& block) {
        trial_block_stress(m.ctx, m.kin, dt, block, m.committed, m.stress, m.inelastic_work.data());
      }, any);
  } catch (const NumericalError&) {
    failure = std::current_exception();  // after the exchange: the other ranks wait for this rank's messages
  }
  if (m.halo) {  // what the gather reads of a ghost partner
    m.halo->exchange(m.stress.force_tensor.data(), 9);
    m.halo->exchange(m.kin.deformation_gradient.data(), 9);
    if (m.damped) m.halo->exchange(m.kin.deformation_gradient_rate.data(), 9);
  }
  if (failure) std::rethrow_exception(failure);
  for (AnyBlock& any : m.blocks)
    std::visit([&](auto& block) {
      compute_correspondence_force(m.ctx, m.kin, m.stress, u, v, f, block.range, &m.hourglass_force,
                                   m.ctx.mirror.planes.empty() ? nullptr : &m.mirror_force);
    }, any);
}

void CorrespondenceBlocks::commit(const VectorField& u, const VectorField& v, MaterialHistory& history) {
  Impl& m = *impl_;
  // The trial R, V, τ become the committed ones; the stale values left in m.stress are overwritten at
  // every point of every block by the next evaluate(), before anything reads them.
  std::swap(m.committed.rotation, m.stress.rotation);
  std::swap(m.committed.left_stretch, m.stress.left_stretch);
  std::swap(m.committed.unrotated_stress, m.stress.unrotated_stress);
  double* dissipation = history.dissipation.data();
  for (AnyBlock& any : m.blocks)
    std::visit([&](auto& block) {
      block.commit_history();
      const BlockRange range = block.range;
#pragma omp parallel for schedule(static)
      for (std::size_t i = range.begin; i < range.end; ++i) dissipation[i] += m.inelastic_work[i];
    }, any);
  if (m.ctx.mirror.active) release_mirror_planes(v);
  if (m.bond_damage) m.update_damaged_bonds(dissipation);

  // Work of the hourglass forces over the step, trapezoidal like the kinetic energy of velocity Verlet.
  const double* volume = m.model->disc->volume.data();
  if (m.have_previous) {
    for (AnyBlock& any : m.blocks) {
      const BlockRange range = std::visit([](auto& block) { return block.range; }, any);
#pragma omp parallel for schedule(static)
      for (std::size_t i = range.begin; i < range.end; ++i) {
        double w = 0;
        for (int d = 0; d < 3; ++d)
          w += 0.5 * (m.previous_hourglass_force(i, d) + m.hourglass_force(i, d)) * (u(i, d) - m.previous_u(i, d));
        m.hourglass_work[i] -= w * volume[i];
      }
    }
  }
  std::swap(m.previous_hourglass_force, m.hourglass_force);  // every block point is rewritten next step
  m.previous_u = u;
  m.have_previous = true;
}

void CorrespondenceBlocks::release_mirror_planes(const VectorField& v) {
  Impl& m = *impl_;
  MirrorBonds& mirror = m.ctx.mirror;
  const Discretization& disc = *m.model->disc;
  const double* volume = disc.volume.data();
  const std::size_t n = m.owned;
  for (std::size_t k = 0; k < mirror.planes.size(); ++k) {
    MirrorPlane& plane = mirror.planes[k];
    if (!plane.active) continue;
    // The normal force of the plane on the bodies and their momentum along n over every rank's points,
    // summed exactly (the same decision for any number of ranks).
    const double normal = reproducible_sum(m.comm, n, [&](std::size_t i) {
      if (mirror.offsets[i] == mirror.offsets[i + 1] || mirror.plane_of[i] != k) return 0.0;
      return (m.mirror_force(i, 0) * plane.normal.x + m.mirror_force(i, 1) * plane.normal.y +
              m.mirror_force(i, 2) * plane.normal.z) * volume[i];
    });
    if (normal >= 0) continue;
    const double momentum = reproducible_sum(m.comm, n, [&](std::size_t i) {
      const std::size_t block = static_cast<std::size_t>(disc.block[i]);
      if (!plane.block_touches[block]) return 0.0;
      return m.model->params[block].density * volume[i] *
             (v(i, 0) * plane.normal.x + v(i, 1) * plane.normal.y + v(i, 2) * plane.normal.z);
    });
    if (momentum > 0) plane.active = false;  // pulled back while moving away: the body leaves the anvil
  }
  mirror.active = std::any_of(mirror.planes.begin(), mirror.planes.end(), [](const MirrorPlane& p) { return p.active; });
}

void CorrespondenceBlocks::symmetry_wall_force_density(std::size_t wall, std::vector<double>& out) const {
  const Impl& m = *impl_;
  const MirrorBonds& mirror = m.ctx.mirror;
  out.assign(3 * m.owned, 0.0);
  if (mirror.empty()) return;
  for (std::size_t i = 0; i < m.owned; ++i)
    if (mirror.offsets[i] < mirror.offsets[i + 1] && mirror.planes[mirror.plane_of[i]].wall == wall)
      for (int d = 0; d < 3; ++d) out[3 * i + d] = m.mirror_force(i, d);
}

bool CorrespondenceBlocks::symmetry_wall_active(std::size_t wall) const {
  for (const MirrorPlane& plane : impl_->ctx.mirror.planes)
    if (plane.wall == wall) return plane.active;
  return false;
}

void CorrespondenceBlocks::state_arrays(StateArrays& arrays) {
  Impl& m = *impl_;
  if (m.blocks.empty()) return;
  const std::size_t n = m.committed.rotation.size();
  arrays.points("correspondence.rotation", m.committed.rotation.data(), n, 9, 0);
  arrays.points("correspondence.left_stretch", m.committed.left_stretch.data(), n, 9, 0);
  arrays.points("correspondence.unrotated_stress", m.committed.unrotated_stress.data(), n, 9, 0);
  // A failed point keeps the F it failed with, which no kinematics can recompute from its (broken) bonds.
  if (m.bond_damage) arrays.points("correspondence.deformation_gradient", m.kin.deformation_gradient.data(), n, 9, 0);
  arrays.points("correspondence.hourglass_force", m.hourglass_force, m.hourglass_force.size());
  arrays.points("correspondence.previous_hourglass_force", m.previous_hourglass_force, m.previous_hourglass_force.size());
  arrays.points("correspondence.previous_u", m.previous_u, m.previous_u.size());
  arrays.points("correspondence.hourglass_work", m.hourglass_work, m.hourglass_work.size());
  arrays.global("correspondence.have_previous", &m.have_previous);
  if (!m.ctx.mirror.planes.empty()) arrays.global("correspondence.mirror_active", &m.ctx.mirror.active);
  for (std::size_t k = 0; k < m.ctx.mirror.planes.size(); ++k)
    arrays.global("correspondence.plane" + std::to_string(k) + ".active", &m.ctx.mirror.planes[k].active);
  for (std::size_t b = 0; b < m.blocks.size(); ++b)
    std::visit([&](auto& block) {
      using History = typename std::decay_t<decltype(block.history)>::value_type;
      if constexpr (!std::is_empty_v<History>)
        arrays.points("correspondence.block" + std::to_string(m.block_index[b]) + ".history", block.history.data(),
                      block.history.size(), 1, block.range.begin);
    }, m.blocks[b]);
}

void CorrespondenceBlocks::strain_energy_density(std::vector<double>& W) const {
  const Impl& m = *impl_;
  for (std::size_t k = 0; k < m.blocks.size(); ++k) {
    const MaterialParams& p = m.model->params[m.block_index[k]];
    const BlockRange range = std::visit([](auto& block) { return block.range; }, m.blocks[k]);
#pragma omp parallel for schedule(static)
    for (std::size_t i = range.begin; i < range.end; ++i)
      W[i] = elastic_energy_density(m.committed.unrotated_stress.get(i), m.kin.deformation_gradient.get(i).determinant(),
                                    p.elastic.bulk_modulus, p.elastic.shear_modulus);
  }
}

const std::vector<double>& CorrespondenceBlocks::point_hourglass_work() const { return impl_->hourglass_work; }

const std::vector<std::string>& CorrespondenceBlocks::output_field_names() { return correspondence_output_names(); }

void CorrespondenceBlocks::write_point_outputs(State& state) const {
  const Impl& m = *impl_;
  const std::size_t n = m.model->disc->num_points();
  const std::vector<std::string>& names = output_field_names();
  std::vector<double*> out;
  for (const std::string& name : names) {
    std::vector<double>& field = state.point_outputs[name];
    field.assign(n, 0.0);
    out.push_back(field.data());
  }
  for (const AnyBlock& any : m.blocks)
    std::visit([&](const auto& block) {
      const BlockRange range = block.range;
#pragma omp parallel for schedule(static)
      for (std::size_t i = range.begin; i < range.end; ++i) {
        const Mat3 F = m.kin.deformation_gradient.get(i);
        const Mat3 sigma = m.stress.cauchy_stress.get(i);
        const Mat3 E = 0.5 * (F.transpose() * F - Mat3::Identity());  // Green–Lagrange strain (eq 62)
        std::size_t k = 0;
        for (int r = 0; r < 3; ++r)
          for (int c = 0; c < 3; ++c) out[k++][i] = F(r, c);
        for (const auto& rc : symmetric_index) out[k++][i] = sigma(rc[0], rc[1]);
        out[k++][i] = von_mises(sigma);
        for (const auto& rc : symmetric_index) out[k++][i] = E(rc[0], rc[1]);
        if constexpr (requires { block.history[0].equivalent_plastic_strain; })  // the plastic laws
          state.history.plastic_strain[i] = block.history[i - range.begin].equivalent_plastic_strain;
      }
    }, any);
  if (any_material_damage(*m.model)) {
    std::vector<double>& damage = state.point_outputs["material_damage"];
    damage.assign(n, 0.0);
    for (const AnyBlock& any : m.blocks)
      std::visit([&](const auto& block) {
        if constexpr (requires { block.history[0].damage; })
          for (std::size_t i = block.range.begin; i < block.range.end; ++i)
            damage[i] = block.history[i - block.range.begin].damage;
      }, any);
  }
  if (!any_thermal_softening(*m.model)) return;
  // T of the points with thermal softening, 0 elsewhere (they have no temperature).
  std::vector<double>& temperature = state.point_outputs["temperature"];
  temperature.assign(n, 0.0);
  for (const AnyBlock& any : m.blocks)
    std::visit([&](const auto& block) {
      if constexpr (requires { block.law.thermal.enabled; }) {  // the laws with thermal softening
        if (!block.law.thermal.enabled) return;
        const std::size_t begin = block.range.begin;
        for (std::size_t i = begin; i < block.range.end; ++i)
          temperature[i] = block.law.thermal.reference_temperature + block.history[i - begin].temperature_rise;
      }
    }, any);
}

CorrespondenceBlocks::Extremes CorrespondenceBlocks::extremes() const {
  const Impl& m = *impl_;
  const Discretization& disc = *m.model->disc;
  // The larger value wins, and of equal values the smaller input id, so that any rank count picks the same point.
  auto better = [&](double value, std::size_t i, double best, std::size_t at) {
    return at == Extremes::none || value > best || (value == best && disc.id_of(i) < disc.id_of(at));
  };
  Extremes e;
  for (const AnyBlock& any : m.blocks)
    std::visit([&](const auto& block) {
      if constexpr (requires { block.history[0].equivalent_plastic_strain; }) {  // the plastic laws
        const std::size_t begin = block.range.begin;
        for (std::size_t i = begin; i < block.range.end; ++i) {
          const auto& h = block.history[i - begin];
          if (better(h.equivalent_plastic_strain, i, e.max_plastic_strain, e.plastic_point)) {
            e.max_plastic_strain = h.equivalent_plastic_strain;
            e.plastic_point = i;
          }
          if constexpr (requires { block.law.thermal.enabled; }) {
            if (!block.law.thermal.enabled) continue;
            const double T = block.law.thermal.reference_temperature + h.temperature_rise;
            if (better(T, i, e.max_temperature, e.hot_point)) {
              e.max_temperature = T;
              e.hot_point = i;
            }
            if (block.law.thermal.homologous(h.temperature_rise) >= 0.99) ++e.near_melting;
          }
        }
      }
    }, any);
  return e;
}

bool any_material_damage(const ModelContext& model) {
  for (std::size_t b = 0; b < model.params.size(); ++b)
    if (is_model<CorrespondenceModel>(model.params[b]) &&
        std::visit([](const auto& law) {
          if constexpr (requires { law.damage.enabled; }) return law.damage.enabled;
          else return false;
        }, model.model_params_of<CorrespondenceModel>(b).law))
      return true;
  return false;
}

bool any_thermal_softening(const ModelContext& model) {
  for (std::size_t b = 0; b < model.params.size(); ++b)
    if (is_model<CorrespondenceModel>(model.params[b]) &&
        std::visit([](const auto& law) {
          if constexpr (requires { law.thermal.enabled; }) return law.thermal.enabled;
          else return false;
        }, model.model_params_of<CorrespondenceModel>(b).law))
      return true;
  return false;
}

}  // namespace peridot
