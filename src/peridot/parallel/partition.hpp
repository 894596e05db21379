#pragma once
// Which rank owns which point: a geometric partition by Zoltan (recursive coordinate bisection by
// default; recursive inertial bisection or a Hilbert space-filling curve on request) of the reference
// positions, each point weighted by its bond count so that the ranks get equal bond work. Computed once,
// from the reference configuration. Where every rank holds the whole discretization (point-file and mesh
// bodies), rank r hands Zoltan the points of its slice [r·N/P, (r+1)·N/P) with their weights, and every rank
// gets back the owner of every point; where each rank made its own points (partition_local_points), it hands
// Zoltan those. For a given deck and rank count the result is the same on every run (Zoltan's RCB is
// deterministic), and a run's trajectory never depends on it.
#include <cstdint>
#include <vector>

#include "peridot/deck/problem.hpp"
#include "peridot/parallel/communicator.hpp"
#include "peridot/state/fields.hpp"

namespace peridot {

/// [begin, end) of rank r's slice of n points.
inline std::size_t slice_begin(std::size_t n, int rank, int ranks) {
  return static_cast<std::size_t>((static_cast<unsigned __int128>(n) * static_cast<unsigned>(rank)) / static_cast<unsigned>(ranks));
}

/// Owner rank of every point. slice_weight: the bond counts of this rank's slice. Collective; on one rank
/// every point is rank 0's.
std::vector<int> partition_points(const Communicator& comm, const Discretization& disc,
                                  const std::vector<std::uint64_t>& slice_weight,
                                  PartitionMethod method = PartitionMethod::rcb);

/// Distributed generation (domain.hpp): the owner rank of each of this rank's `points` (global ids and bond
/// counts given), every rank handing Zoltan its own points. Collective; on one rank every point is rank 0's.
std::vector<int> partition_local_points(const Communicator& comm, const Discretization& points,
                                        const std::vector<std::uint32_t>& global_id,
                                        const std::vector<std::uint64_t>& weight, PartitionMethod method);

}  // namespace peridot
