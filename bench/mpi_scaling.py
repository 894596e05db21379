#!/usr/bin/python3
"""Distributed runs: measured throughput on 1 and 2 ranks, measured halo traffic on 2-8 ranks, and a
weak-scaling projection to 1000 ranks from that traffic (docs/performance.md, "Distributed runs").

    /usr/bin/python3 bench/mpi_scaling.py [--bench build/bench/bench_explicit] [--n 100] [--steps 40] [--repeats 3]

1. Throughput: bench_explicit on an n³ block (PMB and LPS): one rank of one thread, one rank of two
   threads and `mpirun -np 2` with one thread per rank, interleaved and repeated (this machine's rates
   drift by ±10 % between runs): bond updates per second per core, the ratios, the communication share of
   the loop of the rank that waits most and of the one that waits least (halo exchanges and the per-step
   failure check; the difference is waiting for a slower rank) and one exchange of u timed alone.
2. Traffic: `mpirun --oversubscribe -np R` for R = 2, 4, 8 (3 steps; counts, not times): ghosts per rank,
   messages and bytes per step per rank, checked against the lattice count of the model below.
3. Projection: each rank owns a cube of L³ points (weak scaling, R = 1000 as 10×10×10); an interior rank
   holds as ghosts every lattice point within the horizon (3.015 spacings) outside its cube, and exchanges
   with its 26 neighbours once per field per step (PMB: u, 24 B a point; LPS: u and θ, 32 B) plus one
   all-reduce. Time per step = compute (bonds per rank / the measured single-rank rate) + messages × α +
   bytes / β + the all-reduce (2 α log2 R), for an InfiniBand-class network (α = 1.5 µs, β = 12 GB/s:
   assumptions, stated as such; this machine has no network).
"""
import argparse
import json
import math
import os
import subprocess

import numpy as np

HORIZON = 3.015
ALPHA = 1.5e-6  # s per message (assumed network latency)
BETA = 12e9     # bytes per second (assumed link bandwidth)


def run(cmd, env):
    out = subprocess.run(cmd, capture_output=True, text=True, env=env, check=True).stdout
    return json.loads(out.strip().splitlines()[-1])


def ghosts_of_box(shape, faces=None):
    """Lattice points outside a box of shape[0] × shape[1] × shape[2] lattice points that are within HORIZON
    of one of its points, across the faces in `faces` only ((axis, −1 | +1) pairs; None: all six, an
    interior rank; the other faces are the block's free surface)."""
    h = int(math.ceil(HORIZON))
    x, y, z = np.meshgrid(*[np.arange(-h, n + h) for n in shape], indexing="ij")
    # per axis, the lattice distance to the nearest point of the box
    d = [np.maximum(np.maximum(-c, c - (n - 1)), 0) for c, n in zip((x, y, z), shape)]
    keep = (d[0] ** 2 + d[1] ** 2 + d[2] ** 2) <= HORIZON ** 2
    keep &= (x < 0) | (x >= shape[0]) | (y < 0) | (y >= shape[1]) | (z < 0) | (z >= shape[2])
    if faces is not None:
        for axis, (c, n) in enumerate(zip((x, y, z), shape)):
            if (axis, -1) not in faces:
                keep &= c >= 0
            if (axis, +1) not in faces:
                keep &= c < n
    return int(keep.sum())


def main():
    p = argparse.ArgumentParser()
    p.add_argument("--bench", default="build/bench/bench_explicit")
    p.add_argument("--n", type=int, default=100)
    p.add_argument("--steps", type=int, default=40)
    p.add_argument("--repeats", type=int, default=3)
    p.add_argument("--dt", default="1.3779225373530762e-07")
    a = p.parse_args()
    env = dict(os.environ, OMP_NUM_THREADS="1", OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1")
    n = [str(a.n)] * 3
    mpirun = ["mpirun", "--oversubscribe", "-np"]

    print("## Throughput: 1 rank of 1 thread, 1 rank of 2 threads, 2 ranks of 1 thread\n")
    print(f"Median of {a.repeats} interleaved repeats; the ratios are per core against 1 rank of 1 thread.\n")
    print("| model | points | ranks × threads | bond updates/s/core (runs) | ratio | communication share (most / least "
          "waiting rank) | u exchange alone | messages/step/rank | bytes/step/rank | ghosts/rank | set-up s | "
          "peak RSS all ranks MiB |")
    print("|---|---|---|---|---|---|---|---|---|---|---|---|")
    rates = {}
    for model in ("pmb", "lps"):
        base = [a.bench, "--model", model, "--n", *n, "--steps", str(a.steps), "--dt", a.dt]
        configs = {"1 × 1": base + ["--threads", "1"], "1 × 2": base + ["--threads", "2"],
                   "2 × 1": mpirun + ["2"] + base + ["--threads", "1"]}
        results = {k: [] for k in configs}
        for _ in range(a.repeats):
            for k, cmd in configs.items():
                results[k].append(run(cmd, env))
        energies = {r["kinetic_energy"] for rs in results.values() for r in rs}
        assert len(energies) == 1, "every configuration must give the same bits"
        median = {k: sorted(rs, key=lambda r: r["bond_updates_per_s_per_core"])[len(rs) // 2] for k, rs in results.items()}
        rates[model] = median["1 × 1"]["bond_updates_per_s_per_core"]
        for k, r in median.items():
            c = r["communication"]
            runs = ", ".join(f"{x['bond_updates_per_s_per_core'] / 1e6:.1f}" for x in results[k])
            print(f"| {model} | {r['points']} | {k} | {r['bond_updates_per_s_per_core'] / 1e6:.1f} M ({runs}) | "
                  f"{r['bond_updates_per_s_per_core'] / rates[model]:.3f} | "
                  f"{100 * c['share_of_loop']:.2f} % / {100 * c['share_of_loop_least_waiting_rank']:.2f} % | "
                  f"{1e3 * c['u_exchange_s']:.3f} ms | {c['messages_per_step_per_rank']:.0f} | "
                  f"{c['bytes_per_step_per_rank']:.0f} | {c['ghosts_per_rank']:.0f} | {r['setup_s']:.1f} | "
                  f"{c['peak_rss_mib_all_ranks']:.0f} |")

    print("\n## Halo traffic on 2, 4 and 8 ranks (LPS, counts) against the lattice model\n")
    print("| ranks | ghosts/rank (largest) | model | messages/step/rank | bytes/step/rank |")
    print("|---|---|---|---|---|")
    for ranks in (2, 4, 8):
        r = run(mpirun + [str(ranks), a.bench, "--model", "lps", "--n", *n, "--steps", "3", "--dt", a.dt], env)
        c = r["communication"]
        # RCB of a cube: 2 ranks = two slabs (one internal face), 4 = four columns (two), 8 = octants (three)
        half = a.n // 2
        if ranks == 2:
            model = ghosts_of_box((a.n, a.n, half), [(2, +1)])
        elif ranks == 4:
            model = ghosts_of_box((half, half, a.n), [(0, +1), (1, +1)])
        else:
            model = ghosts_of_box((half, half, half), [(0, +1), (1, +1), (2, +1)])
        print(f"| {ranks} | {c['ghosts_per_rank']:.0f} | {model} | {c['messages_per_step_per_rank']:.0f} | "
              f"{c['bytes_per_step_per_rank']:.0f} |")

    print("\n## Weak-scaling projection to 1000 ranks (interior rank, 26 neighbours; network assumed)\n")
    print("| model | points/rank | ghosts/rank | bytes/step | messages/step | compute ms/step | "
          "communication ms/step | efficiency |")
    print("|---|---|---|---|---|---|---|---|")
    for model, fields, size in (("pmb", 1, 24), ("lps", 2, 32)):
        for L in (40, 58, 100):
            g = ghosts_of_box((L, L, L))
            bonds = L ** 3 * 122  # interior points: 122 bonds each
            compute = bonds / rates[model]
            messages = 26 * fields
            comm = messages * ALPHA + g * size / BETA + 2 * ALPHA * math.log2(1000)
            print(f"| {model} | {L ** 3} | {g} | {g * size} | {messages} + 1 all-reduce | {1e3 * compute:.1f} | "
                  f"{1e3 * comm:.3f} | {compute / (compute + comm):.4f} |")


if __name__ == "__main__":
    main()
