#include "peridot/geometry/discretize.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <fstream>
#include <limits>
#include <map>
#include <numeric>
#include <sstream>

#include <unistd.h>

#include <fmt/format.h>

#include "peridot/geometry/mesh.hpp"

namespace peridot {

double uniform01(std::uint64_t& state) {
  std::uint64_t z = (state += 0x9E3779B97F4A7C15ull);
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
  z ^= z >> 31;
  return static_cast<double>(z >> 11) * 0x1.0p-53;
}

namespace {

struct RawPoint {
  Vec3 x;
  double volume;
  std::int32_t block;
  std::uint64_t morton;
  std::uint64_t site = 0;  ///< lattice points: linear index in the problem's lattice extent
  bool layer = false;      ///< a volume-constraint layer's point
};

/// Where lattice sites are made: every site, or (distributed) only those whose index along `axis` is in
/// [first, last).
/// Every site: the window of discretize().
SiteBox everywhere() {
  SiteBox box;
  for (int d = 0; d < 3; ++d) box.lo[d] = std::numeric_limits<long>::min(), box.hi[d] = std::numeric_limits<long>::max();
  return box;
}

/// [lo, hi] (inclusive) clipped to the window's half-open range along d.
void clip(const SiteBox& window, long lo[3], long hi[3]) {
  for (int d = 0; d < 3; ++d) {
    lo[d] = std::max(lo[d], window.lo[d]);
    hi[d] = std::min(hi[d], window.hi[d] == std::numeric_limits<long>::max() ? hi[d] : window.hi[d] - 1);
  }
}

// Interleaves the low 21 bits of three cell indices: points close in space get close codes.
std::uint64_t morton_code(std::uint32_t a, std::uint32_t b, std::uint32_t c) {
  auto spread = [](std::uint64_t v) {
    v &= 0x1fffff;
    v = (v | v << 32) & 0x1f00000000ffffull;
    v = (v | v << 16) & 0x1f0000ff0000ffull;
    v = (v | v << 8) & 0x100f00f00f00f00full;
    v = (v | v << 4) & 0x10c30c30c30c30c3ull;
    v = (v | v << 2) & 0x1249249249249249ull;
    return v;
  };
  return spread(a) | spread(b) << 1 | spread(c) << 2;
}

/// The lattice sites a shape body's bounding box, widened by `reach`, spans (one more on each side).
void site_range(const Problem& problem, const BodySpec& body, double reach, long lo[3], long hi[3]) {
  const BoundingBox box = body.shape->bounds(problem.dimension);
  for (int d = 0; d < 3; ++d) lo[d] = hi[d] = 0;
  for (int d = 0; d < problem.dimension; ++d) {
    lo[d] = static_cast<long>(std::floor((box.lo[d] - reach - problem.lattice_origin[d]) / problem.spacing - 0.5)) - 1;
    hi[d] = static_cast<long>(std::ceil((box.hi[d] + reach - problem.lattice_origin[d]) / problem.spacing - 0.5)) + 1;
  }
}

/// Moves a lattice point by its jitter: uniform in ±jitter·Δx along each axis, drawn from a stream seeded by the
/// deck's seed and the point's site alone (not by the order of generation), so that a rank making only part of
/// the lattice moves each point as a serial run does.
void jitter(const Problem& problem, std::int32_t block, bool layer, std::uint64_t site, Vec3& p) {
  if (!(problem.jitter > 0)) return;
  std::uint64_t state = problem.seed;
  for (std::uint64_t word : {static_cast<std::uint64_t>(block) << 1 | (layer ? 1u : 0u), site}) {
    state ^= word;
    uniform01(state);  // mixes the word into the state
  }
  for (int d = 0; d < problem.dimension; ++d) p[d] += (2 * uniform01(state) - 1) * problem.jitter * problem.spacing;
}

// A lattice site inside several bodies belongs to the first of them (bodies share one lattice).
bool claimed_by_earlier_body(const Problem& problem, std::int32_t block, Vec3 p) {
  for (std::int32_t b = 0; b < block; ++b) {
    const BodySpec& earlier = problem.bodies[b];
    if (earlier.shape && earlier.shape->contains(p, problem.dimension)) return true;
  }
  return false;
}

void fill_shape(const Problem& problem, std::int32_t block, const LatticeExtent& extent, const SiteBox& window,
                std::vector<RawPoint>& out) {
  const BodySpec& body = problem.bodies[block];
  const int dim = problem.dimension;
  const double dx = problem.spacing;
  const Vec3 origin = problem.lattice_origin;
  long lo[3], hi[3];
  site_range(problem, body, 0, lo, hi);
  clip(window, lo, hi);  // the same sites in the same order, those outside the window skipped
  const double volume = std::pow(dx, dim) * problem.cross_section();
  for (long k = lo[2]; k <= hi[2]; ++k)
    for (long j = lo[1]; j <= hi[1]; ++j)
      for (long i = lo[0]; i <= hi[0]; ++i) {
        Vec3 p{origin.x + (i + 0.5) * dx, dim >= 2 ? origin.y + (j + 0.5) * dx : 0.0, dim == 3 ? origin.z + (k + 0.5) * dx : 0.0};
        if (!body.shape->contains(p, dim) || claimed_by_earlier_body(problem, block, p)) continue;
        const std::uint64_t site = extent.site(i, j, k);
        jitter(problem, block, false, site, p);
        out.push_back({p, volume, block, 0, site, false});
      }
}

/// The volume-constraint layer of a shape body: the lattice sites outside every body's shape within
/// body.volume_constraint of one of this body's own sites, with its material; their indices in `out` go to
/// `layer`.
void fill_layer(const Problem& problem, std::int32_t block, const LatticeExtent& extent, const SiteBox& window,
                std::vector<RawPoint>& out, std::vector<std::uint32_t>& layer) {
  const BodySpec& body = problem.bodies[block];
  const int dim = problem.dimension;
  const double dx = problem.spacing, reach = body.volume_constraint;
  const Vec3 origin = problem.lattice_origin;
  const long steps = static_cast<long>(std::floor(reach / dx + 1e-9));
  // The lattice offsets within the thickness: a site is in the layer when one of them leads to a site of the body.
  std::vector<std::array<long, 3>> offsets;
  for (long k = dim == 3 ? -steps : 0; k <= (dim == 3 ? steps : 0); ++k)
    for (long j = dim >= 2 ? -steps : 0; j <= (dim >= 2 ? steps : 0); ++j)
      for (long i = -steps; i <= steps; ++i)
        if (static_cast<double>(i * i + j * j + k * k) * dx * dx <= reach * reach * (1 + 1e-12)) offsets.push_back({i, j, k});
  const auto site = [&](long i, long j, long k) {
    return Vec3{origin.x + (i + 0.5) * dx, dim >= 2 ? origin.y + (j + 0.5) * dx : 0.0, dim == 3 ? origin.z + (k + 0.5) * dx : 0.0};
  };
  const auto of_this_body = [&](Vec3 q) { return body.shape->contains(q, dim) && !claimed_by_earlier_body(problem, block, q); };
  const auto in_any_body = [&](Vec3 q) {
    return std::any_of(problem.bodies.begin(), problem.bodies.end(),
                       [&](const BodySpec& b) { return b.shape && b.shape->contains(q, dim); });
  };
  long lo[3], hi[3];
  site_range(problem, body, reach, lo, hi);
  clip(window, lo, hi);
  const double volume = std::pow(dx, dim) * problem.cross_section();
  for (long k = lo[2]; k <= hi[2]; ++k)
    for (long j = lo[1]; j <= hi[1]; ++j)
      for (long i = lo[0]; i <= hi[0]; ++i) {
        Vec3 p = site(i, j, k);
        if (in_any_body(p)) continue;
        const bool near = std::any_of(offsets.begin(), offsets.end(), [&](const std::array<long, 3>& o) {
          return of_this_body(site(i + o[0], j + o[1], k + o[2]));
        });
        if (!near) continue;
        const std::uint64_t site = extent.site(i, j, k);
        jitter(problem, block, true, site, p);
        layer.push_back(static_cast<std::uint32_t>(out.size()));
        out.push_back({p, volume, block, 0, site, true});
      }
}

// The least a point and a directed bond take (coordinates, volume, displacement, velocity, force; a bond's
// partner index and state): the estimate below is a floor, so a refused deck would not have fitted.
constexpr double point_bytes = 100, bond_bytes = 5;
// A body's bounding box is searched site by site: at most this many times the points that fit in memory (and
// at least 1e8 sites, a second or so), so that a thin shape in a huge box cannot keep the set-up busy for hours.
constexpr double sites_per_point = 100, min_lattice_sites = 1e8;

/// Refuses, before any point is made, bodies whose lattice would not fit in memory: a body's points are its
/// bounding box's lattice sites times the fraction of 16^dim sample sites that the shape contains, its
/// bonds that many times a full family's count (δ/Δx)^dim times the unit ball's measure.
void check_size(const Problem& problem) {
  const int dim = problem.dimension;
  const double dx = problem.spacing;
  const double limit = problem.memory_limit > 0 ? problem.memory_limit
                                                : static_cast<double>(sysconf(_SC_PHYS_PAGES)) * static_cast<double>(sysconf(_SC_PAGE_SIZE));
  const double max_lattice_sites = std::max(min_lattice_sites, sites_per_point * limit / point_bytes);
  double points = 0, bonds = 0, largest = -1;
  const BodySpec* culprit = nullptr;
  for (const BodySpec& body : problem.bodies) {
    if (!body.shape) continue;  // a point file is as large as it is
    const BoundingBox box = body.shape->bounds(dim);
    double sites = 1;
    for (int d = 0; d < dim; ++d) sites *= std::max(1.0, (box.hi[d] - box.lo[d]) / dx + 1);
    if (!(sites <= max_lattice_sites))
      throw InputError(body.pos, fmt::format("bodies.{}: its bounding box holds {:.3g} lattice sites of spacing {:g} m "
                                             "(at most {:.3g} are searched, 100 per point that fits in memory); a "
                                             "larger spacing or a smaller body",
                                             body.name, sites, dx, max_lattice_sites));
    constexpr int samples = 16;
    int inside = 0, total = 0;
    for (int k = 0; k < (dim == 3 ? samples : 1); ++k)
      for (int j = 0; j < (dim >= 2 ? samples : 1); ++j)
        for (int i = 0; i < samples; ++i, ++total) {
          const int index[3] = {i, j, k};
          Vec3 p;
          for (int d = 0; d < dim; ++d) p[d] = box.lo[d] + (index[d] + 0.5) / samples * (box.hi[d] - box.lo[d]);
          inside += body.shape->contains(p, dim) ? 1 : 0;
        }
    const double body_points = sites * inside / total;
    const double m = body.horizon / dx;
    const double family = dim == 3 ? 4.18879 * m * m * m : dim == 2 ? 3.14159 * m * m : 2 * m;
    points += body_points;
    bonds += body_points * family;
    if (body_points > largest) largest = body_points, culprit = &body;
  }
  const double bytes = points * point_bytes + bonds * bond_bytes;
  if (culprit && bytes > limit)
    throw InputError(culprit->pos,
                     fmt::format("bodies.{}: with spacing {:g} m the bodies hold about {:.3g} points and {:.3g} bonds, "
                                 "at least {:.3g} GiB, more than the {:.3g} GiB {}; a larger spacing or smaller bodies",
                                 culprit->name, dx, points, bonds, bytes / 0x1p30, limit / 0x1p30,
                                 problem.memory_limit > 0 ? "allowed by --max-memory" : "of this machine's memory"));
}

/// Appends the points of a point-file body whose place k in the file (after the block filter) passes keep(k);
/// returns how many points the file gives the body.
template <class Keep>
std::size_t read_point_file(const Problem& problem, const BodySpec& body, std::int32_t block, Keep&& keep,
                            std::vector<RawPoint>& out) {
  std::ifstream in(body.points_file);
  if (!in) throw InputError(body.pos, "bodies." + body.name + ": cannot open points_file '" + body.points_file + "'");
  const int dim = problem.dimension;
  std::string line;
  int line_number = 0;
  std::size_t count = 0;
  while (std::getline(in, line)) {
    ++line_number;
    auto hash = line.find('#');
    if (hash != std::string::npos) line.erase(hash);
    std::istringstream fields(line);
    std::vector<double> values;
    double value;
    while (fields >> value) values.push_back(value);
    if (!fields.eof()) {
      throw InputError(SourcePos{body.points_file, line_number, 1},
                       "bodies." + body.name + ": not a number in points_file");
    }
    if (values.empty()) continue;
    const std::size_t expected = static_cast<std::size_t>(dim) + 1;
    if (values.size() != expected && values.size() != expected + 1) {
      throw InputError(SourcePos{body.points_file, line_number, 1},
                       "bodies." + body.name + ": expected " + std::to_string(expected) + " or " +
                           std::to_string(expected + 1) + " columns (x" + (dim >= 2 ? " y" : "") + (dim == 3 ? " z" : "") +
                           " volume [block]), found " + std::to_string(values.size()));
    }
    if (values.size() == expected + 1 && body.block_filter && static_cast<int>(values[expected]) != *body.block_filter)
      continue;
    Vec3 p{values[0], dim >= 2 ? values[1] : 0.0, dim == 3 ? values[2] : 0.0};
    double volume = values[dim];
    if (!(volume > 0)) {
      throw InputError(SourcePos{body.points_file, line_number, 1},
                       "bodies." + body.name + ": point volume must be positive");
    }
    if (keep(count++)) out.push_back({p, volume, block, 0});
  }
  return count;
}

/// Appends the points of a body read from a point file or a mesh, in file order, whose place k in the body
/// passes keep(k), and its mesh's sets (points by place in the body); returns the body's point count.
/// `meshes`: the meshes read so far (bodies sharing a file read it once).
template <class Keep>
std::size_t read_file_body(const Problem& problem, std::int32_t block, std::map<std::string, Mesh>& meshes, Keep&& keep,
                           std::vector<RawPoint>& out, std::vector<MeshPointSet>& sets) {
  const BodySpec& body = problem.bodies[static_cast<std::size_t>(block)];
  if (!body.mesh) return read_point_file(problem, body, block, keep, out);
  const std::string key = body.mesh->format + ":" + body.mesh->file;
  if (!meshes.contains(key)) meshes.emplace(key, read_mesh(*body.mesh));
  const MeshPoints points = mesh_points(meshes.at(key), *body.mesh, problem.dimension, problem.cross_section(), body.name);
  for (std::size_t i = 0; i < points.x.size(); ++i)
    if (keep(i)) out.push_back({points.x[i], points.volume[i], block, 0});
  sets = mesh_point_sets(meshes.at(key), points);
  return points.x.size();
}

}  // namespace

LatticeExtent lattice_extent(const Problem& problem) {
  LatticeExtent e;
  bool first = true;
  for (const BodySpec& body : problem.bodies) {
    if (!body.shape) continue;
    long lo[3], hi[3];
    site_range(problem, body, body.volume_constraint, lo, hi);
    for (int d = 0; d < 3; ++d) {
      e.lo[d] = first ? lo[d] : std::min(e.lo[d], lo[d]);
      e.hi[d] = first ? hi[d] : std::max(e.hi[d], hi[d]);
    }
    first = false;
  }
  return e;
}

std::uint64_t morton_key(Vec3 x, Vec3 lo, double spacing, int dimension) {
  auto cell = [&](int d) { return static_cast<std::uint32_t>(std::max(0.0, (x[d] - lo[d]) / spacing)); };
  return morton_code(cell(0), cell(1), dimension == 3 ? cell(2) : 0);
}

double cell_side(double volume, const Problem& problem) {
  const double cell = volume / problem.cross_section();
  return problem.dimension == 3 ? std::cbrt(cell) : problem.dimension == 2 ? std::sqrt(cell) : cell;
}

SiteBox bisected_site_box(const Problem& problem, int rank, int ranks) {
  const LatticeExtent extent = lattice_extent(problem);
  // Each body's estimated sites: its bounding box (with its layer), evenly filled.
  std::vector<SiteBox> bodies;
  for (const BodySpec& body : problem.bodies) {
    if (!body.shape) continue;
    long lo[3], hi[3];
    site_range(problem, body, body.volume_constraint, lo, hi);
    SiteBox b;
    for (int d = 0; d < 3; ++d) b.lo[d] = lo[d], b.hi[d] = hi[d] + 1;
    bodies.push_back(b);
  }
  auto weight = [&](const SiteBox& box) {
    double w = 0;
    for (const SiteBox& b : bodies) {
      double overlap = 1;
      for (int d = 0; d < 3; ++d) overlap *= static_cast<double>(std::max(0L, std::min(box.hi[d], b.hi[d]) - std::max(box.lo[d], b.lo[d])));
      w += overlap;
    }
    return w;
  };
  SiteBox box;
  for (int d = 0; d < 3; ++d) box.lo[d] = extent.lo[d], box.hi[d] = extent.hi[d] + 1;
  int first = 0, count = ranks;  // the ranks this box is for
  while (count > 1) {
    const int left = count / 2;
    int axis = 0;
    for (int d = 1; d < problem.dimension; ++d)
      if (box.hi[d] - box.lo[d] > box.hi[axis] - box.lo[axis]) axis = d;
    // The first cut whose lower part holds at least its share (binary search: the weight grows with the cut).
    const double total = weight(box), share = total * left / count;
    long lo = box.lo[axis], hi = box.hi[axis];
    if (total > 0) {
      while (lo < hi) {
        const long cut = lo + (hi - lo) / 2;
        SiteBox lower = box;
        lower.hi[axis] = cut;
        if (weight(lower) >= share) hi = cut;
        else lo = cut + 1;
      }
    } else {
      lo = box.lo[axis] + (box.hi[axis] - box.lo[axis]) * left / count;
    }
    const long cut = lo;
    if (rank < first + left) {
      box.hi[axis] = cut;
      count = left;
    } else {
      box.lo[axis] = cut;
      first += left;
      count -= left;
    }
  }
  return box;
}

LatticePoints discretize_window(const Problem& problem, const SiteBox& window) {
  check_size(problem);
  const LatticeExtent extent = lattice_extent(problem);
  std::vector<RawPoint> raw;
  for (std::size_t b = 0; b < problem.bodies.size(); ++b) {
    if (!problem.bodies[b].shape) continue;
    fill_shape(problem, static_cast<std::int32_t>(b), extent, window, raw);
    std::vector<std::uint32_t> layer;
    if (problem.bodies[b].volume_constraint > 0) fill_layer(problem, static_cast<std::int32_t>(b), extent, window, raw, layer);
  }
  LatticePoints out;
  out.disc.dimension = problem.dimension;
  for (const BodySpec& body : problem.bodies) out.disc.block_names.push_back(body.name);
  out.disc.x.resize(raw.size());
  out.disc.volume.resize(raw.size());
  out.disc.block.resize(raw.size());
  out.site.resize(raw.size());
  out.layer.resize(raw.size());
  for (std::size_t k = 0; k < raw.size(); ++k) {
    out.disc.x.set(k, raw[k].x);
    out.disc.volume[k] = raw[k].volume;
    out.disc.block[k] = raw[k].block;
    out.site[k] = raw[k].site;
    out.layer[k] = raw[k].layer ? 1 : 0;
  }
  return out;
}

FilePoints read_file_bodies(const Problem& problem, int rank, int ranks) {
  FilePoints files;
  files.disc.dimension = problem.dimension;
  for (const BodySpec& body : problem.bodies) files.disc.block_names.push_back(body.name);
  files.body_points.assign(problem.bodies.size(), 0);
  std::map<std::string, Mesh> meshes;
  std::vector<RawPoint> raw;
  for (std::size_t b = 0; b < problem.bodies.size(); ++b) {
    if (problem.bodies[b].shape) continue;
    const std::size_t before = raw.size();
    std::vector<MeshPointSet> sets;
    const auto keep = [&](std::size_t k) { return k % static_cast<std::size_t>(ranks) == static_cast<std::size_t>(rank); };
    files.body_points[b] = read_file_body(problem, static_cast<std::int32_t>(b), meshes, keep, raw, sets);
    for (std::size_t k = before; k < raw.size(); ++k)
      files.place.push_back(static_cast<std::uint64_t>(rank) + static_cast<std::uint64_t>(ranks) * (k - before));
    for (MeshPointSet& set : sets) {
      Discretization::MeshSet& out = files.sets.emplace_back();
      out.name = std::move(set.name);
      out.block = static_cast<std::int32_t>(b);
      out.input_ids.assign(set.points.begin(), set.points.end());
    }
  }
  files.disc.x.resize(raw.size());
  for (std::size_t k = 0; k < raw.size(); ++k) {
    files.disc.x.set(k, raw[k].x);
    files.disc.volume.push_back(raw[k].volume);
    files.disc.block.push_back(raw[k].block);
  }
  return files;
}

Discretization discretize(const Problem& problem) {
  std::vector<RawPoint> raw;
  std::vector<Diagnostic> errors;
  check_size(problem);
  const LatticeExtent extent = lattice_extent(problem);
  const SiteBox all = everywhere();
  std::map<std::string, Mesh> meshes;
  std::vector<Discretization::MeshSet> mesh_sets;
  for (std::size_t b = 0; b < problem.bodies.size(); ++b) {
    const BodySpec& body = problem.bodies[b];
    const std::size_t before = raw.size();
    if (body.shape) {
      fill_shape(problem, static_cast<std::int32_t>(b), extent, all, raw);
      if (body.volume_constraint > 0 && raw.size() > before) {
        Discretization::MeshSet& layer = mesh_sets.emplace_back();
        layer.name = body.name + "_constraint";
        layer.block = static_cast<std::int32_t>(b);
        fill_layer(problem, static_cast<std::int32_t>(b), extent, all, raw, layer.input_ids);
        if (layer.input_ids.empty())
          errors.push_back({body.pos, "bodies." + body.name +
                                          ".volume_constraint: the layer holds no lattice site (is it thinner than the "
                                          "spacing, or inside other bodies?)"});
      }
    } else {
      std::vector<MeshPointSet> sets;
      read_file_body(problem, static_cast<std::int32_t>(b), meshes, [](std::size_t) { return true; }, raw, sets);
      for (MeshPointSet& set : sets) {
        Discretization::MeshSet& out = mesh_sets.emplace_back();
        out.name = std::move(set.name);
        out.block = static_cast<std::int32_t>(b);
        for (std::size_t k : set.points) out.input_ids.push_back(static_cast<std::uint32_t>(before + k));
      }
    }
    if (raw.size() == before)
      errors.push_back({body.pos, "bodies." + body.name + ": the body contains no point (is it smaller than the spacing?)"});
  }
  if (!errors.empty()) throw InputError(errors);

  // Sort key: block, then Morton code of the point's cell on a grid of the smallest spacing.
  Vec3 lo{1e300, 1e300, 1e300};
  double min_spacing = 1e300;
  for (const RawPoint& p : raw) {
    for (int d = 0; d < 3; ++d) lo[d] = std::min(lo[d], p.x[d]);
    min_spacing = std::min(min_spacing, cell_side(p.volume, problem));
  }
  for (RawPoint& p : raw) p.morton = morton_key(p.x, lo, min_spacing, problem.dimension);
  std::vector<std::uint32_t> order(raw.size());
  std::iota(order.begin(), order.end(), 0u);
  std::stable_sort(order.begin(), order.end(), [&](std::uint32_t a, std::uint32_t b) {
    if (raw[a].block != raw[b].block) return raw[a].block < raw[b].block;
    return raw[a].morton < raw[b].morton;
  });

  Discretization disc;
  disc.dimension = problem.dimension;
  for (const BodySpec& body : problem.bodies) disc.block_names.push_back(body.name);
  disc.x.resize(raw.size());
  disc.volume.resize(raw.size());
  disc.block.resize(raw.size());
  disc.input_id.resize(raw.size());
  for (std::size_t k = 0; k < order.size(); ++k) {
    const RawPoint& p = raw[order[k]];
    disc.x.set(k, p.x);
    disc.volume[k] = p.volume;
    disc.block[k] = p.block;
    disc.input_id[k] = order[k];
  }
  disc.mesh_sets = std::move(mesh_sets);
  return disc;
}

std::vector<BlockRange> block_ranges(const Discretization& disc, std::size_t count) {
  std::vector<BlockRange> ranges(disc.block_names.size());
  const std::size_t n = std::min(count, disc.num_points());
  std::size_t i = 0;
  while (i < n) {
    std::size_t j = i;
    while (j < n && disc.block[j] == disc.block[i]) ++j;
    ranges[disc.block[i]] = {i, j};
    i = j;
  }
  return ranges;
}

}  // namespace peridot
