#!/usr/bin/python3
"""Peridot against LAMMPS PERI on the identical problem, in the same run (bench/lammps/README.md):
a simple-cubic block, δ = 3.015Δx, 200 velocity-Verlet steps, no damage, PMB and LPS.

For every model and size it runs bench_explicit (1 thread) and LAMMPS twice (as shipped, and with its
short-range contact pass switched off, `--no-contact`, which leaves the answers bitwise unchanged), then
prints bond updates per second per core, the ratios, bytes per bond, peak memory, and how closely the
answers agree (kinetic energy and displacements of every point).

    /usr/bin/python3 bench/compare_lammps.py [--sizes 37,37,37 58,58,60] [--models pmb lps] [--steps 200]
    /usr/bin/python3 bench/compare_lammps.py --critical-stretch 1e-3 --v0 5     # with bonds breaking
    /usr/bin/python3 bench/compare_lammps.py --repeat 3                         # medians of 3 rounds

With --repeat K each code runs K times, interleaved (Peridot, LAMMPS, LAMMPS without contact, then again),
and the rates are the medians: on a shared VM single runs of either code vary by 10-30 %, and interleaving
exposes both codes to the same drifts. The answers are the same bits in every round; the last is compared.

With --critical-stretch both codes break bonds (s0 constant; LAMMPS α = 0). LAMMPS checks a bond after
using its force in a step, Peridot before: Peridot runs twice, in its own order (the timed run) and in
LAMMPS's order (`--lammps-failure-order`), and the script compares the broken bonds of both with LAMMPS's
(the fraction of broken bonds of every point, summed: the number of broken bonds over the family size).
"""
import argparse
import json
import os
import subprocess
import sys
import tempfile

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(HERE, "lammps"))
import run_lammps  # noqa: E402  (the problem's definition: stable step, material)


def run_json(command):
    out = subprocess.run(command, capture_output=True, text=True, check=True).stdout
    return json.loads(out.strip().splitlines()[-1])


def load_dump(path, lammps):
    """(id, x, y, z, vx, vy, vz) rows sorted by 0-based lattice id."""
    data = np.loadtxt(path, skiprows=9 if lammps else 0)
    if lammps:
        data[:, 0] -= 1
    return data[np.argsort(data[:, 0])]


def main():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--sizes", nargs="+", default=["37,37,37", "58,58,60"])
    p.add_argument("--models", nargs="+", default=["pmb", "lps"])
    p.add_argument("--steps", type=int, default=200)
    p.add_argument("--bench", default=os.path.join(HERE, "..", "build", "bench", "bench_explicit"))
    p.add_argument("--lmp", default="lmp")
    p.add_argument("--critical-stretch", type=float, default=None)
    p.add_argument("--v0", type=float, default=None, help="initial velocity amplitude, m/s (default as run_lammps.py)")
    p.add_argument("--repeat", type=int, default=1, help="rounds of each run; rates are the medians")
    a = p.parse_args()
    damage = ["--critical-stretch", repr(a.critical_stretch)] if a.critical_stretch else []
    velocity = ["--v0", repr(a.v0)] if a.v0 else []
    work = tempfile.mkdtemp(prefix="peridot_vs_lammps_")
    spacing, volume = 1e-3, 1e-9
    dt = 0.8 * run_lammps.stable_dt(spacing)  # both codes take this Δt (full volumes, as LAMMPS)
    rows = []
    for size in a.sizes:
        n = size.split(",")
        for model in a.models:
            tag = f"{model}_{'x'.join(n)}"
            peridot_dump = os.path.join(work, tag + ".peridot")
            peridot_runs, lammps_runs = [], ([], [])
            for _ in range(a.repeat):
                peridot_runs.append(run_json([a.bench, "--model", model, "--n", *n, "--steps", str(a.steps),
                                              "--threads", "1", "--dt", repr(dt), "--dump", peridot_dump, *damage,
                                              *velocity]))
                for runs, extra in zip(lammps_runs, ([], ["--no-contact"])):
                    lammps_dump = os.path.join(work, tag + ".lammps")
                    runs.append(run_json([sys.executable, os.path.join(HERE, "lammps", "run_lammps.py"), "--model",
                                          model, "--n", *n, "--steps", str(a.steps), "--dt", repr(dt), "--lmp", a.lmp,
                                          "--workdir", os.path.join(work, tag + "_lmp"), "--dump", lammps_dump, *extra,
                                          *damage, *velocity]))
            if damage:  # the same run in LAMMPS's failure order
                run_json([a.bench, "--model", model, "--n", *n, "--steps", str(a.steps), "--threads", "1",
                          "--dt", repr(dt), "--dump", peridot_dump + ".lammps_order", *damage, *velocity,
                          "--lammps-failure-order"])
            rate = "bond_updates_per_s_per_core"
            pd, lm, lm_bonds_only = peridot_runs[-1], lammps_runs[0][-1], lammps_runs[1][-1]
            rounds = {"peridot": [r[rate] for r in peridot_runs], "lammps": [r[rate] for r in lammps_runs[0]],
                      "lammps_no_contact": [r[rate] for r in lammps_runs[1]]}
            P, L = load_dump(peridot_dump, False), load_dump(lammps_dump, True)
            # The answers are compared in the same failure order (LAMMPS's, with damage).
            Q = load_dump(peridot_dump + ".lammps_order", False) if damage else P
            reference = np.round(L[:, 1:4] / spacing) * spacing
            u_l, u_p = L[:, 1:4] - reference, Q[:, 1:4] - reference
            displacement_error = np.abs(u_p - u_l).max() / np.abs(u_l).max()
            # The dump and the energy of the run without contact (the second): with bonds breaking, LAMMPS's
            # contact pass acts between the pieces and changes the answer, and Peridot has no contact.
            ke_lammps = lm_bonds_only["kinetic_energy"] * volume
            ke_peridot = 0.5 * run_lammps.RHO * volume * float(np.sum(Q[:, 4:7] ** 2)) if damage else pd["kinetic_energy"]
            broken = {}
            if damage:  # Σ_i (broken fraction of i) in each code: columns 8 of both dumps
                broken["lammps"] = float(L[:, 7].sum())
                broken["peridot"] = float(P[:, 7].sum())
                broken["peridot_lammps_order"] = float(Q[:, 7].sum())
            rows.append({
                "model": model, "points": pd["points"], "bonds": pd["directed_bonds"],
                "same_bonds": pd["directed_bonds"] == lm["directed_bonds"],
                **{code: float(np.median(rates)) for code, rates in rounds.items()}, "rounds": rounds,
                "lammps_cpu_pct": min(r["cpu_use_pct"] for runs in lammps_runs for r in runs),
                "bytes_per_bond": pd["bytes_per_bond"], "peak_rss_mib": pd["peak_rss_mib"],
                "kinetic_energy_rel_diff": abs(ke_peridot - ke_lammps) / ke_lammps,
                "displacement_rel_diff": displacement_error, "broken": broken})
            print(json.dumps(rows[-1]), flush=True)

    print()
    print(f"{'model':5} {'points':>8} {'bonds':>10} {'peridot':>9} {'lammps':>9} {'ratio':>6} "
          f"{'lmp bonds-only':>14} {'ratio':>6} {'B/bond':>6} {'RSS MiB':>8} {'ΔKE':>8} {'Δu':>8}")
    for r in rows:
        print(f"{r['model']:5} {r['points']:8.0f} {r['bonds']:10.0f} {r['peridot'] / 1e6:8.1f}M {r['lammps'] / 1e6:8.1f}M "
              f"{r['peridot'] / r['lammps']:6.2f} {r['lammps_no_contact'] / 1e6:13.1f}M "
              f"{r['peridot'] / r['lammps_no_contact']:6.2f} {r['bytes_per_bond']:6.2f} {r['peak_rss_mib']:8.1f} "
              f"{r['kinetic_energy_rel_diff']:8.1e} {r['displacement_rel_diff']:8.1e}")
    print("bond updates per second per core; ratio = Peridot / LAMMPS; 'bonds-only' = LAMMPS without its contact "
          "pass (equal work); ΔKE, Δu = relative difference of the final kinetic energy and displacements")
    if a.repeat > 1:
        print(f"medians of {a.repeat} interleaved rounds; the rounds (M bond updates/s/core):")
        for r in rows:
            print(f"{r['model']:5} {r['points']:8.0f}: " + "; ".join(
                f"{code} " + " ".join(f"{x / 1e6:.1f}" for x in rates) for code, rates in r["rounds"].items()))
    for r in rows:
        if r["broken"]:
            b = r["broken"]
            print(f"{r['model']:5} {r['points']:8.0f}: broken-bond fractions summed over points: LAMMPS {b['lammps']:.6g}, "
                  f"Peridot {b['peridot']:.6g} ({b['peridot'] / b['lammps'] - 1:+.2%}), Peridot in LAMMPS's failure "
                  f"order {b['peridot_lammps_order']:.6g} ({b['peridot_lammps_order'] / b['lammps'] - 1:+.2e})")
    if any(r["lammps_cpu_pct"] < 98 for r in rows):
        print("warning: LAMMPS shared its core in some runs (CPU use < 98 %): the machine was busy")
    return 0


if __name__ == "__main__":
    sys.exit(main())
