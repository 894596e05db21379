#include "peridot/solvers/runner.hpp"

#include <algorithm>
#include <array>
#include <chrono>
#include <csignal>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <memory>
#include <optional>
#include <sstream>

#include <fmt/format.h>
#include <fmt/ranges.h>

#include "peridot/deck/deck.hpp"
#include "peridot/core/exact_sum.hpp"
#include "peridot/core/resident_memory.hpp"
#include "peridot/core/simd.hpp"
#include "peridot/materials/models.hpp"
#include "peridot/output/csv_writer.hpp"
#include "peridot/output/exodus_pieces.hpp"
#include "peridot/output/exodus_writer.hpp"
#include "peridot/solvers/checkpoint.hpp"
#include "peridot/state/point_fields.hpp"

namespace peridot {

namespace fs = std::filesystem;

double point_field(const State& state, const std::string& field, std::size_t i) {
  int component = 0;
  const PointField* entry = find_point_field(field, &component);
  if (!entry || !entry->probe) throw std::out_of_range("unknown point field '" + field + "'");
  return entry->value(state, i, component);
}

/// The optional Exodus fields a problem writes (registry order): plastic strain and dissipation with an
/// inelastic model, the correspondence fields with correspondence blocks, temperature with a temperature field
/// or thermal softening, fragment labels with damage.
std::vector<std::string> optional_exodus_fields(const Simulation& sim) {
  const bool correspondence = sim.has_correspondence();
  std::vector<std::string> fields;
  for (const PointField& field : point_fields()) {
    bool written = false;
    switch (field.scope) {
      case FieldScope::always: break;
      case FieldScope::inelastic: written = sim.model().bond_history_arrays() > 0 || correspondence; break;
      case FieldScope::correspondence: written = correspondence; break;
      case FieldScope::thermal:
        written = (correspondence && any_thermal_softening(sim.model())) || sim.problem().temperature.has_value();
        break;
      case FieldScope::damage: written = sim.model().any_damage(); break;
      case FieldScope::material_damage: written = correspondence && any_material_damage(sim.model()); break;
    }
    if (written) fields.emplace_back(field.name);
  }
  return fields;
}

std::string describe_setup(const Simulation& sim) {
  // From each rank's owned points and counts summed over the ranks (collective): no rank needs the whole problem.
  const Discretization& disc = sim.discretization();
  const Problem& problem = sim.problem();
  const Communicator& comm = sim.communicator();
  std::ostringstream out;
  const double bonds = static_cast<double>(sim.global_bond_count());
  const std::size_t points = sim.global_point_count();
  std::vector<std::uint64_t> block_points(disc.block_names.size(), 0);
  for (std::size_t i = 0; i < sim.num_owned(); ++i) ++block_points[static_cast<std::size_t>(disc.block[i])];
  for (std::uint64_t& count : block_points) count = comm.sum(count);
  out << fmt::format("dimension        {}{}\n", disc.dimension,
                     disc.dimension == 2   ? (problem.plane == PlaneKind::stress ? " (plane stress)" : " (plane strain)")
                     : disc.dimension == 1 ? fmt::format(" (a bar of area {:g} m²)", problem.area)
                                           : std::string());
  out << fmt::format("points           {}\n", points);
  out << fmt::format("bond loops       {}\n", simd::describe());
  for (std::size_t b = 0; b < disc.block_names.size(); ++b) {
    const MaterialParams& p = sim.model().params[b];
    out << fmt::format("  block {:<10} {} points, model {}, horizon {:.6g} m, critical stretch {}\n", disc.block_names[b],
                       block_points[b], model_name(p.model), p.horizon,
                       std::isfinite(p.critical_stretch) ? fmt::format("{:.6g}", p.critical_stretch) : "none");
    if (const EnergyFailure* energy = sim.energy_failure(); energy && p.fracture_energy > 0)
      out << fmt::format("  {:<16} energy criterion: Gc {:.6g} J/m^2, N_c {:g} micropotentials per cell, bond work "
                         "W V_i V_j >= {:.6g} J\n", "", p.fracture_energy, energy->micropotentials(b), energy->threshold(b));
  }
  out << fmt::format("bonds            {} directed ({:.1f} per point)\n", static_cast<std::uint64_t>(bonds),
                     points ? bonds / static_cast<double>(points) : 0.0);
  if (const SurfaceCorrectionResult& c = sim.surface_correction(); c.applied)
    out << fmt::format("surface correction: uniaxial energies within {:.1f} % of the classical ({:.1f} % uncorrected)\n",
                       100 * c.largest_deviation, 100 * c.largest_uncorrected);
  for (const NodeSet& set : sim.node_sets())  // each rank's owned points
    out << fmt::format("  node set {:<10} {} points\n", set.name, comm.sum(static_cast<std::uint64_t>(set.points.size())));
  const double memory = static_cast<double>(sim.memory_bytes());
  if (comm.serial()) {
    out << fmt::format("memory           {:.1f} MiB (points and bonds)\n", memory / (1 << 20));
  } else {
    const double owned = static_cast<double>(sim.num_owned());
    const double ghosts = static_cast<double>(sim.halo().ghosts());
    out << fmt::format("ranks            {} (owned points per rank {:.0f} to {:.0f}, ghosts up to {:.0f})\n", comm.size(),
                       comm.min(owned), comm.max(owned), comm.max(ghosts));
    out << fmt::format("memory           {:.1f} MiB on the largest rank (points and bonds)\n", comm.max(memory) / (1 << 20));
    out << "points made      by each rank for its own part of space (its box of the lattice, its share of the point "
           "files and meshes)\n";
  }
  out << sim.integrator().describe();
  return out.str();
}

namespace {

/// Distributed runs look for a stop request every this many steps (serial runs after every step).
constexpr std::int64_t stop_check_interval = 32;

/// The signal that asked the run to stop; 0 while none has.
volatile std::sig_atomic_t stop_signal = 0;

extern "C" void request_stop(int signal) {
  stop_signal = signal;
  std::signal(signal, SIG_DFL);  // a second one ends the process at once (async-signal-safe)
}

/// SIGINT, SIGTERM and SIGUSR1 (a batch system's notice before its limit) ask the step loop to stop, for the
/// lifetime of this object; the earlier handlers come back after it.
class StopSignals {
 public:
  StopSignals() {
    stop_signal = 0;
    for (std::size_t k = 0; k < signals_.size(); ++k) previous_[k] = std::signal(signals_[k], request_stop);
  }
  ~StopSignals() {
    for (std::size_t k = 0; k < signals_.size(); ++k) std::signal(signals_[k], previous_[k]);
  }
  StopSignals(const StopSignals&) = delete;
  StopSignals& operator=(const StopSignals&) = delete;
  int received() const { return stop_signal; }

 private:
  static constexpr std::array<int, 3> signals_ = {SIGINT, SIGTERM, SIGUSR1};
  std::array<void (*)(int), 3> previous_{};
};

/// The results are written under NAME.partial and moved into place together at the end, so that a rerun
/// stopped early never leaves fewer frames where a finished run had more. A symlink of either name is
/// replaced, never followed out of the folder.
class ResultFiles {
 public:
  explicit ResultFiles(fs::path dir) : dir_(std::move(dir)) {}
  /// The path to write `name` to; a stale partial file of that name is removed first. `shown`: how
  /// partial_names() names it (a piece: the whole set).
  fs::path partial(const std::string& name, const std::string& shown = {}) {
    names_.push_back(name);
    shown_.push_back((shown.empty() ? name : shown) + ".partial");
    const fs::path path = dir_ / (name + ".partial");
    fs::remove(path);
    return path;
  }
  void publish() const {
    for (const std::string& name : names_) fs::rename(dir_ / (name + ".partial"), dir_ / name);
  }
  std::string partial_names() const { return fmt::format("{}", fmt::join(shown_, ", ")); }

 private:
  fs::path dir_;
  std::vector<std::string> names_, shown_;
};


/// Log lines go to the run log (flushed at once) and to the optional stream.
/// Distributed, only rank 0 writes (enabled).
class RunLog {
 public:
  RunLog(std::ostream* echo, bool enabled) : enabled_(enabled), echo_(echo) {}
  /// The file, once its folder exists; lines before go to the echo alone.
  void open(const fs::path& path, bool append) {
    if (enabled_) file_.open(path, append ? std::ios::app : std::ios::trunc);
  }
  void line(const std::string& text) {
    if (!enabled_) return;
    file_ << text << '\n' << std::flush;
    if (echo_) *echo_ << text << '\n' << std::flush;
  }
  /// A line for the log file alone (the command line prints it on stderr itself).
  void file_line(const std::string& text) {
    if (enabled_) file_ << text << '\n' << std::flush;
  }

 private:
  bool enabled_;
  std::ofstream file_;
  std::ostream* echo_;
};

class History {
 public:
  /// Every rank computes each row (row(): collective, nothing gathered); rank 0 keeps the rows in memory
  /// (rows()) and, once open()ed, writes them to a CSV file. Collective.
  explicit History(Simulation& sim)
      : sim_(sim), keep_(sim.communicator().is_root()),
        contact_energy_(!sim.problem().rigid_bodies.empty() || sim.problem().contact) {
    const Problem& problem = sim.problem();
    std::vector<std::string> columns = {"time", "step", "kinetic_energy", "strain_energy", "external_work",
                                        "momentum_x", "momentum_y", "momentum_z", "max_damage", "dissipated_energy",
                                        "fragments"};
    if (sim.has_correspondence()) columns.push_back("hourglass_work");
    if (sim.any_damage()) columns.push_back("broken_fraction");
    for (const std::string& name : sim.integrator().history_columns()) columns.push_back(name);
    if (contact_energy_) columns.push_back("contact_energy");
    if (problem.contact)
      for (const BodySpec& body : problem.bodies)
        for (const char* axis : {"_x", "_y", "_z"}) columns.push_back("contact_" + body.name + axis);
    for (std::size_t k = 0; k < sim.rigid_bodies().size(); ++k) {
      const RigidBody& body = sim.rigid_bodies()[k];
      if (body.wall) {
        for (const char* axis : {"_x", "_y", "_z"}) columns.push_back("wall_" + body.name + axis);
        continue;
      }
      for (const char* what : {"_x", "_y", "_z", "_vx", "_vy", "_vz", "_fx", "_fy", "_fz"})
        columns.push_back("body_" + body.name + what);
    }
    for (const std::string& name : problem.output.reaction_sets) {
      reaction_sets_.push_back(name);
      for (const char* axis : {"_x", "_y", "_z"}) columns.push_back("reaction_" + name + axis);
    }
    for (const ProbeSpec& probe : problem.output.probes) {
      probes_.push_back({nearest_point(probe.point), probe.field});
      columns.push_back(probe.name);
    }
    rows_.columns = std::move(columns);
  }
  /// Rank 0: the rows go to the CSV file at `path` too.
  void open(const fs::path& path) { writer_ = std::make_unique<CsvWriter>(path.string(), rows_.columns); }
  void close() {
    if (writer_) writer_->close();
  }
  const HistoryRows& rows() const { return rows_; }
  std::int64_t copy_rows(const std::string& earlier, std::int64_t last_step, std::int64_t every) {
    return writer_->copy_rows(earlier, last_step, every);
  }
  /// The row of this instant, on every rank (after Simulation::prepare_outputs with totals). Collective.
  std::vector<double> row() const {
    const Totals t = sim_.output_totals();
    const State& s = sim_.state();
    std::vector<double> row = {s.time, static_cast<double>(s.step), t.kinetic_energy, t.strain_energy,
                               t.external_work, t.momentum.x, t.momentum.y, t.momentum.z, t.max_damage,
                               t.dissipated_energy, static_cast<double>(t.fragments)};
    if (sim_.has_correspondence()) row.push_back(t.hourglass_work);
    if (sim_.any_damage()) row.push_back(t.broken_fraction);
    for (double value : sim_.integrator().history_values()) row.push_back(value);
    if (contact_energy_) row.push_back(t.contact_energy);
    for (const Vec3& force : t.body_contact_force) row.insert(row.end(), {force.x, force.y, force.z});
    for (std::size_t k = 0; k < t.rigid_force.size(); ++k) {
      const RigidBody& body = sim_.rigid_bodies()[k];
      const Vec3& force = t.rigid_force[k];
      if (!body.wall) {
        const Vec3 at = body.center + body.offset;
        row.insert(row.end(), {at.x, at.y, at.z, body.velocity.x, body.velocity.y, body.velocity.z});
      }
      row.insert(row.end(), {force.x, force.y, force.z});
    }
    for (const std::string& set : reaction_sets_) {
      Vec3 r = sim_.reaction(set);
      row.insert(row.end(), {r.x, r.y, r.z});
    }
    for (const auto& [point, field] : probes_) row.push_back(probe(point, field));
    return row;
  }
  /// Rank 0: keeps the row and writes it (once open). Returns the name of its first non-finite column (""
  /// when every value is finite); the row is written either way.
  std::string write(const std::vector<double>& row) {
    if (!keep_) return {};
    if (writer_) writer_->write_row(row);
    rows_.values.insert(rows_.values.end(), row.begin(), row.end());
    for (std::size_t k = 0; k < row.size(); ++k)
      if (!std::isfinite(row[k])) return rows_.columns[k];
    return {};
  }

 private:
  /// The global index of the point nearest p in the reference configuration (in 2D, in the plane); of equally
  /// near points the first in the global order, as a serial search finds. Collective.
  std::size_t nearest_point(Vec3 p) const {
    const Discretization& disc = sim_.discretization();
    const Communicator& comm = sim_.communicator();
    double best_distance = INFINITY;
    std::size_t best = 0;
    for (std::size_t i = 0; i < sim_.num_owned(); ++i) {
      Vec3 d = disc.x.get(i) - p;
      if (disc.dimension == 2) d.z = 0;
      if (dot(d, d) < best_distance) best_distance = dot(d, d), best = global_of(i);
    }
    const double nearest = comm.min(best_distance);
    // Global indices are below 2^32: exact as doubles.
    return static_cast<std::size_t>(comm.min(best_distance == nearest ? static_cast<double>(best) : INFINITY));
  }
  std::size_t global_of(std::size_t i) const { return sim_.communicator().serial() ? i : sim_.global_index()[i]; }
  /// The field's value at the point of global index `point`, from the rank that owns it. Collective.
  double probe(std::size_t point, const std::string& field) const {
    std::vector<ExactSum> value(1);
    const std::vector<std::uint32_t>& index = sim_.global_index();
    if (sim_.communicator().serial()) {
      value[0].add(point_field(sim_.state(), field, point));
    } else {
      const auto last = index.begin() + static_cast<std::ptrdiff_t>(sim_.num_owned());
      const auto found = std::lower_bound(index.begin(), last, static_cast<std::uint32_t>(point));
      if (found != last && *found == point)
        value[0].add(point_field(sim_.state(), field, static_cast<std::size_t>(found - index.begin())));
    }
    sim_.communicator().sum(value);  // one term in all: the owner's value
    return value[0].value();
  }
  Simulation& sim_;
  bool keep_;  ///< rank 0 keeps and writes the rows
  /// Decks with rigid bodies or short-range contact have a contact_energy column (walls alone keep the old columns).
  bool contact_energy_ = false;
  std::vector<std::string> reaction_sets_;
  std::vector<std::pair<std::size_t, std::string>> probes_;
  std::unique_ptr<CsvWriter> writer_;  // null: in memory only
  HistoryRows rows_;
};

class Progress {
 public:
  explicit Progress(bool enabled) : enabled_(enabled), start_(Clock::now()), last_(start_) {}
  void update(const Simulation& sim, bool force = false) {
    if (!enabled_) return;
    const auto now = Clock::now();
    if (!force && now - last_ < std::chrono::seconds(1)) return;
    last_ = now;
    const double elapsed = std::chrono::duration<double>(now - start_).count();
    const auto step = sim.state().step, total = sim.total_steps();
    const double rate = elapsed > 0 ? static_cast<double>(step) / elapsed : 0;
    const double eta = rate > 0 ? static_cast<double>(total - step) / rate : 0;
    std::cerr << fmt::format("\rstep {}/{}  t = {:.4e} s  {:5.1f}%  {:.0f} steps/s  ETA {:.1f} s   ", step, total,
                             sim.state().time, total ? 100.0 * static_cast<double>(step) / static_cast<double>(total) : 100.0,
                             rate, eta)
              << (force ? "\n" : "") << std::flush;
  }
  double elapsed() const { return std::chrono::duration<double>(Clock::now() - start_).count(); }

 private:
  using Clock = std::chrono::steady_clock;
  bool enabled_;
  Clock::time_point start_, last_;
};

/// The earlier results a restart continues: a stopped run's NAME.partial (moved aside to
/// NAME.before-restart, as the new NAME.partial takes its name), else a finished run's NAME. Empty: none.
fs::path earlier_results(const fs::path& dir, const std::string& name) {
  const fs::path partial = dir / (name + ".partial"), aside = dir / (name + ".before-restart"), done = dir / name;
  if (fs::exists(partial)) {
    fs::rename(partial, aside);
    return aside;
  }
  if (fs::exists(aside)) return aside;  // left by a restart stopped before it had copied them
  if (fs::exists(done)) return done;
  return {};
}

/// The same for Exodus results, which a distributed run writes as pieces NAME.N.r: the files of the earlier
/// run (stopped: its partial files moved aside; finished: NAME, or its pieces), whatever its rank count.
std::vector<std::string> earlier_exodus_results(const fs::path& dir, const std::string& name) {
  auto with_suffix = [&](const std::string& suffix) {  // NAME + suffix and NAME.N.r + suffix
    std::vector<fs::path> found;
    const std::string stem = name + ".";
    for (const auto& entry : fs::directory_iterator(dir)) {
      const std::string file = entry.path().filename().string();
      if (file.size() <= suffix.size() || file.compare(file.size() - suffix.size(), suffix.size(), suffix) != 0) continue;
      const std::string base = file.substr(0, file.size() - suffix.size());
      if (base == name) found.push_back(entry.path());
      else if (base.rfind(stem, 0) == 0 && is_piece_suffix(base.substr(stem.size()))) found.push_back(entry.path());
    }
    std::sort(found.begin(), found.end());
    return found;
  };
  std::vector<std::string> earlier;
  if (const auto partial = with_suffix(".partial"); !partial.empty()) {
    for (const fs::path& file : partial) {
      fs::path aside = file;
      aside.replace_extension(".before-restart");
      fs::rename(file, aside);
      earlier.push_back(aside.string());
    }
    return earlier;
  }
  for (const fs::path& file : with_suffix(".before-restart")) earlier.push_back(file.string());  // a restart stopped early
  if (!earlier.empty()) return earlier;
  earlier = piece_paths((dir / name).string());
  if (earlier.empty() && fs::exists(dir / name)) earlier.push_back((dir / name).string());
  return earlier;
}

}  // namespace

struct Run::Impl {
  Impl(const Problem& problem, const RunOptions& run_options)
      : options(run_options), sim(problem), comm(sim.communicator()), root(comm.is_root() && options.write_files),
        restart(!options.restart.empty()), dir(problem.output.directory), results(dir),
        log(options.log, root),
        progress(options.progress && problem.output.progress && comm.is_root()) {}

  RunOptions options;
  Simulation sim;  // every input error surfaces here, before anything is written
  const Communicator& comm;
  const bool root;  // distributed, rank 0 writes every output but the Exodus pieces (no rank does without write_files)
  const bool restart;
  const fs::path dir;
  ResultFiles results;
  RunLog log;
  Progress progress;
  std::optional<StopSignals> stop;
  std::unique_ptr<ExodusWriter> exodus;
  std::unique_ptr<History> history;
  std::vector<fs::path> checkpoints;  // the newest output.checkpoint_keep this run wrote stay
  std::chrono::steady_clock::time_point last_checkpoint = std::chrono::steady_clock::now();
  std::int64_t checkpoint_step = -1;
  std::string restored_note;  ///< for the log: what the restart read
  std::int64_t frame_step = -1, row_step = -1;  // the steps of the last frame and row written
  bool finished = false;

  /// A failure to write on rank 0 stops every rank (the others would wait for it in the next collective), and
  /// goes into the run log as well as to stderr (the log may be the file that cannot be written).
  template <class Write>
  void on_root(Write&& write) {
    on_ranks(root, write);
  }
  /// The same for what every rank writes (its Exodus piece).
  template <class Write>
  void on_every_rank(Write&& write) {
    on_ranks(options.write_files, write);
  }
  /// `write` where `mine`; a failure on any rank stops every rank with its message. Collective.
  template <class Write>
  void on_ranks(bool mine, Write&& write) {
    std::string failure;
    if (mine) {
      try {
        write();
      } catch (const std::exception& e) {
        failure = e.what();
      }
    }
    const int failing = comm.first_rank_with(!failure.empty());
    if (failing < 0) return;
    const std::string message = comm.broadcast(failure, failing);
    log.file_line("error: " + message);
    throw OutputError(message);
  }

  void open_outputs();
  void write_outputs(bool force);
  void write_checkpoint();
  bool checkpoint_due(bool looked);
  /// Closed before they are moved into place; a failure to close is a failure to write.
  /// Published, the new results replace every earlier one of their names: a whole Exodus file or pieces of
  /// another rank count left by an earlier run are removed.
  void close_results(bool publish) {
    finished = true;
    on_every_rank([&] {
      if (exodus) exodus->close();
      if (root && history) history->close();
      if (publish) results.publish();
    });
    if (!publish || !exodus) return;
    on_root([&] {
      const std::string name = (dir / sim.problem().output.exodus_file).string();
      std::vector<std::string> written;
      if (comm.serial()) written.push_back(name);
      for (int r = 0; r < comm.size() && !comm.serial(); ++r) written.push_back(ExodusWriter::piece_path(name, r, comm.size()));
      for (const std::string& file : exodus_result_files(name))
        if (std::find(written.begin(), written.end(), file) == written.end()) fs::remove(file);
    });
  }
};

void Run::Impl::open_outputs() {
  const Problem& problem = sim.problem();
  if (restart) {  // checked and restored before anything is written
    CheckpointSource checkpoint = read_checkpoint(options.restart, sim);
    if (checkpoint.first.step > sim.total_steps())
      throw InputError(SourcePos{options.restart, 0, 0},
                       fmt::format("restart: '{}' is at step {}, after this deck's end (step {}); give a later end time "
                                   "or more steps", options.restart, checkpoint.first.step, sim.total_steps()));
    sim.initialize();
    const std::size_t pieces = checkpoint.files.size(), read = restore_checkpoint(sim, checkpoint, options.restart);
    restored_note = fmt::format("restart          step {} of '{}': {} file(s), at most {} read by one rank",
                                sim.state().step, options.restart, pieces, comm.max(static_cast<double>(read)));
    checkpoint_step = frame_step = row_step = sim.state().step;
  }
  const OutputSpec& output = problem.output;
  on_root([&] {
    fs::create_directories(dir);
    write_file_atomically(results.partial("resolved_deck.yaml"), resolved_deck_yaml(problem));
    log.open(dir / "run.log", restart);
  });
  log.line("peridot run " + problem.deck_path + (restart ? " --restart " + options.restart : ""));
  if (!restored_note.empty()) log.line(restored_note);
  for (const Diagnostic& w : problem.warnings) log.line(w.str());
  std::istringstream setup(describe_setup(sim));
  for (std::string line; std::getline(setup, line);) log.line(line);
  log.line(fmt::format("set-up           points, bonds and partition in {:.2f} s (the slowest rank)", comm.max(sim.setup_seconds())));
  if (sim.integrator().bounded_by_stable_time_step() && sim.time_step() > sim.stable_time_step()) {
    const std::string warning = fmt::format("warning: time step {:.6g} s is above the stable time step {:.6g} s",
                                            sim.time_step(), sim.stable_time_step());
    log.line(warning);
    if (!options.log && comm.is_root()) std::cerr << warning << '\n';  // quiet runs still hear about it
  }

  std::vector<std::string> earlier_exodus;  // a restart's earlier results, found before NAME.partial is new
  fs::path earlier_history;
  on_root([&] {
    if (restart && output.exodus_every > 0) earlier_exodus = earlier_exodus_results(dir, output.exodus_file);
    if (restart && output.history_every > 0) earlier_history = earlier_results(dir, output.history_file);
  });
  if (!comm.serial()) {  // every rank continues its own piece from them
    std::string list = fmt::format("{}", fmt::join(earlier_exodus, "\n"));
    list = comm.broadcast(list, 0);
    earlier_exodus.clear();
    for (std::size_t start = 0; start < list.size();) {
      const std::size_t end = std::min(list.find('\n', start), list.size());
      earlier_exodus.push_back(list.substr(start, end - start));
      start = end + 1;
    }
  }
  if (output.exodus_every > 0) {
    // Serial: NAME by rank 0; distributed: each rank its piece NAME.N.r (output/exodus_writer.hpp).
    const bool pieces = !comm.serial();
    const ExodusPiece piece = pieces ? sim.exodus_piece() : ExodusPiece{};  // collective
    on_every_rank([&] {
      if (!pieces && !root) return;
      std::vector<NodeSetOutput> sets;
      for (const NodeSet& set : sim.node_sets()) sets.push_back({set.name, set.points});
      const std::string name = pieces ? ExodusWriter::piece_path(output.exodus_file, comm.rank(), comm.size()) : output.exodus_file;
      const std::string shown = pieces ? fmt::format("{}.{}.*", output.exodus_file, comm.size()) : std::string{};
      exodus = std::make_unique<ExodusWriter>(results.partial(name, shown).string(), sim.discretization(), sets,
                                              "peridot: " + problem.deck_path, problem.cross_section(),
                                              optional_exodus_fields(sim), pieces ? &piece : nullptr);
    });
  }
  // Without files the history is still kept in memory (rank 0) for Run::history.
  if (output.history_every > 0) history = std::make_unique<History>(sim);
  on_root([&] {
    if (output.history_every > 0) history->open(results.partial(output.history_file));
  });
  if (restart) {  // the earlier frames and rows up to the checkpoint, those on this run's schedule
    const std::int64_t step = sim.state().step;
    log.line(fmt::format("restarted from {} at step {}, t = {:.6g} s", options.restart, step, sim.state().time));
    std::vector<std::string> notes;
    // A failure to read the earlier results is a note, not an error: the new results begin at this step.
    if (output.exodus_every > 0) {
      std::string copied, failure;
      on_every_rank([&] {
        if (!exodus || earlier_exodus.empty()) return;
        try {
          copied = fmt::format("{} frames", exodus->copy_frames(earlier_exodus, sim.time_step(), step, output.exodus_every));
        } catch (const std::runtime_error& e) {
          failure = e.what();
        }
      });
      const int failing = comm.first_rank_with(!failure.empty());
      if (failing >= 0) failure = comm.broadcast(failure, failing);
      on_root([&] {
        const std::string& name = output.exodus_file;
        if (earlier_exodus.empty()) {
          notes.push_back(fmt::format("{}: no earlier results to continue; it begins at step {}", name, step));
        } else if (failing >= 0) {
          notes.push_back(fmt::format("{}: not continued ({}); it begins at step {}", name, failure, step));
        } else {
          const fs::path first(earlier_exodus.front());
          notes.push_back(fmt::format("{}: {} from {}{} up to step {}", name, copied, first.filename().string(),
                                      earlier_exodus.size() > 1 ? fmt::format(" and {} more pieces", earlier_exodus.size() - 1) : "",
                                      step));
          for (const std::string& file : earlier_exodus)
            if (fs::path(file).extension() == ".before-restart") fs::remove(file);
        }
      });
    }
    on_root([&] {
      auto carry_over = [&](const std::string& name, const fs::path& earlier, auto&& copy) {
        if (earlier.empty()) {
          notes.push_back(fmt::format("{}: no earlier results to continue; it begins at step {}", name, step));
          return;
        }
        try {
          notes.push_back(fmt::format("{}: {} from {} up to step {}", name, copy(earlier.string()), earlier.filename().string(), step));
        } catch (const std::runtime_error& e) {
          notes.push_back(fmt::format("{}: not continued ({}); it begins at step {}", name, e.what(), step));
          return;
        }
        if (earlier.extension() == ".before-restart") fs::remove(earlier);
      };
      if (history)
        carry_over(output.history_file, earlier_history, [&](const std::string& earlier) {
          return fmt::format("{} rows", history->copy_rows(earlier, step, output.history_every));
        });
    });
    for (const std::string& note : notes) log.line(note);
  }
}

/// The frame and the row due at this step (on the schedule, or `force`d: the last step, a stop), each at most
/// once per step.
void Run::Impl::write_outputs(bool force) {
  const OutputSpec& output = sim.problem().output;
  const std::int64_t step = sim.state().step;
  auto due = [&](std::int64_t every) { return every > 0 && (step % every == 0 || force); };
  const bool frame = due(output.exodus_every) && frame_step != step;
  const bool row = due(output.history_every) && row_step != step;
  if (!frame && !row) return;
  sim.prepare_outputs(frame, row);
  if (frame) frame_step = step;
  if (row) row_step = step;
  std::string non_finite;  // a total that overflowed while every point's values stayed finite
  const std::vector<double> values = row && history ? history->row() : std::vector<double>{};  // collective
  if (row && history && !options.write_files) non_finite = history->write(values);
  if (frame) on_every_rank([&] { if (exodus) exodus->write_frame(sim.state().time, sim.state()); });
  if (row) on_root([&] { non_finite = history->write(values); });
  if (!row) return;
  const int failing = comm.first_rank_with(!non_finite.empty());
  if (failing >= 0)
    throw NumericalError(fmt::format("non-finite {} in the history at step {}, time {:.6g} s (written as the last row)",
                                     comm.broadcast(non_finite, failing), sim.state().step, sim.state().time));
}

void Run::Impl::write_checkpoint() {
  const OutputSpec& output = sim.problem().output;
  const CheckpointData data = collect_checkpoint(sim);  // distributed: this rank's piece
  const fs::path path = dir / fmt::format("checkpoint_{}.nc", sim.state().step);
  // Serial: one file; distributed: each rank its piece checkpoint_<step>.nc.N.r, so nothing is gathered.
  auto mine = [&](const fs::path& set) {
    return comm.serial() ? set : fs::path(ExodusWriter::piece_path(set.string(), comm.rank(), comm.size()));
  };
  on_every_rank([&] {
    write_checkpoint_file(mine(path).string(), data);
    checkpoints.push_back(path);
    while (checkpoints.size() > static_cast<std::size_t>(output.checkpoint_keep)) {
      fs::remove(mine(checkpoints.front()));
      checkpoints.erase(checkpoints.begin());
    }
  });
  log.line(fmt::format("checkpoint {}{} at step {}, t = {:.6g} s", path.filename().string(),
                       comm.serial() ? "" : fmt::format(" ({} pieces: {}.{}.*)", comm.size(), path.filename().string(), comm.size()),
                       sim.state().step,
                       sim.state().time));
  last_checkpoint = std::chrono::steady_clock::now();
  checkpoint_step = sim.state().step;
}

/// Due by steps, or by wall-clock time (distributed: when any rank's clock says so, looked at with the stop
/// signals, so that every rank writes after the same step).
bool Run::Impl::checkpoint_due(bool looked) {
  const OutputSpec& output = sim.problem().output;
  const std::int64_t step = sim.state().step;
  if (output.checkpoint_every > 0 && step % output.checkpoint_every == 0) return true;
  if (output.checkpoint_wall_time <= 0 || !looked) return false;
  const double since = std::chrono::duration<double>(std::chrono::steady_clock::now() - last_checkpoint).count();
  return comm.max(since >= output.checkpoint_wall_time ? 1.0 : 0.0) > 0;
}

Run::Run(const Problem& problem, const RunOptions& options) : impl_(std::make_unique<Impl>(problem, options)) {
  impl_->open_outputs();
  if (options.catch_signals) impl_->stop.emplace();
  if (!impl_->restart) {
    try {
      impl_->sim.initialize();
      impl_->write_outputs(impl_->sim.total_steps() == 0);
    } catch (const NumericalError& e) {
      impl_->log.line(std::string("error: ") + e.what());
      impl_->close_results(true);  // every frame written so far stays readable, in place
      throw;
    }
  }
}

Run::~Run() {
  if (impl_->finished) return;
  try {  // abandoned before finish (an exception, a Python object let go): the results stay NAME.partial
    impl_->close_results(false);
  } catch (const std::exception&) {
  }
}

Simulation& Run::simulation() { return impl_->sim; }
const Simulation& Run::simulation() const { return impl_->sim; }
bool Run::finished() const { return impl_->finished; }

int Run::advance(std::int64_t last_step) {
  Impl& run = *impl_;
  Simulation& sim = run.sim;
  if (run.finished) throw std::logic_error("this run has finished");
  if (last_step > sim.total_steps())
    throw std::out_of_range(fmt::format("step {} is after the run's end (step {})", last_step, sim.total_steps()));
  const Communicator& comm = run.comm;
  const OutputSpec& output = sim.problem().output;
  int signal = 0;
  try {
    while (sim.state().step < last_step) {
      sim.step();
      // Every rank stops after the same step, whichever received the signal. Distributed, the ranks ask each
      // other every stop_check_interval steps: a reduction per step slows small runs on busy cores noticeably.
      const bool looked = comm.serial() || sim.state().step % stop_check_interval == 0;
      const int received = run.stop ? run.stop->received() : 0;
      if (comm.serial()) signal = received;
      else if (looked) signal = static_cast<int>(comm.max(received));
      const bool last = sim.state().step == sim.total_steps();
      run.write_outputs(last || signal != 0);
      if (output.checkpoints() && run.options.write_files && (run.checkpoint_due(looked) || last || signal != 0))
        run.write_checkpoint();
      run.progress.update(sim);
      if (signal != 0) break;
    }
  } catch (const NumericalError& e) {
    run.log.line(std::string("error: ") + e.what());
    run.close_results(true);  // every frame written so far stays readable, in place
    throw;
  }
  return signal;
}

void Run::finish() {
  Impl& run = *impl_;
  if (run.finished) throw std::logic_error("this run has finished");
  const Simulation& sim = run.sim;
  run.write_outputs(true);
  run.progress.update(sim, true);
  run.close_results(true);
  run.log.line(fmt::format("done: {} steps to t = {:.6g} s in {:.2f} s", sim.state().step, sim.state().time,
                           run.progress.elapsed()));
  for (const std::string& line : sim.plasticity_summary()) {
    run.log.line(line);
    // quiet runs still hear about it
    if (line.starts_with("warning") && !run.options.log && run.comm.is_root()) std::cerr << line << '\n';
  }
  if (const ShortRangeContact* contact = sim.short_range())
    run.log.line(fmt::format("contact: {} pair-list builds in {:.2f} s, pair forces {:.2f} s; {} pairs listed at the end (rank 0)",
                             contact->builds(), contact->build_seconds(), contact->compute_seconds(), contact->pairs()));
  // Collective: every rank's peak, in the log of rank 0.
  const std::vector<double> peak = run.comm.gather(std::vector<double>{static_cast<double>(peak_resident_bytes())});
  if (run.comm.is_root()) {
    const double mib = 1 << 20;
    if (peak.size() == 1) {
      run.log.line(fmt::format("peak resident memory {:.1f} MiB", peak[0] / mib));
    } else {
      std::string each;
      double sum = 0;
      for (double p : peak) each += fmt::format("{}{:.1f}", each.empty() ? "" : ", ", p / mib), sum += p;
      run.log.line(fmt::format("peak resident memory {:.1f} MiB on the largest rank, {:.1f} MiB on all (per rank: {})",
                               *std::max_element(peak.begin(), peak.end()) / mib, sum / mib, each));
    }
  }
}

void Run::stopped(int signal) {
  Impl& run = *impl_;
  const Simulation& sim = run.sim;
  run.progress.update(sim, true);
  run.close_results(false);
  const std::string name = signal == SIGINT ? "SIGINT" : signal == SIGTERM ? "SIGTERM" : "SIGUSR1";
  std::string saved = fmt::format(
      "stopped by {} after step {} of {}, t = {:.6g} s: results up to this step are in {} (in {}); the "
      "previous run's results there are untouched",
      name, sim.state().step, sim.total_steps(), sim.state().time, run.results.partial_names(), run.dir.string());
  if (run.checkpoint_step == sim.state().step)
    saved += fmt::format("; continue with: peridot run {} --restart {}", sim.problem().deck_path,
                         (run.dir / fmt::format("checkpoint_{}.nc", run.checkpoint_step)).string());
  else
    saved += "; no checkpoint (output.checkpoint is not set)";
  run.log.line(saved);
  if (!run.options.log && run.comm.is_root()) std::cerr << saved << '\n';
}

const HistoryRows& Run::history() const {
  static const HistoryRows none;
  return impl_->history ? impl_->history->rows() : none;
}

void write_file_atomically(const std::string& path, const std::string& text) {
  fs::path tmp = path;
  tmp += ".tmp";
  {
    std::ofstream out(tmp, std::ios::binary);
    out << text;
    if (!out.flush()) throw std::runtime_error("cannot write " + tmp.string());
  }
  fs::rename(tmp, path);
}

RunOutcome run_problem(const Problem& problem, const RunOptions& options) {
  Run run(problem, options);
  RunOutcome outcome;
  outcome.signal = run.advance(run.simulation().total_steps());
  if (outcome.signal != 0) run.stopped(outcome.signal);
  else run.finish();
  return outcome;
}

}  // namespace peridot
