#!/usr/bin/python3
"""Time to solution of the two static solvers on the same problem (issue: implicit solver, must-show 4): an LPS
steel bar of nx × n × n points (Δx = 1 mm, δ = 3.015Δx), held over a horizon at x = 0 and pulled by ε = 1e-3 at
the other end, one load step, both to the same relative force residual. Prints, per solver: wall time, iterations
(relaxation; Newton and Krylov for implicit), peak resident memory (GNU time), and for implicit the bond tangent's
bytes per directed bond (its nonzeros as PETSc reports them, 8 B of value and 4 B of column index each); optionally the implicit solver on 1
and 2 MPI ranks (the threads split among them). Example: bench/static_solvers.py --peridot build/peridot --length 200 --width 32 (204 800 points)."""
import argparse
import os
import re
import shutil
import subprocess
import sys
import time

DECK = """discretization: {{dimension: 3, spacing: 1 mm, horizon_factor: 3.015}}
materials:
  steel: {{model: lps, density: 7800, youngs_modulus: 200 GPa, poisson_ratio: 0.3}}
bodies:
  bar: {{material: steel, shape: {{box: {{min: [0, 0, 0], max: [{L}, {W}, {W}]}}}}}}
node_sets:
  left:  {{shape: {{box: {{min: [-1, -1, -1], max: [0.003, 1, 1]}}}}}}
  right: {{shape: {{box: {{min: [{grip}, -1, -1], max: [1, 1, 1]}}}}}}
boundary_conditions:
  - {{node_set: left,  displacement: {{x: "0", y: "0", z: "0"}}}}
  - {{node_set: right, displacement: {{x: "{pull}", y: "0", z: "0"}}}}
solver: {{type: {solver}, load_steps: 1, tolerance: {tolerance}{extra}}}
output: {{directory: out, progress: false, history: {{every: 1, reaction: [right]}}}}
"""


def main():
    p = argparse.ArgumentParser()
    p.add_argument("--peridot", required=True)
    p.add_argument("--length", type=int, default=60, help="points along the bar")
    p.add_argument("--width", type=int, default=12, help="points across")
    p.add_argument("--tolerance", default="1e-8")
    p.add_argument("--threads", default="2")
    p.add_argument("--ranks", default="", help="comma-separated rank counts for the implicit solver under mpirun")
    p.add_argument("--skip-relaxation", action="store_true")
    p.add_argument("--work", default="/tmp/peridot_static_solvers")
    a = p.parse_args()
    shutil.rmtree(a.work, ignore_errors=True)
    os.makedirs(a.work)
    L, W = a.length * 1e-3, a.width * 1e-3
    env = dict(os.environ, OMP_NUM_THREADS=a.threads, OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1")
    print(f"bar {a.length} × {a.width} × {a.width} points ({a.length * a.width * a.width} points), "
          f"tolerance {a.tolerance}, {a.threads} threads; CPU: {cpu()}")
    runs = [] if a.skip_relaxation else [("relaxation", None)]
    runs.append(("implicit", None))
    runs += [("implicit", int(n)) for n in a.ranks.split(",") if n]
    for solver, ranks in runs:
        name = solver + (f"_np{ranks}" if ranks else "")
        deck = os.path.join(a.work, name + ".yaml")
        extra = ", print_iterations: false" if solver == "implicit" else ", max_iterations: 10000000"
        open(deck, "w").write(DECK.format(L=L, W=W, grip=L - 0.003, pull=1e-3 * L, solver=solver,
                                          tolerance=a.tolerance, extra=extra))
        out = os.path.join(a.work, name)
        cmd = ["/usr/bin/time", "-f", "peak_rss_kb %M", a.peridot, "run", "-q", "-o", out, deck]
        run_env = dict(env, PETSC_OPTIONS="-mat_view ::ascii_info") if solver == "implicit" and not ranks else env
        if ranks:  # the same cores: the threads split among the ranks
            cmd = ["mpirun", "--oversubscribe", "--bind-to", "none", "-np", str(ranks)] + cmd
            run_env = dict(env, OMP_NUM_THREADS=str(max(1, int(a.threads) // ranks)))
        start = time.perf_counter()
        r = subprocess.run(cmd, capture_output=True, text=True, env=run_env)
        seconds = time.perf_counter() - start
        if r.returncode != 0:
            print(f"{name}: failed\n{r.stderr[-3000:]}")
            continue
        rss = max(int(x) for x in re.findall(r"peak_rss_kb (\d+)", r.stderr))
        rows = open(os.path.join(out, "history.csv")).read().splitlines()
        head, last = rows[0].split(","), rows[-1].split(",")
        value = lambda c: last[head.index(c)]
        line = (f"{name}: {seconds:.1f} s, iterations {value('iterations')}"
                + (f", Krylov {value('linear_iterations')}" if solver == "implicit" else "")
                + f", residual {float(value('residual')):.2e}, reaction {float(value('reaction_right_x')):.6g} N, "
                  f"peak RSS {rss / 1024:.0f} MiB" + (" per rank (largest)" if ranks else "")
                + (f", {run_env['OMP_NUM_THREADS']} thread(s) per rank" if ranks else ""))
        if solver == "implicit" and not ranks:
            bonds = bond_count(a.peridot, deck, env)
            nonzeros = int(re.search(r"bs=3\s+total: nonzeros=(\d+)", r.stdout).group(1))
            line += (f"; bond tangent: {nonzeros} nonzeros, {12 * nonzeros / 2**20:.0f} MiB of values and column "
                     f"indices = {12 * nonzeros / bonds:.0f} B per directed bond ({bonds} bonds)")
        print(line, flush=True)


def cpu():
    for line in open("/proc/cpuinfo"):
        if line.startswith("model name"):
            return line.split(":", 1)[1].strip()
    return "unknown"


def bond_count(peridot, deck, env):
    r = subprocess.run([peridot, "check", deck], capture_output=True, text=True, env=env)
    m = re.search(r"bonds\s+(\d+) directed", r.stdout)
    return int(m.group(1)) if m else 0


if __name__ == "__main__":
    sys.exit(main())
