#pragma once
// Checkpoint and restart (docs/design.md "Checkpoint and restart"). A checkpoint holds every array of
// Simulation::state_arrays() (the state, the models' histories, broken bonds, the energy criterion, the
// correspondence stresses, the rigid bodies, the solver's own state, the step and the time) by global point
// index (serial: one file in the global order; distributed: one piece per rank, output/checkpoint_file.hpp),
// so that a run restarts bitwise on any number of ranks and threads. What the set-up computes
// from the deck (points, bonds, volumes, shape tensors, load expressions) is not stored: the restart builds it
// again from the same deck, runs initialize(), then overwrites the state with the checkpoint's.
// A restart refuses, before writing anything (InputError, exit 2): another code version, another deck (its
// resolved form, less the output settings and the end), another Δt, and a file that is damaged.
#include <string>
#include <vector>

#include "peridot/deck/problem.hpp"
#include "peridot/output/checkpoint_file.hpp"
#include "peridot/solvers/simulation.hpp"

namespace peridot {

/// "0.1.0 (COMMIT)": the project version and the commit this build is from.
std::string code_version();

/// The deck a checkpoint belongs to: the resolved deck without its output settings, end time and step count,
/// which a restart may change.
std::string checkpoint_fingerprint(const Problem& problem);

/// Every array of sim.state_arrays(): serial, the whole problem; distributed, this rank's piece (its owned
/// points with their global indices; nothing is gathered), written by each rank to its own file
/// (checkpoint_<step>.nc.N.r). Collective.
CheckpointData collect_checkpoint(Simulation& sim);

/// A checkpoint's files (one, or a distributed run's pieces in rank order) and the first one's contents.
struct CheckpointSource {
  std::vector<std::string> files;
  CheckpointData first;
};

/// Reads the checkpoint at path (a file, or the pieces path.N.r; a piece's own name stands for its set) for a
/// restart of sim's problem (before initialize()) and checks the code version, the deck and Δt. Throws
/// InputError (every rank the same) naming the file and what differs.
CheckpointSource read_checkpoint(const std::string& path, const Simulation& sim);

/// Puts the checkpoint's values into sim, after sim.initialize(): each rank reads the files one after the
/// other (those whose points' box, listed in the first piece, meets the box of its own points) and keeps its
/// own points' values (owned and ghosts), whatever rank count wrote them; returns how many files this rank
/// read. Throws InputError on every rank when the arrays or points do not fit this problem's. Collective.
std::size_t restore_checkpoint(Simulation& sim, CheckpointSource& source, const std::string& path);

}  // namespace peridot
