#pragma once
// Runs a validated problem to its end: writes the resolved deck and a run log, Exodus frames and CSV
// history, and prints a progress line. Output starts only once the whole problem has been set up, so a
// deck problem found at set-up (an empty node set) leaves nothing behind.
#include <iosfwd>
#include <string>

#include "peridot/deck/problem.hpp"
#include "peridot/solvers/simulation.hpp"

namespace peridot {

struct RunOptions {
  bool progress = true;        ///< progress line on stderr (also off when output.progress is false)
  std::ostream* log = nullptr; ///< extra copy of the log (stdout by the CLI)
  std::string restart;         ///< a checkpoint to continue from (solvers/checkpoint.hpp); empty: from t = 0
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

/// The summary `peridot check` prints: points, bonds, memory, time steps.
std::string describe_setup(const Simulation& simulation);

/// Value of a probe field ("displacement_x", "damage", …; probe_field_names() in state/point_fields.hpp)
/// at point i; throws std::out_of_range for a name that is not one.
double point_field(const State& state, const std::string& field, std::size_t i);

}  // namespace peridot
