#include "peridot/parallel/domain.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>

#include "peridot/core/bounding_box.hpp"
#include "peridot/core/error.hpp"
#include "peridot/geometry/discretize.hpp"
#include "peridot/parallel/box_search.hpp"
#include "peridot/parallel/global_order.hpp"
#include "peridot/parallel/partition.hpp"

namespace peridot {

namespace {

/// This rank's domain from a set of points `all` (the whole problem, or the rank's owned points and its
/// candidates for ghosts) holding every partner of the owned points: global_of(t) and owner_of(t) of each,
/// `owned` (indices into `all`, increasing global index) and their families (neighbours: indices into `all`,
/// in increasing global index).
template <class GlobalOf, class OwnerOf>
LocalDomain assemble(const Communicator& comm, const Discretization& all, const std::vector<std::uint32_t>& owned,
                     BondList families, GlobalOf&& global_of, OwnerOf&& owner_of) {
  LocalDomain d;
  // Ghosts: partners owned elsewhere, grouped by owner rank, increasing global index within a group.
  std::vector<std::uint8_t> partner(all.num_points(), 0);
  for (std::uint32_t j : families.neighbors) partner[j] = 1;
  std::vector<std::uint32_t> ghosts;
  for (std::size_t t = 0; t < partner.size(); ++t)
    if (partner[t] && owner_of(static_cast<std::uint32_t>(t)) != comm.rank()) ghosts.push_back(static_cast<std::uint32_t>(t));
  partner = {};
  std::sort(ghosts.begin(), ghosts.end(), [&](std::uint32_t a, std::uint32_t b) {
    return owner_of(a) != owner_of(b) ? owner_of(a) < owner_of(b) : global_of(a) < global_of(b);
  });
  std::vector<int> ghost_owner;
  for (std::uint32_t g : ghosts) ghost_owner.push_back(owner_of(g));

  d.owned = owned.size();
  std::vector<std::uint32_t> source = owned;  // local → index into `all`
  source.insert(source.end(), ghosts.begin(), ghosts.end());
  const std::size_t local = source.size();
  std::vector<std::uint32_t> local_of(all.num_points(), UINT32_MAX);
  for (std::size_t l = 0; l < local; ++l) local_of[source[l]] = static_cast<std::uint32_t>(l);

  d.disc.dimension = all.dimension;
  d.disc.block_names = all.block_names;
  d.disc.x.resize(local);
  d.disc.volume.resize(local);
  d.disc.block.resize(local);
  d.disc.input_id.resize(local);
  d.global_index.resize(local);
  for (std::size_t l = 0; l < local; ++l) {
    const std::uint32_t t = source[l];
    d.global_index[l] = global_of(t);
    d.disc.x.set(l, all.x.get(t));
    d.disc.volume[l] = all.volume[t];
    d.disc.block[l] = all.block[t];
    d.disc.input_id[l] = all.input_id.empty() ? t : all.input_id[t];
  }

  // The families become the bonds, renumbered in place (the bonds are most of a rank's memory: no copy).
  d.bonds = std::move(families);
  d.bonds.offsets.resize(local + 1, d.bonds.offsets.back());  // ghosts: empty families
  for (std::uint32_t& j : d.bonds.neighbors) j = local_of[j];
  d.bonds.broken.assign(d.bonds.neighbors.size(), 0);
  // Each owner is asked for the points this rank holds as ghosts: one global index per ghost.
  std::vector<int> count(static_cast<std::size_t>(comm.size()), 0);
  for (int r : ghost_owner) ++count[r];
  std::vector<std::uint32_t> requests(ghosts.size());
  for (std::size_t g = 0; g < ghosts.size(); ++g) requests[g] = global_of(ghosts[g]);
  const auto owned_begin = d.global_index.begin(), owned_end = owned_begin + static_cast<std::ptrdiff_t>(d.owned);
  d.halo = Halo::serve(comm, d.owned, requests, count, 1, [&](const std::uint32_t* global) {
    const auto found = std::lower_bound(owned_begin, owned_end, *global);
    PERIDOT_REQUIRE(found != owned_end && *found == *global, "a ghost was asked of a rank that does not own it");
    return static_cast<std::uint32_t>(found - owned_begin);
  });
  d.ghost_owner = std::move(ghost_owner);
  return d;
}

/// Points travelling between ranks: four integers and four doubles each.
struct PointPacket {
  std::vector<std::uint32_t> ints;  ///< global index, input id, block, layer flag
  std::vector<double> reals;        ///< x, y, z, volume
  void add(std::uint32_t global, std::uint32_t input, std::int32_t block, std::uint8_t layer, Vec3 x, double volume) {
    ints.insert(ints.end(), {global, input, static_cast<std::uint32_t>(block), layer});
    reals.insert(reals.end(), {x.x, x.y, x.z, volume});
  }
  std::size_t size() const { return ints.size() / 4; }
};

/// Sends the points of `out` (count[r] to rank r, rank after rank) and returns those received with the rank
/// each came from.
PointPacket send_points(const Communicator& comm, const PointPacket& out, const std::vector<int>& count,
                        std::vector<int>& source) {
  std::vector<int> int_count(count.size()), real_count(count.size()), received;
  for (std::size_t r = 0; r < count.size(); ++r) int_count[r] = real_count[r] = 4 * count[r];
  PointPacket in;
  in.ints = comm.all_to_all(out.ints, int_count, received);
  in.reals = comm.all_to_all(out.reals, real_count, received);
  source.clear();
  for (std::size_t r = 0; r < received.size(); ++r) source.insert(source.end(), static_cast<std::size_t>(received[r] / 4), static_cast<int>(r));
  return in;
}

}  // namespace

LocalDomain decompose(const Communicator& comm, const Problem& problem, const NeighborhoodOptions& options,
                      PartitionMethod method) {
  const int dim = problem.dimension, ranks = comm.size();
  const double dx = problem.spacing;
  // 1. This rank's box of the lattice (a recursive bisection weighted by the bodies' estimated site counts),
  //    and the points one reach beyond it on every side.
  const LatticeExtent extent = lattice_extent(problem);
  const SiteBox box = bisected_site_box(problem, comm.rank(), ranks);
  const double max_horizon = *std::max_element(options.horizon_of_block.begin(), options.horizon_of_block.end());
  // Every bond the neighbour search admits (horizon, partial-volume ring, its round-off allowance) is shorter.
  const double reach = (max_horizon + (options.bond_beyond_horizon ? options.partial_volume_radius : 0.0)) * (1 + 1e-6);
  const long reach_planes = static_cast<long>(std::ceil(reach / dx)) + 1;
  SiteBox window = box;
  for (int d = 0; d < dim; ++d) window.lo[d] -= reach_planes, window.hi[d] += reach_planes;
  LatticePoints made = discretize_window(problem, window);
  const std::size_t made_count = made.disc.num_points();
  auto in_box = [&](std::size_t k) {  // the site is in this rank's own box
    std::uint64_t site = made.site[k];
    long index[3];
    for (int d = 0; d < 3; ++d) {
      index[d] = static_cast<long>(site % static_cast<std::uint64_t>(extent.count(d))) + extent.lo[d];
      site /= static_cast<std::uint64_t>(extent.count(d));
    }
    return box.holds(index[0], index[1], index[2]);
  };
  // The box's points first, then the others (kept in generation order within each).
  std::vector<std::uint32_t> order;
  for (std::size_t k = 0; k < made_count; ++k)
    if (in_box(k)) order.push_back(static_cast<std::uint32_t>(k));
  std::size_t mine = order.size();
  for (std::size_t k = 0; k < made_count; ++k)
    if (!in_box(k)) order.push_back(static_cast<std::uint32_t>(k));
  Discretization generated;
  generated.dimension = dim;
  generated.block_names = made.disc.block_names;
  generated.x.resize(made_count);
  generated.volume.resize(made_count);
  generated.block.resize(made_count);
  std::vector<std::uint64_t> site(mine);
  std::vector<std::uint8_t> layer(mine);
  for (std::size_t k = 0; k < made_count; ++k) {
    const std::uint32_t from = order[k];
    generated.x.set(k, made.disc.x.get(from));
    generated.volume[k] = made.disc.volume[from];
    generated.block[k] = made.disc.block[from];
    if (k < mine) site[k] = made.site[from], layer[k] = made.layer[from];
  }
  made = LatticePoints{};
  std::vector<std::uint64_t> bond_count = count_bonds(generated, options, 0, mine);

  // Then this rank's share of the point-file and mesh bodies (read_file_bodies): after the box's lattice points,
  // in place of the window's others. Their third key is their place in the body's file (the generation order);
  // their partners are not here, so their Zoltan weight is a full family's bond count estimated from the volume.
  FilePoints files = read_file_bodies(problem, comm.rank(), ranks);
  {
    const std::size_t from_files = files.disc.num_points();
    Discretization both;
    both.dimension = dim;
    both.block_names = generated.block_names;
    both.x.resize(mine + from_files);
    for (std::size_t k = 0; k < mine; ++k) both.x.set(k, generated.x.get(k));
    for (std::size_t k = 0; k < from_files; ++k) both.x.set(mine + k, files.disc.x.get(k));
    both.volume.assign(generated.volume.begin(), generated.volume.begin() + static_cast<std::ptrdiff_t>(mine));
    both.volume.insert(both.volume.end(), files.disc.volume.begin(), files.disc.volume.end());
    both.block.assign(generated.block.begin(), generated.block.begin() + static_cast<std::ptrdiff_t>(mine));
    both.block.insert(both.block.end(), files.disc.block.begin(), files.disc.block.end());
    generated = std::move(both);
    site.insert(site.end(), files.place.begin(), files.place.end());
    layer.resize(mine + from_files, 0);
    const double measure = dim == 3 ? 4.18879020478639 : dim == 2 ? 3.14159265358979 : 2.0;  // unit ball
    for (std::size_t k = 0; k < from_files; ++k) {
      const double delta = options.horizon_of_block[static_cast<std::size_t>(files.disc.block[k])];
      const double cell = files.disc.volume[k] / problem.cross_section();
      bond_count.push_back(static_cast<std::uint64_t>(std::max(1.0, std::round(measure * std::pow(delta, dim) / cell))));
    }
    mine += from_files;
    files.disc = Discretization{};
    files.place = {};
  }

  // Empty bodies and layers, from every box's count; each block's first input id.
  const std::size_t blocks = problem.bodies.size();
  std::vector<Diagnostic> errors;
  std::vector<std::uint64_t> first_input(blocks + 1, 0);
  for (std::size_t b = 0; b < blocks; ++b) {
    std::uint64_t points = 0, layer_points = 0;
    for (std::size_t k = 0; k < mine; ++k)
      if (generated.block[k] == static_cast<std::int32_t>(b)) (layer[k] ? layer_points : points) += 1;
    points = comm.sum(points);
    layer_points = comm.sum(layer_points);
    first_input[b + 1] = first_input[b] + points + layer_points;
    const BodySpec& body = problem.bodies[b];
    if (points == 0) errors.push_back({body.pos, "bodies." + body.name + ": the body contains no point (is it smaller than the spacing?)"});
    else if (body.volume_constraint > 0 && layer_points == 0)
      errors.push_back({body.pos, "bodies." + body.name +
                                      ".volume_constraint: the layer holds no lattice site (is it thinner than the "
                                      "spacing, or inside other bodies?)"});
  }
  if (!errors.empty()) throw InputError(errors);

  // 2. Storage order and generation order over all boxes.
  const std::uint64_t total = comm.sum(static_cast<std::uint64_t>(mine));
  PERIDOT_REQUIRE(total <= UINT32_MAX, "more than 2^32 points: global indices need 64 bits");
  Vec3 lo{1e300, 1e300, 1e300};
  double min_spacing = 1e300;
  for (std::size_t k = 0; k < mine; ++k) {
    for (int d = 0; d < 3; ++d) lo[d] = std::min(lo[d], generated.x(k, d));
    min_spacing = std::min(min_spacing, cell_side(generated.volume[k], problem));
  }
  for (int d = 0; d < 3; ++d) lo[d] = comm.min(lo[d]);
  min_spacing = comm.min(min_spacing);
  std::vector<OrderKey> key(mine);
  for (std::size_t k = 0; k < mine; ++k) {
    const auto block = static_cast<std::uint64_t>(generated.block[k]);
    key[k] = {block, morton_key(generated.x.get(k), lo, min_spacing, dim), std::uint64_t{layer[k]} << 62 | site[k]};
  }
  const std::vector<std::uint64_t> global = global_ranks(comm, key);
  for (std::size_t k = 0; k < mine; ++k) key[k] = {static_cast<std::uint64_t>(generated.block[k]), layer[k], site[k]};
  const std::vector<std::uint64_t> input = global_ranks(comm, key);
  key = {};

  // 3. Owners; every point of the box goes to its owner.
  std::vector<std::uint32_t> box_global(global.begin(), global.end());
  Discretization box_points;  // the box's own points, for Zoltan
  box_points.dimension = dim;
  box_points.x.resize(mine);
  box_points.volume.assign(generated.volume.begin(), generated.volume.begin() + static_cast<std::ptrdiff_t>(mine));
  for (std::size_t k = 0; k < mine; ++k) box_points.x.set(k, generated.x.get(k));
  const std::vector<int> owner = partition_points(comm, box_points, box_global, bond_count, method);
  box_points = Discretization{};
  std::vector<std::uint32_t> by_owner(mine);
  std::iota(by_owner.begin(), by_owner.end(), 0u);
  std::stable_sort(by_owner.begin(), by_owner.end(), [&](std::uint32_t a, std::uint32_t b) { return owner[a] < owner[b]; });
  std::vector<int> count(static_cast<std::size_t>(ranks), 0), source;
  PointPacket out;
  for (std::uint32_t k : by_owner) {
    ++count[static_cast<std::size_t>(owner[k])];
    out.add(box_global[k], static_cast<std::uint32_t>(input[k]), generated.block[k], layer[k], generated.x.get(k), generated.volume[k]);
  }
  generated = Discretization{};
  PointPacket owned = send_points(comm, out, count, source);
  out = PointPacket{};

  // 4. Candidates for ghosts: every other rank's points within a reach of this rank's owned points.
  const std::vector<double> boxes = comm.all_gather(bounding_box(owned.reals.data(), 4, owned.size()).widened(reach).six());
  const std::vector<std::vector<std::uint32_t>> inside = points_in_boxes(owned.reals.data(), 4, owned.size(), boxes, comm.rank());
  for (int r = 0; r < ranks; ++r) {
    count[static_cast<std::size_t>(r)] = static_cast<int>(inside[static_cast<std::size_t>(r)].size());
    for (const std::uint32_t k : inside[static_cast<std::size_t>(r)]) {
      out.ints.insert(out.ints.end(), owned.ints.begin() + static_cast<std::ptrdiff_t>(4 * k), owned.ints.begin() + static_cast<std::ptrdiff_t>(4 * k + 4));
      out.reals.insert(out.reals.end(), owned.reals.begin() + static_cast<std::ptrdiff_t>(4 * k), owned.reals.begin() + static_cast<std::ptrdiff_t>(4 * k + 4));
    }
  }
  std::vector<int> candidate_owner;
  const PointPacket candidates = send_points(comm, out, count, candidate_owner);
  out = PointPacket{};

  // Owned points and candidates in increasing global index: a family built over them is sorted as the serial one.
  const std::size_t owned_count = owned.size(), all_count = owned_count + candidates.size();
  auto packet_of = [&](std::size_t t) -> std::pair<const PointPacket*, std::size_t> {
    return t < owned_count ? std::pair{&owned, t} : std::pair{&candidates, t - owned_count};
  };
  std::vector<std::uint32_t> sorted(all_count);
  std::iota(sorted.begin(), sorted.end(), 0u);
  auto global_of_packet = [&](std::size_t t) { const auto [p, k] = packet_of(t); return p->ints[4 * k]; };
  std::sort(sorted.begin(), sorted.end(), [&](std::uint32_t a, std::uint32_t b) { return global_of_packet(a) < global_of_packet(b); });
  Discretization all;
  all.dimension = dim;
  for (const BodySpec& body : problem.bodies) all.block_names.push_back(body.name);
  all.x.resize(all_count);
  all.volume.resize(all_count);
  all.block.resize(all_count);
  all.input_id.resize(all_count);
  std::vector<std::uint32_t> all_global(all_count);
  std::vector<int> all_owner(all_count);
  std::vector<std::uint8_t> all_layer(all_count);
  std::vector<std::uint32_t> owned_in_all;
  for (std::size_t t = 0; t < all_count; ++t) {
    const auto [p, k] = packet_of(sorted[t]);
    all_global[t] = p->ints[4 * k];
    PERIDOT_REQUIRE(t == 0 || all_global[t] > all_global[t - 1], "a point reached a rank twice");
    all.input_id[t] = p->ints[4 * k + 1];
    all.block[t] = static_cast<std::int32_t>(p->ints[4 * k + 2]);
    all_layer[t] = static_cast<std::uint8_t>(p->ints[4 * k + 3]);
    all.x.set(t, Vec3{p->reals[4 * k], p->reals[4 * k + 1], p->reals[4 * k + 2]});
    all.volume[t] = p->reals[4 * k + 3];
    all_owner[t] = sorted[t] < owned_count ? comm.rank() : candidate_owner[sorted[t] - owned_count];
    if (sorted[t] < owned_count) owned_in_all.push_back(static_cast<std::uint32_t>(t));
  }
  LocalDomain d = assemble(comm, all, owned_in_all, build_neighborhood(all, options, owned_in_all), [&](std::uint32_t t) { return all_global[t]; },
                           [&](std::uint32_t t) { return all_owner[t]; });
  d.global_points = total;
  // The volume-constraint layers and the meshes' sets, by input id, over the rank's points, in the serial order
  // (body after body).
  std::vector<std::uint32_t> local_inputs = d.disc.input_id;
  std::sort(local_inputs.begin(), local_inputs.end());
  for (std::size_t b = 0; b < blocks; ++b) {
    if (problem.bodies[b].volume_constraint > 0) {
      Discretization::MeshSet& set = d.disc.mesh_sets.emplace_back();
      set.name = problem.bodies[b].name + "_constraint";
      set.block = static_cast<std::int32_t>(b);
      for (std::size_t l = 0; l < d.global_index.size(); ++l) {
        const auto t = static_cast<std::size_t>(std::lower_bound(all_global.begin(), all_global.end(), d.global_index[l]) - all_global.begin());
        if (all_layer[t] && all.block[t] == static_cast<std::int32_t>(b)) set.input_ids.push_back(d.disc.input_id[l]);
      }
    }
    for (const Discretization::MeshSet& read : files.sets) {
      if (read.block != static_cast<std::int32_t>(b)) continue;
      Discretization::MeshSet& set = d.disc.mesh_sets.emplace_back();
      set.name = read.name;
      set.block = read.block;
      for (std::uint32_t place : read.input_ids) {
        const auto id = static_cast<std::uint32_t>(first_input[b] + place);
        if (std::binary_search(local_inputs.begin(), local_inputs.end(), id)) set.input_ids.push_back(id);
      }
    }
  }
  return d;
}

namespace {

/// The bond of local point i (owned) to the point of global index `partner`, found by binary search: a
/// family is sorted by global index.
std::uint64_t find_bond(const LocalDomain& d, std::size_t i, std::uint32_t partner) {
  const auto& nb = d.bonds.neighbors;
  std::uint64_t lo = d.bonds.offsets[i], hi = d.bonds.offsets[i + 1];
  while (lo < hi) {
    const std::uint64_t mid = (lo + hi) / 2;
    if (d.global_index[nb[mid]] < partner) lo = mid + 1;
    else hi = mid;
  }
  PERIDOT_REQUIRE(lo < d.bonds.offsets[i + 1] && d.global_index[nb[lo]] == partner, "bond families are not symmetric");
  return lo;
}

}  // namespace

Halo build_partner_bonds(const Communicator& comm, LocalDomain& d) {
  BondList& bonds = d.bonds;
  const std::size_t nnz = bonds.num_bonds();
  PERIDOT_REQUIRE(nnz <= UINT32_MAX, "more than 2^32 bonds on a rank: reverse bond indices need 64 bits");
  bonds.reverse.assign(nnz, 0);
  // Bonds to ghosts, grouped by the ghost's owner, in bond order within a group: one slot each.
  struct ToGhost {
    std::uint64_t bond;
    std::uint32_t point;  ///< its owned end
  };
  std::vector<ToGhost> to_ghost;
  for (std::size_t i = 0; i < d.owned; ++i)
    for (std::uint64_t b = bonds.offsets[i]; b < bonds.offsets[i + 1]; ++b) {
      const std::uint32_t j = bonds.neighbors[b];
      if (j < d.owned) bonds.reverse[b] = static_cast<std::uint32_t>(find_bond(d, j, d.global_index[i]));
      else to_ghost.push_back({b, static_cast<std::uint32_t>(i)});
    }
  auto owner_of = [&](const ToGhost& t) { return d.ghost_owner[bonds.neighbors[t.bond] - d.owned]; };
  std::stable_sort(to_ghost.begin(), to_ghost.end(), [&](const ToGhost& a, const ToGhost& b) { return owner_of(a) < owner_of(b); });
  PERIDOT_REQUIRE(nnz + to_ghost.size() <= UINT32_MAX, "more than 2^32 bonds and partner slots on a rank");
  bonds.partner_slots = to_ghost.size();

  // Each owner is asked for the bond j → i of every slot: (global j, global i).
  std::vector<int> count(static_cast<std::size_t>(comm.size()), 0);
  std::vector<std::uint32_t> requests;
  for (std::size_t k = 0; k < to_ghost.size(); ++k) {
    const ToGhost& t = to_ghost[k];
    bonds.reverse[t.bond] = static_cast<std::uint32_t>(nnz + k);
    ++count[owner_of(t)];
    requests.push_back(d.global_index[bonds.neighbors[t.bond]]);
    requests.push_back(d.global_index[t.point]);
  }
  const auto owned_begin = d.global_index.begin(), owned_end = owned_begin + static_cast<std::ptrdiff_t>(d.owned);
  return Halo::serve(comm, nnz, requests, count, 2, [&](const std::uint32_t* pair) {
    const auto j = std::lower_bound(owned_begin, owned_end, pair[0]);
    PERIDOT_REQUIRE(j != owned_end && *j == pair[0], "a partner bond was asked of a rank that does not own it");
    return static_cast<std::uint32_t>(find_bond(d, static_cast<std::size_t>(j - owned_begin), pair[1]));
  });
}

}  // namespace peridot
