// Explicit-dynamics benchmark: a simple-cubic block of points (horizon 3.015 spacings, 122 bonds per
// interior point), PMB, LPS or the inelastic LPS models, a smooth initial velocity field, N velocity-Verlet
// steps. Prints one JSON
// line: points, directed bonds, neighbour-build and step times, bond updates per second per core, bytes
// per bond (with the breakdown) and peak resident memory. bench/compare_lammps.py runs LAMMPS on the
// identical problem (bench/lammps/run_lammps.py) and prints the ratios.
//
//   bench_explicit --model lps --n 58 58 60 --steps 200 [--threads 1] [--critical-stretch 1e-4]
//                  [--dump final.txt]
//   --model lps_plastic [--yield-stress 1e4]   (a small σ_y makes the block flow: the costly case)
//   --model lps_viscoelastic                   (λ_i = 0.5, τ_b = 10 µs)
//   --model correspondence [--law j2|hypoelastic] [--yield-stress 1e4]
//                                              (Foster's J2 law, n = 13.5, m = 44, with the block's E and ν;
//                                              C_HG = 0.05; σ_y = 1e4 Pa makes the points flow at the default
//                                              v0: a Brent solve per point and step)
//   --dim 2                  plane stress, thickness Δx, NX·NY points (NZ ignored): 28 bonds per interior point
//   --influence constant|inverse_distance|gaussian   (default: constant for pmb, 1/|ξ| otherwise, as LAMMPS)
//   --lammps-failure-order   a bond failing in a step still carries that step's force, as in LAMMPS PERI
//   --contact                short-range contact on (contact: {} in a deck): its cost when nothing touches
//   mpirun -np R bench_explicit …   distributed: rates per core over all R × threads cores, the slowest
//                                   rank's loop time, and its communication (halo exchanges and the
//                                   per-step failure check: seconds, messages and bytes per step)
#include <omp.h>
#include <sys/resource.h>

#include <time.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <string>

#include "peridot/parallel/communicator.hpp"
#include "peridot/solvers/simulation.hpp"
#include "benchmark_problem.hpp"

namespace {

using namespace peridot;
using bench::benchmark_problem;
using bench::Options;

Options parse(int argc, char** argv) {
  Options o;
  for (int k = 1; k < argc; ++k) {
    const std::string a = argv[k];
    auto next = [&] { return std::string(argv[++k]); };
    if (a == "--model") o.model = next();
    else if (a == "--n") for (int d = 0; d < 3; ++d) o.n[d] = std::stoi(next());
    else if (a == "--spacing") o.spacing = std::stod(next());
    else if (a == "--steps") o.steps = std::stoi(next());
    else if (a == "--dt") o.dt = std::stod(next());
    else if (a == "--v0") o.v0 = std::stod(next());
    else if (a == "--critical-stretch") o.critical_stretch = std::stod(next());
    else if (a == "--yield-stress") o.yield_stress = std::stod(next());
    else if (a == "--law") o.law = next();
    else if (a == "--dim") o.dimension = std::stoi(next());
    else if (a == "--influence") o.influence = next();
    else if (a == "--lammps-failure-order") o.lammps_failure_order = true;
    else if (a == "--contact") o.contact = true;
    else if (a == "--threads") o.threads = std::stoi(next());
    else if (a == "--dump") o.dump = next();
    else {
      std::fprintf(stderr, "unknown option %s\n", a.c_str());
      std::exit(2);
    }
  }
  return o;
}

// CPU time of the whole process (all threads): on a busy machine it still measures our own work.
double cpu_seconds() {
  timespec t{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
  return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
}

double seconds_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

}  // namespace

int main(int argc, char** argv) {
  MpiSession mpi(argc, argv);
  const Communicator comm = Communicator::world();
  const Options o = parse(argc, argv);
  if (!o.dump.empty() && !comm.serial()) {
    std::fprintf(stderr, "--dump needs one rank\n");
    return 2;
  }
  omp_set_num_threads(o.threads);
  const Problem problem = benchmark_problem(o);

  const auto t_setup = std::chrono::steady_clock::now();
  Simulation sim(problem);  // discretization, neighbour build, materials
  const double setup_s = comm.max(seconds_since(t_setup));
  sim.initialize();
  comm.barrier();
  const Halo::Traffic before = sim.communication();
  const auto t_run = std::chrono::steady_clock::now();
  const double cpu_start = cpu_seconds();
  for (int s = 0; s < o.steps; ++s) sim.step();
  const double run_s = comm.max(seconds_since(t_run));  // the slowest rank sets the pace
  const double run_cpu_s = comm.max(cpu_seconds() - cpu_start);
  Halo::Traffic traffic = sim.communication();
  traffic.seconds -= before.seconds;
  traffic.messages -= before.messages;
  traffic.bytes -= before.bytes;

  // The transfer alone: back-to-back exchanges of u once every rank is at the same point (the loop's
  // communication time also holds the waits for a slower rank).
  double exchange_s = 0;
  if (!comm.serial()) {
    constexpr int repeats = 20;
    comm.barrier();
    const double start = MPI_Wtime();
    for (int k = 0; k < repeats; ++k) sim.halo().exchange(sim.state().u.data(), 3);
    exchange_s = comm.max(MPI_Wtime() - start) / repeats;
  }

  const Totals totals = sim.totals();
  const double points = static_cast<double>(sim.discretization().num_points());
  const double bonds = static_cast<double>(sim.global_bond_count());
  const double cores = static_cast<double>(o.threads) * comm.size();
  const double updates_per_s_core = bonds * o.steps / run_s / cores;
  // Bond storage: neighbour index (4 B), broken flag (1 B), CSR offsets (8 B per point); inelastic models add
  // 8 B per history array and 4 B of partner-bond index; correspondence adds its bond weight ω V_j × partial
  // volume factor (8 B).
  const double neighbor_bytes = 4, state_bytes = 1, offset_bytes = 8 * (points + 1) / bonds;
  const int history_arrays = sim.model().bond_history_arrays();
  const double history_bytes = history_arrays > 0 ? 8.0 * history_arrays + 4 : sim.has_correspondence() ? 8.0 : 0.0;
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  const double rss_mib = static_cast<double>(usage.ru_maxrss) / 1024.0;
  // The rank that waits most also waits for the slower one (imbalance); the rank that waits least spends
  // about the transfer itself.
  const double comm_s = comm.max(traffic.seconds), comm_min_s = comm.min(traffic.seconds);
  const double messages = comm.max(static_cast<double>(traffic.messages)) / o.steps;
  const double bytes = comm.max(static_cast<double>(traffic.bytes)) / o.steps;
  const double ghosts = comm.max(static_cast<double>(sim.halo().ghosts()));
  const double peak_rss_sum = static_cast<double>(comm.sum(static_cast<std::uint64_t>(rss_mib)));
  if (!comm.is_root()) return 0;
  std::printf(
      "{\"code\": \"peridot\", \"model\": \"%s\", \"points\": %.0f, \"directed_bonds\": %.0f, \"steps\": %d, "
      "\"ranks\": %d, \"threads\": %d, \"dt\": %.17g, \"setup_s\": %.4f, \"loop_s\": %.4f, \"loop_cpu_s\": %.4f, "
      "\"bond_updates_per_s_per_core\": %.4g, \"bond_updates_per_cpu_s\": %.4g, "
      "\"bytes_per_bond\": %.3f, \"bytes_per_bond_breakdown\": {\"neighbor_index\": %.0f, \"broken_flag\": %.0f, "
      "\"csr_offsets\": %.3f, \"model_per_bond_arrays\": %.0f}, \"peak_rss_mib\": %.1f, "
      "\"communication\": {\"share_of_loop\": %.4f, \"share_of_loop_least_waiting_rank\": %.4f, \"seconds\": %.4f, "
      "\"u_exchange_s\": %.3g, \"messages_per_step_per_rank\": %.1f, "
      "\"bytes_per_step_per_rank\": %.0f, \"ghosts_per_rank\": %.0f, \"peak_rss_mib_all_ranks\": %.0f}, "
      "\"kinetic_energy\": %.17g, \"strain_energy\": %.17g, \"dissipated_energy\": %.17g, \"max_damage\": %.6g, "
      "\"contact_pairs\": %.0f, \"contact_list_builds\": %.0f, \"contact_build_s\": %.4f, \"contact_force_s\": %.4f}\n",
      o.model.c_str(), points, bonds, o.steps, comm.size(), o.threads, sim.time_step(), setup_s, run_s, run_cpu_s,
      updates_per_s_core, bonds * o.steps / run_cpu_s / comm.size(),
      neighbor_bytes + state_bytes + offset_bytes + history_bytes, neighbor_bytes, state_bytes, offset_bytes, history_bytes,
      rss_mib, run_s > 0 ? comm_s / run_s : 0.0, run_s > 0 ? comm_min_s / run_s : 0.0, comm_s, exchange_s, messages, bytes, ghosts, peak_rss_sum, totals.kinetic_energy,
      totals.strain_energy, totals.dissipated_energy, totals.max_damage,
      sim.short_range() ? static_cast<double>(sim.short_range()->pairs()) : 0.0,
      sim.short_range() ? static_cast<double>(sim.short_range()->builds()) : 0.0,
      sim.short_range() ? sim.short_range()->build_seconds() : 0.0, sim.short_range() ? sim.short_range()->compute_seconds() : 0.0);

  if (!o.dump.empty()) {  // final state by lattice index, for comparison with LAMMPS
    // The last column is the fraction of a point's bonds that are broken, unweighted: LAMMPS's damage/atom
    // (1 − Σ_intact V_j / Σ_all V_j with the full volumes, all equal on this lattice).
    std::ofstream out(o.dump);
    out.precision(17);
    const Discretization& disc = sim.discretization();
    const BondList& bonds = sim.bonds();
    for (std::size_t i = 0; i < disc.num_points(); ++i) {
      std::size_t broken = 0;
      for (std::uint64_t b = bonds.offsets[i]; b < bonds.offsets[i + 1]; ++b) broken += bonds.broken[b];
      const double all = static_cast<double>(bonds.offsets[i + 1] - bonds.offsets[i]);
      out << disc.input_id[i];
      for (int d = 0; d < 3; ++d) out << ' ' << disc.x(i, d) + sim.state().u(i, d);
      for (int d = 0; d < 3; ++d) out << ' ' << sim.state().v(i, d);
      out << ' ' << (all > 0 ? static_cast<double>(broken) / all : 0.0) << '\n';
    }
  }
  return 0;
}
