#pragma once
// Checkpoint and restart (docs/design.md "Checkpoint and restart"). A checkpoint holds every array of
// Simulation::state_arrays() (the state, the models' histories, broken bonds, the energy criterion, the
// correspondence stresses, the rigid bodies, the solver's own state, the step and the time) in the global
// point order, so that a run restarts bitwise on any number of ranks and threads. What the set-up computes
// from the deck (points, bonds, volumes, shape tensors, load expressions) is not stored: the restart builds it
// again from the same deck, runs initialize(), then overwrites the state with the checkpoint's.
// A restart refuses, before writing anything (InputError, exit 2): another code version, another deck (its
// resolved form, less the output settings and the end), another Δt, and a file that is damaged.
#include <string>

#include "peridot/deck/problem.hpp"
#include "peridot/output/checkpoint_file.hpp"
#include "peridot/solvers/simulation.hpp"

namespace peridot {

/// "0.1.0 (COMMIT)": the project version and the commit this build is from.
std::string code_version();

/// The deck a checkpoint belongs to: the resolved deck without its output settings, end time and step count,
/// which a restart may change.
std::string checkpoint_fingerprint(const Problem& problem);

/// Every array of sim.state_arrays(), gathered into the global order on rank 0 (the other ranks get an empty
/// result). Collective.
CheckpointData collect_checkpoint(Simulation& sim);

/// Reads the checkpoint at path for a restart of sim's problem (before initialize()) and checks the code
/// version, the deck and Δt. Throws InputError (every rank the same) naming the file and what differs.
CheckpointData read_checkpoint(const std::string& path, const Simulation& sim);

/// Puts the checkpoint's values into sim, after sim.initialize(). Throws InputError on every rank when its
/// arrays do not fit this problem's. Collective.
void restore_checkpoint(Simulation& sim, const CheckpointData& data, const std::string& path);

}  // namespace peridot
