#include "peridot/solvers/newton_krylov.hpp"

#include <algorithm>
#include <cfloat>
#include <cmath>
#include <cstdlib>
#include <limits>

#include <fmt/format.h>
#include <petscsnes.h>

#include "peridot/deck/map_reader.hpp"
#include "peridot/materials/bond_loop.hpp"
#include "peridot/materials/models.hpp"
#include "peridot/parallel/communicator.hpp"
#include "peridot/solvers/family_tangent.hpp"
#include "peridot/solvers/simulation.hpp"

// KeySpecs are written with designated initializers that leave the other fields at their defaults on
// purpose; GCC 12 warns about every omitted field regardless.
#pragma GCC diagnostic ignored "-Wmissing-field-initializers"

namespace peridot {

SolverInfo NewtonKrylov::info() {
  SolverInfo info{
      .name = name,
      .summary = "static equilibrium in load steps by Newton–Krylov (PETSc)",
      .description = "Newton's method with a line search for each equilibrium of the load steps (the same steps, "
                     "ramp, bond breaking and residual as solver type relaxation), the linear systems by a Krylov "
                     "method preconditioned with the assembled pmb-like tangent, through PETSc's SNES and KSP "
                     "(docs/algorithms.md)",
      .keys = load_step_keys("50", "Newton iterations allowed for one equilibrium; more ends the run with an error "
                                   "naming the residual reached"),
      .check = &NewtonKrylov::check};
  info.keys.push_back(
      {.key = "jacobian", .type = ValueType::choice, .default_yaml = "matrix_free",
       .description = "matrix_free: Jacobian–vector products by a finite difference of the residual (every model, "
                      "Newton's quadratic convergence); bond_tangent: the assembled bond tangent itself (one "
                      "matrix–vector product per Krylov iteration; exact for pmb, whose Newton iterations then "
                      "converge quadratically; for the other models the pmb-like springs c/ξ along the deformed "
                      "bonds, a modified Newton method converging linearly); exact: the assembled exact tangent of "
                      "pmb and lps (lps's dilatation couples every pair of a family: a 2δ stencil, about 8 times "
                      "the bond tangent's memory), also the preconditioner's matrix; finite_difference: the same "
                      "2δ stencil assembled for any model by colored finite differences of the residual (one "
                      "residual per color, some hundreds in 2D and thousands in 3D: for small problems and "
                      "checks)",
       .choices = {"matrix_free", "bond_tangent", "exact", "finite_difference"}});
  info.keys.push_back({.key = "linear_solver", .type = ValueType::choice, .default_yaml = "gmres",
                       .description = "Krylov method: gmres (any tangent) or cg (symmetric positive definite "
                                      "tangents: elastic models without contact)",
                       .choices = {"gmres", "cg"}});
  info.keys.push_back({.key = "preconditioner", .type = ValueType::choice, .default_yaml = "gamg",
                       .description = "of the assembled bond tangent: gamg (PETSc's algebraic multigrid, the "
                                      "translations as its near-null space), ilu (block Jacobi with ILU(0) per "
                                      "rank when distributed), jacobi or none",
                       .choices = {"gamg", "ilu", "jacobi", "none"}});
  info.keys.push_back({.key = "linear_tolerance", .default_yaml = "1e-6", .range = {0, 1, true, true},
                       .description = "each linear solve stops when its residual has fallen by this factor"});
  info.keys.push_back({.key = "max_linear_iterations", .type = ValueType::integer, .default_yaml = "1000",
                       .range = at_least_one, .description = "Krylov iterations allowed for one linear solve"});
  info.keys.push_back({.key = "line_search", .type = ValueType::choice, .default_yaml = "backtracking",
                       .description = "backtracking: the Newton step is shortened until the residual norm "
                                      "decreases enough (PETSc's bt); none: the full step always",
                       .choices = {"backtracking", "none"}});
  info.keys.push_back({.key = "print_iterations", .type = ValueType::boolean, .default_yaml = "false",
                       .description = "print each Newton iterate's relative residual and Krylov iterations on "
                                      "standard output"});
  return info;
}

void NewtonKrylov::check(const Problem& problem, DeckContext& context) {
  check_static(problem, context, name);
  if (const Parameters::Entry* jacobian = problem.solver.parameters.find("jacobian"); jacobian && jacobian->text == "exact")
    for (const MaterialSpec& m : problem.materials)
      if (!has_exact_tangent(m.model))
        context.error(jacobian->pos, "solver.jacobian",
                      fmt::format("jacobian: exact is the closed-form tangent of pmb and lps, and material '{}' is {}; "
                                  "use finite_difference (any model, assembled) or matrix_free",
                                  m.name, m.model));
}

// -- PETSc ----------------------------------------------------------------------------------------

namespace {

/// Turns a PETSc error code into an exception naming the call.
void check_petsc(PetscErrorCode code, const char* call) {
  if (code == 0) return;
  const char* text = nullptr;
  PetscErrorMessage(code, &text, nullptr);
  throw NumericalError(fmt::format("PETSc: {} failed: {}", call, text != nullptr ? text : "unknown error"));
}
#define PERIDOT_PETSC(call) check_petsc((call), #call)

/// PETSc starts once per process, on first use (a deck that only `check`s never starts it). When Peridot
/// runs without a launcher MPI is not started, and PETSc starts it (a singleton) and finalizes it at exit.
void start_petsc() {
  PetscBool up = PETSC_FALSE;
  PetscInitialized(&up);
  if (up) return;
  int mpi_up = 0;
  MPI_Initialized(&mpi_up);
  // Peridot handles SIGINT, SIGTERM and SIGUSR1 itself (a clean stop with the step's output).
  PetscOptionsSetValue(nullptr, "-no_signal_handler", nullptr);
  PERIDOT_PETSC(PetscInitializeNoArguments());
  PetscPushErrorHandler(PetscReturnErrorHandler, nullptr);  // errors come back as codes, reported here
  if (mpi_up == 0) std::atexit([] { PetscFinalize(); });
}

}  // namespace

struct NewtonKrylov::Petsc {
  MPI_Comm comm = MPI_COMM_NULL;
  Vec x = nullptr, r = nullptr, base_x = nullptr, base_r = nullptr, work = nullptr;
  Mat J = nullptr, P = nullptr;
  MatFDColoring coloring = nullptr;  ///< jacobian: finite_difference
  SNES snes = nullptr;
  bool assembled = false;       ///< P holds K of this equilibrium
  std::vector<PetscInt> block;  ///< per point, owned then ghosts: its global block row, −1 if it has none
  /// The 2δ stencil (jacobian exact, finite_difference): the block columns of each owned block row, sorted,
  /// row m's from starts[m]; the first owned block row.
  std::vector<PetscInt> starts, columns;
  PetscInt first_row = 0;
  std::vector<double> sums;  ///< the exact tangent of the owned rows, summed here before it goes to P
  /// Which owned families reach each point, owned or ghost (CSR from member_start): the family's point and
  /// the point's slot in it (0: its own family; q: the partner of its q-th intact bond).
  std::vector<std::size_t> member_start;
  std::vector<std::uint32_t> member_family, member_slot;
  ~Petsc() {
    SNESDestroy(&snes);
    MatFDColoringDestroy(&coloring);
    MatDestroy(&J);
    MatDestroy(&P);
    for (Vec* v : {&x, &r, &base_x, &base_r, &work}) VecDestroy(v);
  }
};

namespace {

/// Runs f, turning an exception into a PETSc error code (exceptions must not cross PETSc's C frames).
template <class F>
PetscErrorCode guarded(NewtonKrylov& self, F&& f) {
  try {
    f();
    return 0;
  } catch (...) {
    self.error = std::current_exception();
    return PETSC_ERR_USER;
  }
}

PetscErrorCode form_function(SNES, Vec x, Vec r, void* context) {
  auto& self = *static_cast<NewtonKrylov*>(context);
  return guarded(self, [&] {
    const PetscScalar* xa = nullptr;
    PetscScalar* ra = nullptr;
    PERIDOT_PETSC(VecGetArrayRead(x, &xa));
    PERIDOT_PETSC(VecGetArray(r, &ra));
    self.evaluate_residual(xa, ra, true);
    PERIDOT_PETSC(VecRestoreArray(r, &ra));
    PERIDOT_PETSC(VecRestoreArrayRead(x, &xa));
  });
}

/// R(x) for the colored finite differences of jacobian: finite_difference (not an iterate: not recorded).
PetscErrorCode difference_function(SNES, Vec x, Vec r, void* context) {
  auto& self = *static_cast<NewtonKrylov*>(context);
  return guarded(self, [&] {
    const PetscScalar* xa = nullptr;
    PetscScalar* ra = nullptr;
    PERIDOT_PETSC(VecGetArrayRead(x, &xa));
    PERIDOT_PETSC(VecGetArray(r, &ra));
    self.evaluate_residual(xa, ra, false);
    PERIDOT_PETSC(VecRestoreArray(r, &ra));
    PERIDOT_PETSC(VecRestoreArrayRead(x, &xa));
  });
}

PetscErrorCode form_jacobian(SNES, Vec x, Mat, Mat, void* context) {
  auto& self = *static_cast<NewtonKrylov*>(context);
  return guarded(self, [&] { self.assemble(x); });
}

PetscErrorCode convergence_test(SNES, PetscInt iteration, PetscReal, PetscReal, PetscReal, SNESConvergedReason* reason,
                                void* context) {
  auto& self = *static_cast<NewtonKrylov*>(context);
  return guarded(self, [&] {
    int r = 0;
    self.converged_or_stop(iteration, r);
    *reason = static_cast<SNESConvergedReason>(r);
  });
}

}  // namespace

// The matrix-free product J v, a shell matrix's multiplication.
static PetscErrorCode jacobian_product(Mat J, Vec v, Vec y);

NewtonKrylov::NewtonKrylov(Simulation& sim)
    : QuasiStatic(sim),
      jacobian_([&] {
        const std::string& text = sim.problem().solver.parameters.text("jacobian");
        return text == "bond_tangent"        ? Jacobian::bond_tangent
               : text == "exact"             ? Jacobian::exact
               : text == "finite_difference" ? Jacobian::finite_difference
                                             : Jacobian::matrix_free;
      }()),
      linear_solver_(sim.problem().solver.parameters.text("linear_solver")),
      preconditioner_(sim.problem().solver.parameters.text("preconditioner")),
      linear_tolerance_(sim.problem().solver.parameters.number("linear_tolerance")),
      max_linear_iterations_(sim.problem().solver.parameters.integer("max_linear_iterations")),
      line_search_(sim.problem().solver.parameters.text("line_search") == "backtracking"),
      print_iterations_(sim.problem().solver.parameters.boolean("print_iterations")) {}

NewtonKrylov::~NewtonKrylov() = default;

bool NewtonKrylov::active(std::size_t k) const {
  const int dimension = sim_.problem().dimension;
  const std::size_t component = k % 3;
  if (static_cast<int>(component) >= dimension) return false;
  return sim_.loads().dof_kinds()[k] == DofKind::free && diagonal_[k / 3] > 0;
}

void NewtonKrylov::set_displacement(const double* x) {
  double* u = sim_.state().u.data();
  const double* target = target_.data();
  std::copy(target, target + 3 * sim_.num_owned(), u);
  for_each_unknown([&](std::size_t row, std::size_t k, std::size_t) {
    if (active(k)) u[k] = x[row];
  });
  sim_.exchange_ghosts(sim_.state().u);
}

void NewtonKrylov::evaluate_residual(const double* x, double* r, bool record) {
  set_displacement(x);
  evaluate_residual_force(force_);
  const double* volume = sim_.discretization().volume.data();
  const double* target = target_.data();
  for_each_unknown([&](std::size_t row, std::size_t k, std::size_t i) {
    r[row] = active(k) ? -force_[k] * volume[i] : diagonal_[i] * (x[row] - target[k]);
  });
  if (!record) return;
  if (!started_) start_norm_ = norm(force_), started_ = true;
  const Residual relative = relative_residual(force_, start_norm_);
  recorded_ = relative.relative;
  recorded_load_ = relative.load;
}

void NewtonKrylov::assemble(Vec x_vector) {
  Petsc& p = *petsc_;
  if (jacobian_ == Jacobian::finite_difference) {  // sets u itself, at x and at every color's perturbation
    PERIDOT_PETSC(MatFDColoringApply(p.P, p.coloring, x_vector, p.snes));
    return;
  }
  const PetscScalar* x = nullptr;
  PERIDOT_PETSC(VecGetArrayRead(x_vector, &x));
  set_displacement(x);
  if (jacobian_ == Jacobian::exact) {
    PERIDOT_PETSC(MatZeroEntries(p.P));
    add_family_blocks(p.P);
    PERIDOT_PETSC(MatAssemblyBegin(p.P, MAT_FINAL_ASSEMBLY));
    PERIDOT_PETSC(MatAssemblyEnd(p.P, MAT_FINAL_ASSEMBLY));
  }
  // Matrix-free, K only preconditions: built once per equilibrium (and the preconditioner with it,
  // SNESSetLagPreconditioner), from the deformation at its start. As the Jacobian itself it follows x.
  if (jacobian_ == Jacobian::bond_tangent || (jacobian_ == Jacobian::matrix_free && !p.assembled))
    assemble_bond_tangent();
  p.assembled = true;
  if (jacobian_ == Jacobian::matrix_free) {  // the base point of the finite differences: x and R(x)
    Vec r = nullptr;
    PERIDOT_PETSC(SNESGetFunction(p.snes, &r, nullptr, nullptr));
    PetscScalar* base = nullptr;
    PERIDOT_PETSC(VecGetArray(p.base_x, &base));
    std::copy(x, x + width_ * unknown_points_.size(), base);
    PERIDOT_PETSC(VecRestoreArray(p.base_x, &base));
    PERIDOT_PETSC(VecCopy(r, p.base_r));
    PERIDOT_PETSC(MatAssemblyBegin(p.J, MAT_FINAL_ASSEMBLY));
    PERIDOT_PETSC(MatAssemblyEnd(p.J, MAT_FINAL_ASSEMBLY));
  }
  PERIDOT_PETSC(VecRestoreArrayRead(x_vector, &x));
}

VectorField NewtonKrylov::unknown_components() const {
  const std::size_t owned = sim_.num_owned();
  VectorField unknown(sim_.discretization().num_points());
  for (std::size_t i = 0; i < owned; ++i)
    unknown.set(i, Vec3{active(3 * i) ? 1.0 : 0.0, active(3 * i + 1) ? 1.0 : 0.0, active(3 * i + 2) ? 1.0 : 0.0});
  sim_.exchange_ghosts(unknown);
  return unknown;
}

void NewtonKrylov::find_family_members() {
  Petsc& p = *petsc_;
  const BondList& bonds = sim_.bonds();
  const std::size_t owned = sim_.num_owned(), points = sim_.discretization().num_points();
  // Every owned family, a fully prescribed point's too: its bonds add to its unknown partners' diagonal blocks.
  const auto for_each_member = [&](auto&& f) {
    for (std::size_t i = 0; i < owned; ++i) {
      f(i, i, 0u);
      std::uint32_t slot = 0;
      for (std::uint64_t b = bonds.offsets[i]; b < bonds.offsets[i + 1]; ++b)
        if (!bonds.broken[b]) f(i, bonds.neighbors[b], ++slot);
    }
  };
  p.member_start.assign(points + 1, 0);
  for_each_member([&](std::size_t, std::size_t r, std::uint32_t) { ++p.member_start[r + 1]; });
  for (std::size_t r = 0; r < points; ++r) p.member_start[r + 1] += p.member_start[r];
  p.member_family.resize(p.member_start[points]);
  p.member_slot.resize(p.member_start[points]);
  std::vector<std::size_t> next(p.member_start.begin(), p.member_start.end() - 1);
  for_each_member([&](std::size_t i, std::size_t r, std::uint32_t slot) {
    p.member_family[next[r]] = static_cast<std::uint32_t>(i);
    p.member_slot[next[r]++] = slot;
  });
}

void NewtonKrylov::add_family_stencil(Mat graph) {
  const Petsc& p = *petsc_;
  const BondList& bonds = sim_.bonds();
  const std::size_t points = sim_.discretization().num_points();
  // Row by row, each point (owned or ghost) that a family reaches: the points of those families, each once.
  std::vector<std::size_t> seen(points, SIZE_MAX);
  std::vector<PetscInt> columns;
  std::vector<double> zeros;
  for (std::size_t r = 0; r < points; ++r) {
    const PetscInt row = p.block[r];
    if (row < 0 || p.member_start[r] == p.member_start[r + 1]) continue;
    columns.clear();
    const auto add = [&](std::size_t c) {
      if (seen[c] == r || p.block[c] < 0) return;
      seen[c] = r;
      columns.push_back(p.block[c]);
    };
    for (std::size_t k = p.member_start[r]; k < p.member_start[r + 1]; ++k) {
      const std::uint32_t i = p.member_family[k];
      add(i);
      for (std::uint64_t b = bonds.offsets[i]; b < bonds.offsets[i + 1]; ++b)
        if (!bonds.broken[b]) add(bonds.neighbors[b]);
    }
    zeros.assign(columns.size(), 0.0);
    PERIDOT_PETSC(MatSetValues(graph, 1, &row, static_cast<PetscInt>(columns.size()), columns.data(), zeros.data(),
                               INSERT_VALUES));
  }
}

void NewtonKrylov::add_family_blocks(Mat target) {
  Petsc& p = *petsc_;
  const VectorField unknown = unknown_components();
  const double* known = unknown.data();
  const double* u = sim_.state().u.data();
  const ModelContext& ctx = sim_.model();
  const std::size_t owned = sim_.num_owned(), points = sim_.discretization().num_points();
  const std::size_t w = static_cast<std::size_t>(width_), w2 = w * w;
  std::vector<FamilyTangent> families(owned);
#pragma omp parallel for schedule(static)
  for (std::size_t i = 0; i < owned; ++i) family_tangent(ctx, u, i, families[i]);
  // Row r sums, over the families that reach it (in a fixed order: the same bits on any thread count), the
  // blocks of its slot against the family's slots; its PETSc columns are sorted, each column point's place
  // found once per row. Rows of unknown owned points into sums; rows of ghosts to their owners through PETSc.
  const auto sum_row = [&](std::size_t r, std::vector<std::size_t>& seen, std::vector<std::size_t>& place,
                           const auto& place_of, double* values, std::size_t count) {
    for (std::size_t k = p.member_start[r]; k < p.member_start[r + 1]; ++k) {
      const FamilyTangent& family = families[p.member_family[k]];
      const std::size_t slot = p.member_slot[k], n = family.points.size();
      const auto column = [&](std::size_t c) {
        const std::uint32_t q = family.points[c];
        if (p.block[q] < 0) return;
        if (seen[q] != r) seen[q] = r, place[q] = place_of(q);
        double block[9] = {0, 0, 0, 0, 0, 0, 0, 0, 0};
        family.add_block(slot, c, block);
        double* out = values + place[q] * w;
        for (std::size_t a = 0; a < w; ++a)
          for (std::size_t b = 0; b < w; ++b)  // a prescribed component's row and column are not K's
            out[a * count * w + b] += known[3 * r + a] * known[3 * q + b] * block[3 * a + b];
      };
      if (family.coupled() || slot == 0) {
        for (std::size_t c = 0; c < n; ++c) column(c);
      } else {
        column(0), column(slot);
      }
    }
  };
  p.sums.assign(w2 * p.columns.size(), 0.0);
#pragma omp parallel
  {
    std::vector<std::size_t> seen(points, SIZE_MAX), place(points, 0);
#pragma omp for schedule(dynamic, 64)
    for (std::size_t m = 0; m < unknown_points_.size(); ++m) {
      const std::uint32_t r = unknown_points_[m];
      const PetscInt* first = p.columns.data() + p.starts[m];
      const PetscInt* last = p.columns.data() + p.starts[m + 1];
      const std::size_t count = static_cast<std::size_t>(last - first);
      const auto place_of = [&](std::uint32_t q) {
        return static_cast<std::size_t>(std::lower_bound(first, last, p.block[q]) - first);
      };
      double* values = p.sums.data() + w2 * static_cast<std::size_t>(p.starts[m]);
      sum_row(r, seen, place, place_of, values, count);
      // A prescribed component of an unknown point: the row d (x − ū) of the residual.
      const std::size_t self = place_of(r);
      for (std::size_t a = 0; a < w; ++a)
        if (!active(3 * r + a)) values[a * count * w + self * w + a] += diagonal_[r];
    }
  }
  for (std::size_t m = 0; m < unknown_points_.size(); ++m) {
    const PetscInt row = p.first_row + static_cast<PetscInt>(m), count = p.starts[m + 1] - p.starts[m];
    PERIDOT_PETSC(MatSetValuesBlocked(target, 1, &row, count, p.columns.data() + p.starts[m],
                                      p.sums.data() + w2 * static_cast<std::size_t>(p.starts[m]), ADD_VALUES));
  }
  // Ghost rows: their columns listed as they come.
  std::vector<std::size_t> seen(points, SIZE_MAX), place(points, 0);
  std::vector<PetscInt> columns;
  std::vector<double> values;
  for (std::size_t r = owned; r < points; ++r) {
    const PetscInt row = p.block[r];
    if (row < 0 || p.member_start[r] == p.member_start[r + 1]) continue;
    columns.clear();
    for (std::size_t k = p.member_start[r]; k < p.member_start[r + 1]; ++k) {  // the columns first
      const FamilyTangent& family = families[p.member_family[k]];
      for (const std::uint32_t q : family.points)
        if (p.block[q] >= 0 && seen[q] != r) seen[q] = r, place[q] = columns.size(), columns.push_back(p.block[q]);
    }
    values.assign(w2 * columns.size(), 0.0);
    sum_row(r, seen, place, [&](std::uint32_t q) { return place[q]; }, values.data(), columns.size());
    PERIDOT_PETSC(MatSetValuesBlocked(target, 1, &row, static_cast<PetscInt>(columns.size()), columns.data(),
                                      values.data(), ADD_VALUES));
  }
}

void NewtonKrylov::assemble_bond_tangent() {
  Petsc& p = *petsc_;
  const Discretization& disc = sim_.discretization();
  const BondList& bonds = sim_.bonds();
  // Which dofs of every point, ghosts included, are unknowns (their columns stay; the others' are zero).
  const VectorField unknown = unknown_components();
  const double* X = disc.x.data();
  const double* u = sim_.state().u.data();
  const double* known = unknown.data();
  // pmb's bonds within its block get the exact tangent: their axial spring (bond_stiffness) and the geometric
  // stiffness of a force that turns with the bond, (t/|y|)(I − n⊗n) = k (e/|y|)(I − n⊗n), e the bond's
  // mechanical extension.
  const ModelContext& ctx = sim_.model();
  std::vector<char> exact(ctx.params.size());
  for (std::size_t b = 0; b < ctx.params.size(); ++b) exact[b] = is_model<Pmb>(ctx.params[b]);
  // One block row at a time: the point's own block first, then one per intact bond (a point and its family
  // are distinct columns), in a single insertion.
  std::vector<PetscInt> columns;
  std::vector<double> values, row_values;
  for (const std::uint32_t i : unknown_points_) {
    columns.assign(1, p.block[i]);
    values.assign(9, 0.0);
    for (std::uint64_t b = bonds.offsets[i]; b < bonds.offsets[i + 1]; ++b) {
      if (bond_k_[b] == 0) continue;
      const std::uint32_t j = bonds.neighbors[b];
      double e[3], length2 = 0;
      for (int d = 0; d < 3; ++d) {
        e[d] = X[3 * j + d] + u[3 * j + d] - X[3 * i + d] - u[3 * i + d];
        length2 += e[d] * e[d];
      }
      if (!(length2 > 0)) continue;
      const double spring = bond_k_[b] * disc.volume[i];
      double turning = 0;  // e/|y| of an exact pmb bond
      if (exact[static_cast<std::size_t>(disc.block[i])] && disc.block[j] == disc.block[i]) {
        double xi2 = 0;
        for (int d = 0; d < 3; ++d) xi2 += (X[3 * j + d] - X[3 * i + d]) * (X[3 * j + d] - X[3 * i + d]);
        const double length = std::sqrt(length2), xi = std::sqrt(xi2);
        turning = bond_loop::bond_mechanical_extension(ctx, i, j, length - xi, xi) / length;
      }
      double block[9];
      for (int a = 0; a < 3; ++a)
        for (int c = 0; c < 3; ++c)
          block[3 * a + c] = spring * ((1 - turning) * e[a] * e[c] / length2 + (a == c ? turning : 0.0));
      // A fully prescribed neighbour is not an unknown of the system: its bond adds to the diagonal only.
      if (p.block[j] < 0) {
        for (int k = 0; k < 9; ++k) values[k] += block[k];
        continue;
      }
      columns.push_back(p.block[j]);
      const std::size_t at = values.size();
      values.resize(at + 9);
      for (int a = 0; a < 3; ++a)
        for (int c = 0; c < 3; ++c) {
          values[3 * a + c] += block[3 * a + c];
          values[at + 3 * a + c] = known[3 * i + a] * known[3 * j + c] * -block[3 * a + c];
        }
    }
    for (int a = 0; a < 3; ++a)
      for (int c = 0; c < 3; ++c) {
        if (known[3 * i + a] == 0 || known[3 * i + c] == 0) values[3 * a + c] = 0;
        if (a == c && known[3 * i + a] == 0) values[3 * a + c] = diagonal_[i];
      }
    // The block row in one call, its values row by row across all its blocks (PETSc's layout), the
    // deck's dimension's components of each 3×3 block.
    const std::size_t n = columns.size(), w = static_cast<std::size_t>(width_);
    row_values.resize(w * w * n);
    for (std::size_t k = 0; k < n; ++k)
      for (std::size_t a = 0; a < w; ++a)
        for (std::size_t c = 0; c < w; ++c) row_values[w * n * a + w * k + c] = values[9 * k + 3 * a + c];
    const PetscInt row = p.block[i];
    PERIDOT_PETSC(MatSetValuesBlocked(p.P, 1, &row, static_cast<PetscInt>(n), columns.data(), row_values.data(),
                                      INSERT_VALUES));
  }
  PERIDOT_PETSC(MatAssemblyBegin(p.P, MAT_FINAL_ASSEMBLY));
  PERIDOT_PETSC(MatAssemblyEnd(p.P, MAT_FINAL_ASSEMBLY));
}

static PetscErrorCode jacobian_product(Mat J, Vec v, Vec y) {
  NewtonKrylov* self = nullptr;
  PetscErrorCode code = MatShellGetContext(J, &self);
  if (code != 0) return code;
  return guarded(*self, [&] { self->multiply(v, y); });
}

void NewtonKrylov::multiply(Vec v, Vec y) {
  Petsc& p = *petsc_;
  PetscReal v_norm = 0, x_norm = 0;
  PERIDOT_PETSC(VecNorm(v, NORM_INFINITY, &v_norm));
  if (v_norm == 0) {
    PERIDOT_PETSC(VecSet(y, 0.0));
    return;
  }
  PERIDOT_PETSC(VecNorm(p.base_x, NORM_INFINITY, &x_norm));
  // A step of √ε relative to the displacement or, near u = 0, to the smallest bond: the finite difference
  // then resolves the bonds' stretch to about √ε.
  const double h = std::sqrt(DBL_EPSILON) * std::max(length_scale_, x_norm) / v_norm;
  PERIDOT_PETSC(VecWAXPY(p.work, h, v, p.base_x));
  const PetscScalar* w = nullptr;
  PetscScalar* out = nullptr;
  PERIDOT_PETSC(VecGetArrayRead(p.work, &w));
  PERIDOT_PETSC(VecGetArray(y, &out));
  evaluate_residual(w, out, false);
  PERIDOT_PETSC(VecRestoreArray(y, &out));
  PERIDOT_PETSC(VecRestoreArrayRead(p.work, &w));
  PERIDOT_PETSC(VecAXPY(y, -1.0, p.base_r));
  PERIDOT_PETSC(VecScale(y, 1.0 / h));
}

void NewtonKrylov::converged_or_stop(std::int64_t iteration, int& reason) {
  newton_residuals_.push_back(recorded_);
  if (print_iterations_ && sim_.communicator().rank() == 0) {
    PetscInt linear = 0;
    SNESGetLinearSolveIterations(petsc_->snes, &linear);
    fmt::print("load step {}, Newton iteration {}: relative residual {:.3e} ({} Krylov iterations so far{})\n",
               sim_.state().step + 1, iteration, recorded_, linear,
               colors_ > 0 ? fmt::format("; {} residuals per Jacobian", colors_ + 1) : "");
    std::fflush(stdout);
  }
  reason = SNES_CONVERGED_ITERATING;
  if (!std::isfinite(recorded_)) {
    reason = SNES_DIVERGED_FNORM_NAN;
  } else if (recorded_ <= tolerance_) {
    reason = SNES_CONVERGED_FNORM_ABS;
    accept_load_scale(recorded_load_);
  } else if (iteration >= max_iterations_) {
    reason = SNES_DIVERGED_MAX_IT;
  }
}

void NewtonKrylov::setup() {
  start_petsc();
  petsc_ = std::make_unique<Petsc>();
  Petsc& p = *petsc_;
  const Communicator& comm = sim_.communicator();
  const Discretization& disc = sim_.discretization();
  const BondList& bonds = sim_.bonds();
  const std::size_t owned = sim_.num_owned();
  p.comm = comm.serial() ? PETSC_COMM_SELF : comm.mpi();
  // The unknowns: the points with a free dof, `width_` components each (the deck's dimension); fully
  // prescribed points are left out of the system, so that GAMG aggregates the body only (their identity rows
  // made aggregates whose coarse blocks were singular).
  width_ = sim_.problem().dimension;
  unknown_points_.clear();
  for (std::size_t i = 0; i < owned; ++i)
    for (int c = 0; c < width_; ++c)
      if (active(3 * i + static_cast<std::size_t>(c))) {
        unknown_points_.push_back(static_cast<std::uint32_t>(i));
        break;
      }
  const auto n = static_cast<PetscInt>(width_ * unknown_points_.size());
  PERIDOT_PETSC(VecCreate(p.comm, &p.x));
  PERIDOT_PETSC(VecSetSizes(p.x, n, PETSC_DETERMINE));
  PERIDOT_PETSC(VecSetBlockSize(p.x, width_));
  PERIDOT_PETSC(VecSetType(p.x, VECSTANDARD));
  for (Vec* v : {&p.r, &p.base_x, &p.base_r, &p.work}) PERIDOT_PETSC(VecDuplicate(p.x, v));
  PetscInt first = 0, global = 0;
  PERIDOT_PETSC(VecGetOwnershipRange(p.x, &first, nullptr));
  PERIDOT_PETSC(VecGetSize(p.x, &global));

  // Every point's global block row: the unknown points in their local order from this rank's first row,
  // ghosts from their owners (a double holds the index exactly), −1 for a point outside the system.
  VectorField index(disc.num_points());
  for (std::size_t i = 0; i < owned; ++i) index.set(i, Vec3{-1, -1, -1});
  for (std::size_t m = 0; m < unknown_points_.size(); ++m) {
    const double row = static_cast<double>(first / width_) + static_cast<double>(m);
    index.set(unknown_points_[m], Vec3{row, row, row});
  }
  sim_.exchange_ghosts(index);
  p.block.resize(disc.num_points());
  for (std::size_t i = 0; i < disc.num_points(); ++i) p.block[i] = static_cast<PetscInt>(index.get(i).x);

  // Preallocation per block row, owned and ghost columns apart (counted below for each stencil).
  std::vector<PetscInt> on_rank(unknown_points_.size(), 0), off_rank(unknown_points_.size(), 0);
  double shortest = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < owned; ++i)
    for (std::uint64_t b = bonds.offsets[i]; b < bonds.offsets[i + 1]; ++b) {
      const Vec3 d = disc.x.get(bonds.neighbors[b]) - disc.x.get(i);
      shortest = std::min(shortest, std::sqrt(d.x * d.x + d.y * d.y + d.z * d.z));
    }
  length_scale_ = comm.min(shortest);
  if (!std::isfinite(length_scale_)) length_scale_ = 1.0;
  PERIDOT_PETSC(MatCreate(p.comm, &p.P));
  PERIDOT_PETSC(MatSetSizes(p.P, n, n, global, global));
  PERIDOT_PETSC(MatSetType(p.P, MATAIJ));
  PERIDOT_PETSC(MatSetBlockSize(p.P, width_));
  if (jacobian_ == Jacobian::exact || jacobian_ == Jacobian::finite_difference) {
    // The 2δ stencil, every pair of every family: a graph of the unknown points gathered by PETSc's
    // preallocator (which also brings the pairs of other ranks' families to this rank's rows), then P's blocks
    // counted from its rows and laid into P as zeros (the colored finite differences color that pattern).
    const auto points = static_cast<PetscInt>(unknown_points_.size());
    Mat pairs = nullptr, graph = nullptr;
    PERIDOT_PETSC(MatCreate(p.comm, &pairs));
    PERIDOT_PETSC(MatSetSizes(pairs, points, points, global / width_, global / width_));
    PERIDOT_PETSC(MatSetType(pairs, MATPREALLOCATOR));
    PERIDOT_PETSC(MatSetUp(pairs));
    find_family_members();
    add_family_stencil(pairs);
    PERIDOT_PETSC(MatAssemblyBegin(pairs, MAT_FINAL_ASSEMBLY));
    PERIDOT_PETSC(MatAssemblyEnd(pairs, MAT_FINAL_ASSEMBLY));
    PERIDOT_PETSC(MatCreate(p.comm, &graph));
    PERIDOT_PETSC(MatSetSizes(graph, points, points, global / width_, global / width_));
    PERIDOT_PETSC(MatSetType(graph, MATAIJ));
    PetscErrorCode code = MatPreallocatorPreallocate(pairs, PETSC_TRUE, graph);
    MatDestroy(&pairs);
    if (code == 0) code = MatAssemblyBegin(graph, MAT_FINAL_ASSEMBLY);
    if (code == 0) code = MatAssemblyEnd(graph, MAT_FINAL_ASSEMBLY);
    if (code != 0) MatDestroy(&graph);
    check_petsc(code, "MatPreallocatorPreallocate");
    const PetscInt first_point = first / width_, last_point = first_point + points;
    std::vector<PetscInt>& starts = p.starts;
    std::vector<PetscInt>& columns = p.columns;
    p.first_row = first_point;
    starts.assign(1, 0);
    columns.clear();
    for (PetscInt row = first_point; row < last_point; ++row) {
      PetscInt count = 0;
      const PetscInt* cols = nullptr;
      PERIDOT_PETSC(MatGetRow(graph, row, &count, &cols, nullptr));
      columns.insert(columns.end(), cols, cols + count);
      starts.push_back(static_cast<PetscInt>(columns.size()));
      const std::size_t m = static_cast<std::size_t>(row - first_point);
      for (PetscInt c = 0; c < count; ++c) ++(cols[c] >= first_point && cols[c] < last_point ? on_rank[m] : off_rank[m]);
      PERIDOT_PETSC(MatRestoreRow(graph, row, &count, &cols, nullptr));
    }
    MatDestroy(&graph);
    PERIDOT_PETSC(MatXAIJSetPreallocation(p.P, width_, on_rank.data(), off_rank.data(), nullptr, nullptr));
    std::vector<double> zeros;
    for (PetscInt m = 0; m < points; ++m) {
      const PetscInt row = first_point + m, count = starts[m + 1] - starts[m];
      zeros.assign(static_cast<std::size_t>(count * width_ * width_), 0.0);
      PERIDOT_PETSC(MatSetValuesBlocked(p.P, 1, &row, count, columns.data() + starts[m], zeros.data(), INSERT_VALUES));
    }
    PERIDOT_PETSC(MatAssemblyBegin(p.P, MAT_FINAL_ASSEMBLY));
    PERIDOT_PETSC(MatAssemblyEnd(p.P, MAT_FINAL_ASSEMBLY));
  } else {  // the bond tangent: the point itself and its unknown neighbours
    for (std::size_t m = 0; m < unknown_points_.size(); ++m) {
      const std::uint32_t i = unknown_points_[m];
      on_rank[m] = 1;
      for (std::uint64_t b = bonds.offsets[i]; b < bonds.offsets[i + 1]; ++b)
        if (const std::uint32_t j = bonds.neighbors[b]; p.block[j] >= 0) ++(j < owned ? on_rank[m] : off_rank[m]);
    }
    PERIDOT_PETSC(MatXAIJSetPreallocation(p.P, width_, on_rank.data(), off_rank.data(), nullptr, nullptr));
  }
  PERIDOT_PETSC(MatSetOption(p.P, MAT_NEW_NONZERO_ALLOCATION_ERR, PETSC_TRUE));
  // GAMG's near-null space: without one it takes the block size's translations. The rotations as well (what
  // PETSc suggests for elasticity) made coarse operators with zero diagonal entries (an aggregate on which the
  // rigid-body modes are dependent, a few points in a row, gives the prolongator zero columns), on which SOR
  // broke down: the 204 800-point bar and the notched plate once its crack grew did not converge.
  if (jacobian_ == Jacobian::matrix_free) {
    PERIDOT_PETSC(MatCreateShell(p.comm, n, n, global, global, this, &p.J));
    PERIDOT_PETSC(MatShellSetOperation(p.J, MATOP_MULT, reinterpret_cast<void (*)(void)>(&jacobian_product)));
  } else {
    PERIDOT_PETSC(PetscObjectReference(reinterpret_cast<PetscObject>(p.P)));
    p.J = p.P;
  }

  PERIDOT_PETSC(SNESCreate(p.comm, &p.snes));
  PERIDOT_PETSC(SNESSetType(p.snes, SNESNEWTONLS));
  PERIDOT_PETSC(SNESSetFunction(p.snes, p.r, form_function, this));
  PERIDOT_PETSC(SNESSetJacobian(p.snes, p.J, p.P, form_jacobian, this));
  SNESLineSearch search = nullptr;
  PERIDOT_PETSC(SNESGetLineSearch(p.snes, &search));
  PERIDOT_PETSC(SNESLineSearchSetType(search, line_search_ ? SNESLINESEARCHBT : SNESLINESEARCHBASIC));
  PERIDOT_PETSC(SNESSetTolerances(p.snes, 0.0, 0.0, 0.0, static_cast<PetscInt>(max_iterations_), 1000000000));
  PERIDOT_PETSC(SNESSetConvergenceTest(p.snes, convergence_test, this, nullptr));
  PERIDOT_PETSC(SNESSetMaxLinearSolveFailures(p.snes, 1000000000));
  if (jacobian_ == Jacobian::finite_difference) {
    // Columns whose rows do not meet share a color (a distance-2 coloring of P's stencil): one residual per
    // color. The step is that of the matrix-free products, √ε · max(|u_k|, Δx_min).
    MatColoring colorer = nullptr;
    ISColoring colors = nullptr;
    PERIDOT_PETSC(MatColoringCreate(p.P, &colorer));
    PERIDOT_PETSC(MatColoringSetDistance(colorer, 2));
    PERIDOT_PETSC(MatColoringSetType(colorer, comm.serial() ? MATCOLORINGSL : MATCOLORINGGREEDY));
    PERIDOT_PETSC(MatColoringSetFromOptions(colorer));
    const PetscErrorCode code = MatColoringApply(colorer, &colors);
    MatColoringDestroy(&colorer);
    check_petsc(code, "MatColoringApply");
    PERIDOT_PETSC(MatFDColoringCreate(p.P, colors, &p.coloring));
    // PETSc's prototype is generic; through void (*)(void), the cast GCC accepts without a warning.
    const auto function = reinterpret_cast<PetscErrorCode (*)(void)>(reinterpret_cast<void (*)(void)>(&difference_function));
    PERIDOT_PETSC(MatFDColoringSetFunction(p.coloring, function, this));
    PERIDOT_PETSC(MatFDColoringSetParameters(p.coloring, std::sqrt(DBL_EPSILON), length_scale_));
    PERIDOT_PETSC(MatFDColoringSetFromOptions(p.coloring));
    PERIDOT_PETSC(MatFDColoringSetUp(p.P, colors, p.coloring));
    PetscInt count = 0;
    PERIDOT_PETSC(ISColoringGetColors(colors, nullptr, &count, nullptr));
    colors_ = count;
    ISColoringDestroy(&colors);
  }
  // Matrix-free, the preconditioner is built once per equilibrium (−1: never again after the first).
  if (jacobian_ == Jacobian::matrix_free) PERIDOT_PETSC(SNESSetLagPreconditioner(p.snes, -1));
  KSP ksp = nullptr;
  PERIDOT_PETSC(SNESGetKSP(p.snes, &ksp));
  PERIDOT_PETSC(KSPSetType(ksp, linear_solver_ == "cg" ? KSPCG : KSPGMRES));
  PERIDOT_PETSC(KSPSetTolerances(ksp, linear_tolerance_, PETSC_DEFAULT, PETSC_DEFAULT,
                                 static_cast<PetscInt>(max_linear_iterations_)));
  PC pc = nullptr;
  PERIDOT_PETSC(KSPGetPC(ksp, &pc));
  if (preconditioner_ == "gamg") {
    PERIDOT_PETSC(PCSetType(pc, PCGAMG));
    // SOR smoothing on the levels (GAMG's default, Jacobi under Chebyshev, took 10-20 times the Krylov
    // iterations on the notched LPS plate), unless PETSC_OPTIONS chooses the smoothers.
    PetscBool chosen = PETSC_FALSE;
    PERIDOT_PETSC(PetscOptionsHasName(nullptr, nullptr, "-mg_levels_pc_type", &chosen));
    if (!chosen) PERIDOT_PETSC(PetscOptionsSetValue(nullptr, "-mg_levels_pc_type", "sor"));
  } else if (preconditioner_ == "ilu") {
    PERIDOT_PETSC(PCSetType(pc, comm.serial() ? PCILU : PCBJACOBI));
  } else if (preconditioner_ == "jacobi") {
    PERIDOT_PETSC(PCSetType(pc, PCJACOBI));
  } else {
    PERIDOT_PETSC(PCSetType(pc, PCNONE));
  }
  // PETSc's own options (the PETSC_OPTIONS environment variable, e.g. -ksp_monitor or -pc_gamg_threshold)
  // refine or override the deck's choices, for those who tune solvers.
  PERIDOT_PETSC(SNESSetFromOptions(p.snes));
}

void NewtonKrylov::begin_load_step() { linear_iterations_ = 0; }

void NewtonKrylov::equilibrate() {
  // Fresh PETSc objects for every equilibrium: what they would carry from one to the next (the random vectors
  // of GAMG's and Chebyshev's eigenvalue estimates draw on a generator that advances) would make an
  // equilibrium depend on those before it, and a restart would not give the same bits.
  State& state = sim_.state();
  const Discretization& disc = sim_.discretization();
  const BondList& bonds = sim_.bonds();
  const std::size_t owned = sim_.num_owned();
  force_.assign(3 * owned, 0.0);
  target_ = state.u;
  // The bonds' springs as they are now (bonds break between equilibria) and each point's diagonal d
  // (which points are unknowns depends on it: a point without bonds is held).
  bond_stiffness(sim_.model(), bond_k_);
  diagonal_.assign(owned, 0.0);
  for (std::size_t i = 0; i < owned; ++i) {
    double sum = 0;
    for (std::uint64_t b = bonds.offsets[i]; b < bonds.offsets[i + 1]; ++b) sum += bond_k_[b];
    diagonal_[i] = sum * disc.volume[i];
  }
  petsc_.reset();
  setup();
  Petsc& p = *petsc_;
  started_ = false;
  newton_residuals_.clear();
  error = nullptr;
  PetscScalar* xa = nullptr;
  PERIDOT_PETSC(VecGetArray(p.x, &xa));
  for_each_unknown([&](std::size_t row, std::size_t k, std::size_t) { xa[row] = state.u.data()[k]; });
  PERIDOT_PETSC(VecRestoreArray(p.x, &xa));

  const PetscErrorCode code = SNESSolve(p.snes, nullptr, p.x);
  if (error) {
    std::exception_ptr thrown = error;
    error = nullptr;
    std::rethrow_exception(thrown);
  }
  check_petsc(code, "SNESSolve");
  PetscInt newton = 0, linear = 0;
  SNESConvergedReason reason = SNES_CONVERGED_ITERATING;
  PERIDOT_PETSC(SNESGetIterationNumber(p.snes, &newton));
  PERIDOT_PETSC(SNESGetLinearSolveIterations(p.snes, &linear));
  PERIDOT_PETSC(SNESGetConvergedReason(p.snes, &reason));
  iterations_ += newton;
  linear_iterations_ += linear;
  // The state is that of the solution (the last evaluation may have been a finite difference's).
  const PetscScalar* solution = nullptr;
  PERIDOT_PETSC(VecGetArrayRead(p.x, &solution));
  std::vector<double> r(width_ * unknown_points_.size());
  evaluate_residual(solution, r.data(), true);
  PERIDOT_PETSC(VecRestoreArrayRead(p.x, &solution));
  residual_ = recorded_;
  if (reason > 0) return;

  std::string why;
  switch (reason) {
    case SNES_DIVERGED_MAX_IT: why = fmt::format("no convergence in {} Newton iterations", newton); break;
    case SNES_DIVERGED_LINE_SEARCH: why = fmt::format("the line search stalled at Newton iteration {}", newton); break;
    case SNES_DIVERGED_FNORM_NAN: why = fmt::format("the residual became non-finite at Newton iteration {}", newton); break;
    case SNES_DIVERGED_LINEAR_SOLVE: why = fmt::format("the linear solve failed at Newton iteration {}", newton); break;
    default: why = fmt::format("SNES stopped ({}) at Newton iteration {}", SNESConvergedReasons[reason], newton);
  }
  std::string cause = unsupported_fragment();
  if (cause.empty()) cause = free_rigid_motion();
  if (cause.empty())
    cause = reason == SNES_DIVERGED_MAX_IT
                ? "use more load_steps, raise solver.max_iterations or loosen solver.tolerance"
                : "the tangent may be singular (a free body or a mechanism: check that the supports hold every "
                  "rigid motion) or the load step too large (use more load_steps)";
  throw NumericalError(fmt::format("Newton's method failed in load step {} (time {:.6g} s, load factor {:.6g}): {}, "
                                   "relative force residual {:.3e}, tolerance {:.3e}; {}",
                                   state.step + 1, state.time, load_factor_, why, residual_, tolerance_, cause));
}

std::string NewtonKrylov::describe() const {
  std::string out;
  out += "solver           implicit (Newton–Krylov through PETSc SNES/KSP)\n";
  out += fmt::format("load steps       {} to t = {:.6g} s ({}), Δt = {:.6g} s\n", sim_.total_steps(),
                     sim_.time_step() * static_cast<double>(sim_.total_steps()),
                     ramp_ ? "loads ramped by k/N" : "loads as given at each t_k", sim_.time_step());
  out += fmt::format("equilibrium      relative force residual ≤ {:.3g}, at most {} Newton iterations, {} line search\n",
                     tolerance_, max_iterations_, line_search_ ? "backtracking" : "no");
  const char* jacobian = jacobian_ == Jacobian::matrix_free    ? "matrix-free"
                         : jacobian_ == Jacobian::bond_tangent ? "bond tangent"
                         : jacobian_ == Jacobian::exact        ? "exact tangent (2δ stencil for lps)"
                                                               : "colored finite differences (2δ stencil)";
  const bool own_matrix = jacobian_ == Jacobian::exact || jacobian_ == Jacobian::finite_difference;
  out += fmt::format("linear solves    {} preconditioned by {} of {}, Jacobian {}, relative tolerance {:.3g}, at most "
                     "{} iterations\n",
                     linear_solver_, preconditioner_, own_matrix ? "the Jacobian" : "the pmb-like tangent", jacobian,
                     linear_tolerance_, max_linear_iterations_);
  return out;
}

}  // namespace peridot
