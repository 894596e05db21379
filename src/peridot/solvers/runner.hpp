#pragma once
// Runs a validated problem to its end: writes the resolved deck and a run log, Exodus frames and CSV
// history, and prints a progress line. Output starts only once the whole problem has been set up, so a
// deck problem found at set-up (an empty node set) leaves nothing behind.
#include <cstdint>
#include <iosfwd>
#include <memory>
#include <string>
#include <vector>

#include "peridot/deck/problem.hpp"
#include "peridot/solvers/simulation.hpp"

namespace peridot {

struct RunOptions {
  bool progress = true;        ///< progress line on stderr (also off when output.progress is false)
  std::ostream* log = nullptr; ///< extra copy of the log (stdout by the CLI)
  std::string restart;         ///< a checkpoint to continue from (solvers/checkpoint.hpp); empty: from t = 0
  /// false: nothing is written (no folder, log, Exodus file, CSV or checkpoint); the history rows are still kept
  /// in memory (Run::history). A calibration loop runs a deck hundreds of times and reads its history.
  bool write_files = true;
  /// SIGINT, SIGTERM and SIGUSR1 stop the run after a step. The Python module leaves them to Python, which looks
  /// for its own KeyboardInterrupt between steps.
  bool catch_signals = true;
};

/// The history rows a run has written, kept in memory on rank 0: the CSV file's columns, and its rows one after
/// another (values.size() = rows × columns.size()).
struct HistoryRows {
  std::vector<std::string> columns;
  std::vector<double> values;
};

/// How a run that returned ended.
struct RunOutcome {
  int signal = 0;  ///< 0: it ran to its end; else the signal (SIGINT, SIGTERM, SIGUSR1) that stopped it after a step
};

/// Runs the problem. Throws InputError (before writing anything) or NumericalError (after closing every
/// output written so far). The results (Exodus file, history, resolved deck) are written as NAME.partial and
/// moved into place, replacing those of an earlier run, when the run ends: completed or failed numerically.
/// SIGINT, SIGTERM and SIGUSR1 stop it after the current step (distributed: within 32 steps, all ranks after
/// the same one) with that step's frame and row written; its
/// results then stay NAME.partial beside the earlier run's, which are untouched (so does a killed run's). A
/// second signal ends the process at once.
/// Checkpoints (output.checkpoint) go to checkpoint_<step>.nc in the output folder, every N steps, every so much
/// wall-clock time, at the end and when a signal stops the run; the newest `keep` this run wrote are kept.
/// A restart (options.restart) checks the checkpoint (InputError, nothing written), continues from its step,
/// appends to run.log, and writes new results that begin with the earlier run's frames and rows up to the
/// checkpoint's step (from NAME.partial of a stopped run, else NAME), those on the schedule only: the files
/// end up byte for byte those of a run never stopped.
RunOutcome run_problem(const Problem& problem, const RunOptions& options);

/// A run taken in pieces (what run_problem does, for a program that steps it, reads its fields and changes its
/// loads between pieces: the Python module). The outputs are those of run_problem, byte for byte, however the
/// steps are split.
class Run {
 public:
  /// Sets the problem up (InputError, nothing written), opens the outputs, and writes step 0 (or restores
  /// options.restart). Collective.
  Run(const Problem& problem, const RunOptions& options);
  /// A run not finished closes its results and leaves them as NAME.partial, as a stopped run does.
  ~Run();
  Run(const Run&) = delete;
  Run& operator=(const Run&) = delete;

  Simulation& simulation();
  const Simulation& simulation() const;
  /// Steps to `last_step` (at most simulation().total_steps()), writing the frames, rows and checkpoints due.
  /// Returns 0, or the signal that stopped it after a step (options.catch_signals). NumericalError: the
  /// results written so far are closed and moved into place, and the run is finished. Collective.
  int advance(std::int64_t last_step);
  /// Writes this step's frame and row unless written already, closes the results and moves them into place.
  /// A run may finish before its end (Python's run to a time). Collective.
  void finish();
  /// After advance returned a signal: closes the results as NAME.partial and says how to restart.
  void stopped(int signal);
  bool finished() const;
  /// The history rows written so far (rank 0; empty elsewhere and without history output).
  const HistoryRows& history() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

/// The summary `peridot check` prints: points, bonds, memory, time steps.
std::string describe_setup(const Simulation& simulation);

/// Writes text to path through a temporary file and a rename, so the file is either absent or whole (the
/// resolved deck; import-peridigm's deck and files). Throws std::runtime_error when it cannot.
void write_file_atomically(const std::string& path, const std::string& text);

/// The optional point fields (point_fields() registry, not FieldScope::always) this problem has and writes.
std::vector<std::string> optional_exodus_fields(const Simulation& sim);

/// Value of a probe field ("displacement_x", "damage", …; probe_field_names() in state/point_fields.hpp)
/// at point i; throws std::out_of_range for a name that is not one.
double point_field(const State& state, const std::string& field, std::size_t i);

}  // namespace peridot
