#!/usr/bin/python3
"""Memory and set-up time of a distributed run against its rank count (docs/performance.md, "Memory per rank").

    /usr/bin/python3 bench/mpi_memory.py [--peridot build/peridot] [--n 200] [--ranks 1,2,4] [--frames] [--out DIR]

An n³-point LPS block (δ = 3.015 Δx, no damage, 2 explicit steps, no output file but the log) run with
`mpirun --oversubscribe -np R` for each R (one thread per rank; R = 1 runs without mpirun). From each run.log:
the peak resident memory of every rank (Linux VmHWM, read at the end of the run), the set-up time of the
slowest rank (points, bonds and partition: Simulation's constructor) and the decomposition `peridot check`
prints (owned points and ghosts per rank). n = 200 is the 8 000 000-point block of issue 25; it needs about
6.5 GB on one rank. With --frames the deck also writes an Exodus frame at every step (3 frames: steps 0, 1, 2;
distributed, one piece per rank) and the table adds the time to write them and their size. With --contact the
deck turns on short-range contact (`contact: {}`: a pair-list build over the points near each rank's own). With
--points-file the block is read from a point file (x y z volume, one line per point, written into the work folder)
instead of made on the lattice: each rank keeps its share of the file.
"""
import argparse
import os
import re
import subprocess
import sys
import tempfile
import time

DECK = """discretization: {{dimension: 3, spacing: 1 mm, horizon_factor: 3.015}}
materials:
  steel: {{model: lps, density: 7800, youngs_modulus: 200 GPa, poisson_ratio: 0.3}}
bodies:
  block: {{material: steel, {source}}}
initial_conditions:
  - {{velocity: {{x: "1e-3 * x"}}}}
{contact}solver: {{num_steps: 2}}
output: {{directory: out, progress: false{frames}}}
"""


def launch(peridot, ranks, args):
    env = dict(os.environ, OMP_NUM_THREADS="1", OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1")
    cmd = [peridot] + args if ranks == 1 else ["mpirun", "--oversubscribe", "-np", str(ranks), peridot] + args
    return subprocess.run(cmd, capture_output=True, text=True, env=env, check=True).stdout


def main():
    p = argparse.ArgumentParser()
    p.add_argument("--peridot", default="build/peridot")
    p.add_argument("--n", type=int, default=200)
    p.add_argument("--ranks", default="1,2,4")
    p.add_argument("--frames", action="store_true", help="write an Exodus frame at every step")
    p.add_argument("--contact", action="store_true", help="short-range contact on")
    p.add_argument("--points-file", action="store_true", help="the block read from a point file")
    p.add_argument("--out", default=None)
    a = p.parse_args()
    peridot = os.path.abspath(a.peridot)
    work = a.out or tempfile.mkdtemp(prefix="mpi_memory_")
    os.makedirs(work, exist_ok=True)
    deck = os.path.join(work, "block.yaml")
    source = f"shape: {{box: {{min: [0, 0, 0], max: [{a.n * 1e-3}, {a.n * 1e-3}, {a.n * 1e-3}]}}}}"
    if a.points_file:
        with open(os.path.join(work, "block.txt"), "w") as f:
            for k in range(a.n):
                for j in range(a.n):
                    f.write("".join(f"{(i + 0.5) * 1e-3!r} {(j + 0.5) * 1e-3!r} {(k + 0.5) * 1e-3!r} 1e-09\n" for i in range(a.n)))
        source = "points_file: block.txt"
    with open(deck, "w") as f:
        f.write(DECK.format(source=source, frames=", exodus: {every: 1, file: block.e}" if a.frames else "",
                           contact="contact: {}\n" if a.contact else ""))
    print(f"{a.n}³ = {a.n ** 3} points, LPS, δ = 3.015 Δx; work in {work}")
    print("| ranks | owned points per rank | ghosts (largest) | bonds | set-up (s) | run (s) | Exodus (MB) | peak resident per rank (MiB) | largest | sum | largest / one rank |")
    print("|---|---|---|---|---|---|---|---|---|---|---|")
    one = None
    for ranks in [int(r) for r in a.ranks.split(",")]:
        out = os.path.join(work, f"np{ranks}")
        start = time.monotonic()
        launch(peridot, ranks, ["run", "-q", "-o", out, deck])
        seconds = time.monotonic() - start
        exodus = sum(os.path.getsize(os.path.join(out, f)) for f in os.listdir(out) if f.startswith("block.e")) / 1e6
        log = open(os.path.join(out, "run.log")).read()
        bonds = re.search(r"^bonds\s+(\d+) directed", log, re.M).group(1)
        setup = float(re.search(r"^set-up\s+points, bonds and partition in ([0-9.]+) s", log, re.M).group(1))
        if ranks == 1:
            per_rank = [float(re.search(r"^peak resident memory ([0-9.]+) MiB", log, re.M).group(1))]
            owned, ghosts = str(a.n ** 3), "0"
        else:
            m = re.search(r"^peak resident memory [0-9.]+ MiB on the largest rank, [0-9.]+ MiB on all \(per rank: ([^)]*)\)", log, re.M)
            per_rank = [float(v) for v in m.group(1).split(",")]
            d = re.search(r"^ranks\s+\d+ \(owned points per rank (\d+) to (\d+), ghosts up to (\d+)\)", log, re.M)
            owned, ghosts = f"{d.group(1)}–{d.group(2)}", d.group(3)
        largest = max(per_rank)
        one = one or largest
        print(f"| {ranks} | {owned} | {ghosts} | {bonds} | {setup:.1f} | {seconds:.1f} | {exodus:.0f} | {', '.join(f'{v:.0f}' for v in per_rank)} | "
              f"{largest:.0f} | {sum(per_rank):.0f} | {largest / one:.3f} |")
        sys.stdout.flush()


if __name__ == "__main__":
    main()
