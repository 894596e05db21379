#include "peridot/loads/node_sets.hpp"

#include <algorithm>
#include <cctype>
#include <fstream>
#include <set>

#include <fmt/format.h>
#include <fmt/ranges.h>

namespace peridot {

namespace {

/// Input id (the order in which points were generated or read) → storage index of the points `disc` holds.
class StorageOf {
 public:
  explicit StorageOf(const Discretization& disc) {
    for (std::size_t i = 0; i < disc.num_points(); ++i) pairs_.push_back({disc.input_id[i], static_cast<std::uint32_t>(i)});
    std::sort(pairs_.begin(), pairs_.end());
  }
  /// Appends the point of input id `id` to `points`, when this discretization holds it.
  void add(std::uint32_t id, std::vector<std::uint32_t>& points) const {
    const auto found = std::lower_bound(pairs_.begin(), pairs_.end(), std::pair{id, std::uint32_t{0}});
    if (found != pairs_.end() && found->first == id) points.push_back(found->second);
  }

 private:
  std::vector<std::pair<std::uint32_t, std::uint32_t>> pairs_;
};

std::vector<std::uint32_t> read_ids(const NodeSetSpec& spec, const Discretization& disc, std::size_t all_points) {
  std::ifstream in(spec.ids_file);
  if (!in) throw InputError(spec.pos, "node_sets." + spec.name + ": cannot open ids_file '" + spec.ids_file + "'");
  const StorageOf storage_of(disc);
  std::vector<std::uint32_t> points;
  long long id;
  while (in >> id) {
    if (id < 0 || static_cast<std::size_t>(id) >= all_points)
      throw InputError(spec.pos, "node_sets." + spec.name + ": id " + std::to_string(id) + " in '" + spec.ids_file +
                                     "' is outside 0 … " + std::to_string(all_points - 1));
    storage_of.add(static_cast<std::uint32_t>(id), points);
  }
  if (!in.eof()) throw InputError(spec.pos, "node_sets." + spec.name + ": '" + spec.ids_file + "' holds a non-integer");
  return points;
}

std::vector<std::uint32_t> select_in_shape(const NodeSetSpec& spec, const Problem& problem, const Discretization& disc) {
  std::vector<char> body_selected(disc.block_names.size(), spec.bodies.empty());
  for (const std::string& body : spec.bodies)
    for (std::size_t b = 0; b < disc.block_names.size(); ++b)
      if (disc.block_names[b] == body) body_selected[b] = 1;
  std::vector<std::uint32_t> points;
  for (std::size_t i = 0; i < disc.num_points(); ++i)
    if (body_selected[disc.block[i]] && spec.shape->contains(disc.x.get(i), problem.dimension))
      points.push_back(static_cast<std::uint32_t>(i));
  return points;
}

/// The points of the bodies' mesh sets named spec.mesh_set: the name as written, else without case (Abaqus names
/// are in capitals), in every body the spec takes.
std::vector<std::uint32_t> select_from_mesh(const NodeSetSpec& spec, const Discretization& disc) {
  std::vector<char> body_selected(disc.block_names.size(), spec.bodies.empty());
  for (const std::string& body : spec.bodies)
    for (std::size_t b = 0; b < disc.block_names.size(); ++b)
      if (disc.block_names[b] == body) body_selected[b] = 1;
  auto upper = [](std::string text) {
    for (char& c : text) c = static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
    return text;
  };
  std::vector<const Discretization::MeshSet*> exact, folded;
  std::set<std::string> known;
  for (const Discretization::MeshSet& set : disc.mesh_sets) {
    if (!body_selected[set.block]) continue;
    known.insert(set.name);
    if (set.name == spec.mesh_set) exact.push_back(&set);
    else if (upper(set.name) == upper(spec.mesh_set)) folded.push_back(&set);
  }
  const auto& chosen = exact.empty() ? folded : exact;
  if (chosen.empty())
    throw InputError(spec.pos, fmt::format("node_sets.{}: the meshes of {} have no node, side or element set '{}'; they "
                                           "have: {}",
                                           spec.name, spec.bodies.empty() ? "the bodies" : "its bodies", spec.mesh_set,
                                           known.empty() ? "none" : fmt::format("{}", fmt::join(known, ", "))));
  const StorageOf storage_of(disc);
  std::vector<std::uint32_t> points;
  for (const Discretization::MeshSet* set : chosen)
    for (std::uint32_t id : set->input_ids) storage_of.add(id, points);
  return points;
}

}  // namespace

Diagnostic empty_node_set_error(const NodeSetSpec& spec) {
  return {spec.pos, "node_sets." + spec.name +
                        (spec.mesh_set.empty() ? ": selects no point (check its shape against the bodies)"
                                               : ": mesh set '" + spec.mesh_set + "' selects no point of " +
                                                     (spec.bodies.empty() ? "the bodies" : "its bodies"))};
}

std::vector<NodeSet> build_node_sets(const Problem& problem, const Discretization& disc, std::size_t all_points) {
  const bool part = all_points > 0;
  if (!part) all_points = disc.num_points();
  std::vector<NodeSet> sets;
  std::vector<Diagnostic> errors;
  for (const NodeSetSpec& spec : problem.node_sets) {
    NodeSet set{spec.name, {}};
    try {
      set.points = spec.shape               ? select_in_shape(spec, problem, disc)
                   : !spec.mesh_set.empty() ? select_from_mesh(spec, disc)
                                            : read_ids(spec, disc, all_points);
    } catch (const InputError& e) {
      errors.insert(errors.end(), e.diagnostics().begin(), e.diagnostics().end());
      continue;
    }
    std::sort(set.points.begin(), set.points.end());
    set.points.erase(std::unique(set.points.begin(), set.points.end()), set.points.end());
    if (set.points.empty() && !part) errors.push_back(empty_node_set_error(spec));
    sets.push_back(std::move(set));
  }
  if (!errors.empty()) throw InputError(errors);
  return sets;
}

const std::vector<std::uint32_t>& points_of(const std::vector<NodeSet>& sets, const std::string& name,
                                            const std::vector<std::uint32_t>& all_points) {
  if (name.empty()) return all_points;
  for (const NodeSet& set : sets)
    if (set.name == name) return set.points;
  PERIDOT_REQUIRE(false, "unknown node set '" + name + "'");
}

}  // namespace peridot
