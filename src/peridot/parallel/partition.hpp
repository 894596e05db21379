#pragma once
// Which rank owns which point: a geometric partition by Zoltan (recursive coordinate bisection by
// default; recursive inertial bisection or a Hilbert space-filling curve on request) of the reference
// positions, each point weighted by its bond count so that the ranks get equal bond work. Computed once,
// from the reference configuration, each rank handing Zoltan the points it made (its box of the lattice) or
// read (its share of the point files and meshes), with their weights. For a given deck and rank count the result is the same on every run (Zoltan's RCB is
// deterministic), and a run's trajectory never depends on it.
#include <cstdint>
#include <vector>

#include "peridot/deck/problem.hpp"
#include "peridot/parallel/communicator.hpp"
#include "peridot/state/fields.hpp"

namespace peridot {

/// The owner rank of each of this rank's `points` (global ids and bond counts given), every rank handing
/// Zoltan the points it made or read (domain.hpp). Collective; on one rank every point is rank 0's, and with
/// fewer points than ranks every point stays where it was made.
std::vector<int> partition_points(const Communicator& comm, const Discretization& points,
                                        const std::vector<std::uint32_t>& global_id,
                                        const std::vector<std::uint64_t>& weight, PartitionMethod method);

}  // namespace peridot
