#!/usr/bin/python3
"""Bond updates per second per core of every model on every SIMD target this CPU runs, one binary.

Runs bench_explicit (1 thread) with PERIDOT_SIMD set to each target (docs/performance.md, "SIMD targets")
for PMB and LPS (3D with each influence function, and 2D), the inelastic LPS models and correspondence,
and prints a table of rates and, per target, each rate as a fraction of that target's 3D LPS rate (the
issue's yardstick for the other models). Rounds are interleaved (every case once, then again) and the
medians reported, as in compare_lammps.py.

    /usr/bin/python3 bench/simd_targets.py [--n 37] [--n2d 225] [--steps 60] [--repeat 1] [--targets avx2 ...]
"""
import argparse
import json
import os
import platform
import statistics
import subprocess

HERE = os.path.dirname(os.path.abspath(__file__))


def cases(n, n2d):
    cube = ["--n", str(n), str(n), str(n)]
    plate = ["--dim", "2", "--n", str(n2d), str(n2d), "1"]
    return [
        ("pmb 3D", ["--model", "pmb", *cube]),
        ("pmb 3D 1/|xi|", ["--model", "pmb", "--influence", "inverse_distance", *cube]),
        ("pmb 3D gaussian", ["--model", "pmb", "--influence", "gaussian", *cube]),
        ("lps 3D", ["--model", "lps", *cube]),
        ("lps 3D constant", ["--model", "lps", "--influence", "constant", *cube]),
        ("lps 3D gaussian", ["--model", "lps", "--influence", "gaussian", *cube]),
        ("pmb 2D", ["--model", "pmb", *plate]),
        ("lps 2D", ["--model", "lps", *plate]),
        ("lps_plastic 3D", ["--model", "lps_plastic", "--yield-stress", "1e4", *cube]),
        ("lps_viscoelastic 3D", ["--model", "lps_viscoelastic", *cube]),
        ("correspondence 3D hypoelastic", ["--model", "correspondence", "--law", "hypoelastic", *cube]),
    ]


def available_targets(peridot):
    out = []
    for t in ["avx512", "avx2", "sse4", "scalar"]:
        env = dict(os.environ, PERIDOT_SIMD=t)
        if subprocess.run([peridot, "info"], env=env, capture_output=True).returncode == 0:
            out.append(t)
    return out


def cpu_name():
    try:
        for line in open("/proc/cpuinfo"):
            if line.startswith("model name"):
                return line.split(":", 1)[1].strip()
    except OSError:
        pass
    return platform.processor()


def main():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--n", type=int, default=37, help="points per edge of the 3D block")
    p.add_argument("--n2d", type=int, default=225, help="points per edge of the 2D plate")
    p.add_argument("--steps", type=int, default=60)
    p.add_argument("--repeat", type=int, default=1)
    p.add_argument("--targets", nargs="+", default=None)
    p.add_argument("--bench", default=os.path.join(HERE, "..", "build", "bench", "bench_explicit"))
    p.add_argument("--peridot", default=os.path.join(HERE, "..", "build", "peridot"))
    a = p.parse_args()
    targets = a.targets or available_targets(a.peridot)
    runs = {}
    for _ in range(a.repeat):
        for name, args in cases(a.n, a.n2d):
            for t in targets:
                env = dict(os.environ, PERIDOT_SIMD=t, OMP_NUM_THREADS="1")
                out = subprocess.run([a.bench, *args, "--steps", str(a.steps), "--threads", "1"], env=env,
                                     capture_output=True, text=True, check=True).stdout
                rate = json.loads(out.strip().splitlines()[-1])["bond_updates_per_s_per_core"]
                runs.setdefault((name, t), []).append(rate)
                print(json.dumps({"case": name, "target": t, "rate": rate}), flush=True)
    rate = {k: statistics.median(v) for k, v in runs.items()}
    print()
    print(f"CPU: {cpu_name()}; 1 thread; {a.steps} steps; medians of {a.repeat} round(s); M bond updates/s/core "
          f"(fraction of the same target's 3D LPS rate)")
    print("| case | " + " | ".join(targets) + " |")
    print("|---|" + "---|" * len(targets))
    for name, _ in cases(a.n, a.n2d):
        cells = []
        for t in targets:
            r, lps = rate[(name, t)], rate[("lps 3D", t)]
            cells.append(f"{r / 1e6:.0f} ({r / lps:.2f})")
        print(f"| {name} | " + " | ".join(cells) + " |")


if __name__ == "__main__":
    main()
