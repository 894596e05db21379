#pragma once
// Node sets: the points a shape selects (optionally only from some bodies), or an id file.
#include <cstdint>
#include <string>
#include <vector>

#include "peridot/deck/problem.hpp"
#include "peridot/state/fields.hpp"

namespace peridot {

struct NodeSet {
  std::string name;
  std::vector<std::uint32_t> points;  ///< increasing point indices
};

/// Every node set of the deck. Throws InputError listing every set that selects no point (at its deck
/// position) and every unreadable or out-of-range id file. all_points > 0: `disc` is one rank's part of a
/// problem of all_points points (ids are checked against that; an empty set is not an error here, the
/// caller sums the ranks' counts: empty_node_set_error).
std::vector<NodeSet> build_node_sets(const Problem& problem, const Discretization& disc, std::size_t all_points = 0);
/// The error build_node_sets reports for a set that selects no point.
Diagnostic empty_node_set_error(const NodeSetSpec& spec);

/// The set named `name` (empty name = every point). The deck stage has already checked the name exists.
const std::vector<std::uint32_t>& points_of(const std::vector<NodeSet>& sets, const std::string& name,
                                            const std::vector<std::uint32_t>& all_points);

}  // namespace peridot
