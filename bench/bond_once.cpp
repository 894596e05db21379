// Each bond once or twice? The PMB force of the benchmark block (bench/benchmark_problem.hpp: a simple-cubic
// block, horizon 3.015 spacings, 122 bonds per interior point, points in the space-filling-curve order of a
// run) by three plain loops, written alike and compiled alike (no hand-written vectors), one thread:
//
//   gather   every directed bond i → j evaluated, its force added to i only: each bond computed twice,
//            f written once per point (what Peridot's loops do; 4 B of neighbour index per directed bond);
//   scatter  each bond once, from the point with the smaller index, added to both ends in a fixed order
//            (LAMMPS's Newton-on pair loop, bpm/peri's "walk each bond once"): half the neighbour list
//            (2 B per directed bond), stores into the partners' forces;
//   buffer   each bond once into a per-bond buffer (24 B per bond pair), then every point gathers its
//            bonds' entries in its CSR order (4 B of pair index per directed bond): deterministic for any
//            thread count by construction, 16 B per directed bond more than gather.
//
// Prints one JSON line: directed bonds, seconds per pass (best of --repeat), directed-bond updates per
// second, bytes per directed bond of each, and the largest difference of the three forces (relative to the
// largest force). Measures the options the performance issue asks for before any is built into the loops.
//
//   bond_once --n 37 37 37 [--repeat 20]
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <string>
#include <vector>

#include "peridot/parallel/communicator.hpp"
#include "peridot/solvers/simulation.hpp"
#include "benchmark_problem.hpp"

namespace {

using namespace peridot;

struct Block {
  std::size_t n = 0;
  std::vector<double> x, u, volume;  // x, u: 3 per point
  std::vector<std::uint64_t> offsets;
  std::vector<std::uint32_t> neighbors;
  std::vector<std::uint64_t> upper_offsets;  // the bonds i → j with j > i, in i's CSR order
  std::vector<std::uint32_t> upper_neighbors;
  std::vector<std::uint32_t> pair_of;  // per directed bond: its bond pair (the upper bond's place)
  double c = 0;                        // micromodulus
};

// f_i += c s V_j y/|y| for the bond i → j (the constant influence; s = (|y| − |ξ|)/|ξ|).
inline void bond_force(const Block& k, std::size_t i, std::size_t j, double g[3]) {
  double xi[3], y[3];
  for (int d = 0; d < 3; ++d) {
    xi[d] = k.x[3 * j + d] - k.x[3 * i + d];
    y[d] = xi[d] + (k.u[3 * j + d] - k.u[3 * i + d]);  // negated exactly when i and j swap
  }
  const double r = std::sqrt(xi[0] * xi[0] + xi[1] * xi[1] + xi[2] * xi[2]);
  const double l = std::sqrt(y[0] * y[0] + y[1] * y[1] + y[2] * y[2]);
  const double scale = k.c * (l - r) / (r * l);
  for (int d = 0; d < 3; ++d) g[d] = scale * y[d];
}

void gather(const Block& k, double* f) {
  for (std::size_t i = 0; i < k.n; ++i) {
    double fi[3] = {0, 0, 0};
    for (std::uint64_t b = k.offsets[i]; b < k.offsets[i + 1]; ++b) {
      const std::size_t j = k.neighbors[b];
      double g[3];
      bond_force(k, i, j, g);
      for (int d = 0; d < 3; ++d) fi[d] += g[d] * k.volume[j];
    }
    for (int d = 0; d < 3; ++d) f[3 * i + d] = fi[d];
  }
}

void scatter(const Block& k, double* f) {
  std::fill(f, f + 3 * k.n, 0.0);
  for (std::size_t i = 0; i < k.n; ++i) {
    double fi[3] = {0, 0, 0};
    for (std::uint64_t b = k.upper_offsets[i]; b < k.upper_offsets[i + 1]; ++b) {
      const std::size_t j = k.upper_neighbors[b];
      double g[3];
      bond_force(k, i, j, g);
      for (int d = 0; d < 3; ++d) {
        fi[d] += g[d] * k.volume[j];
        f[3 * j + d] -= g[d] * k.volume[i];
      }
    }
    for (int d = 0; d < 3; ++d) f[3 * i + d] += fi[d];
  }
}

void buffered(const Block& k, double* f, std::vector<double>& pair_force) {
  for (std::size_t i = 0; i < k.n; ++i)
    for (std::uint64_t b = k.upper_offsets[i]; b < k.upper_offsets[i + 1]; ++b) bond_force(k, i, k.upper_neighbors[b], &pair_force[3 * b]);
  for (std::size_t i = 0; i < k.n; ++i) {
    double fi[3] = {0, 0, 0};
    for (std::uint64_t b = k.offsets[i]; b < k.offsets[i + 1]; ++b) {
      const std::size_t j = k.neighbors[b];
      const double sign = j > i ? 1.0 : -1.0;  // the pair's force was computed from its smaller end
      const double* g = &pair_force[3 * static_cast<std::size_t>(k.pair_of[b])];
      for (int d = 0; d < 3; ++d) fi[d] += sign * g[d] * k.volume[j];
    }
    for (int d = 0; d < 3; ++d) f[3 * i + d] = fi[d];
  }
}

template <class Pass>
double best_seconds(int repeat, Pass&& pass) {
  double best = 1e300;
  for (int r = 0; r < repeat; ++r) {
    const auto t0 = std::chrono::steady_clock::now();
    pass();
    best = std::min(best, std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
  }
  return best;
}

}  // namespace

int main(int argc, char** argv) {
  int n[3] = {37, 37, 37}, repeat = 20;
  for (int a = 1; a < argc; ++a) {
    const std::string arg = argv[a];
    if (arg == "--n" && a + 3 < argc) for (int d = 0; d < 3; ++d) n[d] = std::stoi(argv[++a]);
    else if (arg == "--repeat" && a + 1 < argc) repeat = std::stoi(argv[++a]);
    else {
      std::fprintf(stderr, "usage: bond_once [--n NX NY NZ] [--repeat R]\n");
      return 2;
    }
  }
  MpiSession mpi(argc, argv);
  const double spacing = 1e-3;
  bench::Options o;  // PMB, the constant influence
  for (int d = 0; d < 3; ++d) o.n[d] = n[d];
  o.spacing = spacing;
  o.steps = 1;
  Simulation sim(bench::benchmark_problem(o));
  const Discretization& disc = sim.discretization();
  const BondList& bonds = sim.bonds();
  Block k;
  k.n = disc.num_points();
  k.x.assign(disc.x.data(), disc.x.data() + 3 * k.n);
  k.volume = disc.volume;
  k.offsets = bonds.offsets;
  k.neighbors = bonds.neighbors;
  const double delta = 3.015 * spacing, E = 200e9, K = E / (3 * (1 - 2 * 0.25));
  k.c = 18 * K / (3.141592653589793 * delta * delta * delta * delta);
  // A smooth displacement of about 1e-4 strain, as bench_explicit's block after some steps.
  k.u.resize(3 * k.n);
  for (std::size_t i = 0; i < k.n; ++i)
    for (int d = 0; d < 3; ++d) k.u[3 * i + d] = 1e-6 * std::sin(300.0 * k.x[3 * i + (d + 1) % 3] + d);
  // Half list and pair index.
  k.upper_offsets.assign(k.n + 1, 0);
  for (std::size_t i = 0; i < k.n; ++i) {
    k.upper_offsets[i + 1] = k.upper_offsets[i];
    for (std::uint64_t b = k.offsets[i]; b < k.offsets[i + 1]; ++b)
      if (k.neighbors[b] > i) k.upper_neighbors.push_back(k.neighbors[b]), ++k.upper_offsets[i + 1];
  }
  k.pair_of.resize(k.neighbors.size());
  for (std::size_t i = 0; i < k.n; ++i)
    for (std::uint64_t b = k.offsets[i]; b < k.offsets[i + 1]; ++b) {
      const std::size_t j = k.neighbors[b];
      const std::size_t lo = std::min(i, j), hi = std::max(i, j);
      const auto first = k.upper_neighbors.begin() + static_cast<std::ptrdiff_t>(k.upper_offsets[lo]);
      const auto last = k.upper_neighbors.begin() + static_cast<std::ptrdiff_t>(k.upper_offsets[lo + 1]);
      k.pair_of[b] = static_cast<std::uint32_t>(std::find(first, last, static_cast<std::uint32_t>(hi)) - k.upper_neighbors.begin());
    }

  const double directed = static_cast<double>(k.neighbors.size());
  std::vector<double> f_gather(3 * k.n), f_scatter(3 * k.n), f_buffer(3 * k.n), pair_force(3 * k.upper_neighbors.size());
  const double t_gather = best_seconds(repeat, [&] { gather(k, f_gather.data()); });
  const double t_scatter = best_seconds(repeat, [&] { scatter(k, f_scatter.data()); });
  const double t_buffer = best_seconds(repeat, [&] { buffered(k, f_buffer.data(), pair_force); });
  double largest = 0, diff_scatter = 0, diff_buffer = 0;
  std::size_t unequal_buffer = 0;
  for (std::size_t q = 0; q < 3 * k.n; ++q) {
    unequal_buffer += f_buffer[q] != f_gather[q];
    largest = std::max(largest, std::abs(f_gather[q]));
    diff_scatter = std::max(diff_scatter, std::abs(f_scatter[q] - f_gather[q]));
    diff_buffer = std::max(diff_buffer, std::abs(f_buffer[q] - f_gather[q]));
  }
  std::printf(
      "{\"points\": %zu, \"directed_bonds\": %.0f, \"repeat\": %d, "
      "\"gather\": {\"s\": %.5f, \"bond_updates_per_s\": %.4g, \"bytes_per_bond\": 4}, "
      "\"scatter\": {\"s\": %.5f, \"bond_updates_per_s\": %.4g, \"bytes_per_bond\": 2, \"vs_gather\": %.3f}, "
      "\"buffer\": {\"s\": %.5f, \"bond_updates_per_s\": %.4g, \"bytes_per_bond\": 20, \"vs_gather\": %.3f}, "
      "\"largest_difference_scatter\": %.3g, \"largest_difference_buffer\": %.3g, \"buffer_components_unequal_to_gather\": %zu}\n",
      k.n, directed, repeat, t_gather, directed / t_gather, t_scatter, directed / t_scatter, t_gather / t_scatter,
      t_buffer, directed / t_buffer, t_gather / t_buffer, diff_scatter / largest, diff_buffer / largest, unequal_buffer);
  return 0;
}
