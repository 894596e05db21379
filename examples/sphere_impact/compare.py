#!/usr/bin/python3
"""LAMMPS's peridynamic impact example (examples/peri: a sphere of radius 1.5 mm at 100 m/s into a brittle
cylinder of radius 5 mm, Δx = 0.5 mm, 1000 steps of 0.1 µs), run in Peridot (deck.yaml: PMB, deck_lps.yaml: LPS)
and in the installed LAMMPS (lammps/in.pmb, lammps/in.lps) side by side, in one command:

    compare.py --peridot PATH [--lmp lmp] [--out DIR] [--models pmb,lps] [--skip-lammps] [--rigid]
    compare.py --peridot PATH --check [--out DIR]

Besides each deck as it is in both codes, it runs the two with each other's conventions: Peridot with
solver.bond_failure: after_force (LAMMPS's failure order) and LAMMPS with alpha = 0 (a constant critical stretch,
Peridot's). --rigid adds Peridot runs with a rigid ball (Peridot's penalty) instead of LAMMPS's soft indenter law.
The full form also writes lammps/reference_alpha0.csv, LAMMPS's α = 0 histories (force on the ball and broken-bond
fraction every 10 steps), which --check (no LAMMPS needed; ctest runs it) compares with Peridot's after_force runs:
LPS to 100 µs, PMB to 35 µs (after about 38 µs the PMB runs part by a few bonds: the codes' round-off differs by
1e-5 of the force and the fracture amplifies it). It exits 1 when a broken-bond fraction differs by more than 5e-4
or a force by more than 0.05 N.

It writes DIR/force.png (the force on the projectile against time), DIR/damage.png (the broken-bond fraction
against time and the final damage histogram), DIR/damage_maps.png (final damage on the cylinder's axial section)
and prints the table of README.md: peak force and its time, impulse, broken-bond fraction at 25, 50, 75 and
100 µs, mean damage and the fraction of points with damage > 0.5, and both codes' wall times."""
import argparse
import csv
import os
import pathlib
import subprocess
import sys
import time

import numpy as np

HERE = pathlib.Path(__file__).resolve().parent
sys.path.insert(0, str(HERE.parents[1] / "tools"))
sys.path.insert(0, str(HERE / "lammps"))
import peridot_results as pr  # noqa: E402
import run_lammps  # noqa: E402

import matplotlib  # noqa: E402

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

DECKS = {"pmb": "deck.yaml", "lps": "deck_lps.yaml"}
MARKS = (250, 500, 750, 1000)  # steps of the table
REFERENCE = HERE / "lammps" / "reference_alpha0.csv"
CHECK_UNTIL = {"pmb": 350, "lps": 1000}  # steps
CHECK_BROKEN, CHECK_FORCE = 5e-4, 0.05  # broken-bond fraction, N


def check(peridot, out, threads, models):
    """Peridot's after_force runs against the stored LAMMPS α = 0 histories; returns whether all agree."""
    with open(REFERENCE) as f:
        reference = list(csv.DictReader(f))
    ok = True
    for model in models:
        r = run_peridot(peridot, model, out, threads, "after_force")
        ref = {int(row["step"]): row for row in reference if row["model"] == model}
        worst_broken = worst_force = 0.0
        for step, force, broken in zip(r["step"], r["force"], r["broken"]):
            step = int(step)
            if step > CHECK_UNTIL[model] or step not in ref:
                continue
            worst_broken = max(worst_broken, abs(broken - float(ref[step]["broken_fraction"])))
            worst_force = max(worst_force, abs(force - float(ref[step]["force_y"])))
        good = worst_broken <= CHECK_BROKEN and worst_force <= CHECK_FORCE
        ok = ok and good
        print(f"{'ok  ' if good else 'FAIL'} {model}: to step {CHECK_UNTIL[model]}, largest difference from LAMMPS (α = 0) "
              f"{worst_broken:.3g} in broken-bond fraction (tolerance {CHECK_BROKEN}), {worst_force:.3g} N in the force on "
              f"the ball (tolerance {CHECK_FORCE} N)")
    return ok


def run_peridot(peridot, model, out, threads, variant=""):
    """Runs the deck into out/peridot_<model>[_variant]; returns time, force on the ball (N), broken fraction, the
    final points (reference positions), their damage and the wall time. variant "rigid": without LAMMPS's indenter
    law, Peridot's own rigid-body penalty; "after_force": bonds break after carrying the step's force (LAMMPS's
    order)."""
    deck = HERE / DECKS[model]
    name = f"peridot_{model}" + (f"_{variant}" if variant else "")
    text = deck.read_text().replace(f"directory: out_{model}", f"directory: {out / name}")
    if variant == "rigid":
        text = "\n".join(line for line in text.splitlines() if "indenter_stiffness" not in line) + "\n"
    if variant == "after_force":
        text = text.replace("  time_step: 0.1 us\n", "  time_step: 0.1 us\n  bond_failure: after_force\n")
    local = out / f"{name}.yaml"
    local.write_text(text)
    env = dict(os.environ, OMP_NUM_THREADS=str(threads))
    start = time.perf_counter()
    subprocess.run([peridot, "run", str(local)], check=True, env=env, stdout=subprocess.DEVNULL)
    wall = time.perf_counter() - start
    with open(out / name / "history.csv") as f:
        rows = list(csv.DictReader(f))
    col = lambda name: np.array([float(r[name]) for r in rows])  # noqa: E731
    with pr.Results(out / name / "impact.e") as res:
        x, damage = res.coords, res.field("damage")
    return {"time": col("time"), "force": col("body_ball_fy"), "broken": col("broken_fraction"), "step": col("step"),
            "x": x, "damage": damage, "wall": wall}


def summary(name, r):
    t, f = r["time"], r["force"]
    peak = int(np.argmax(f))
    impulse = np.trapz(f, t)
    at = {int(s): b for s, b in zip(r["step"], r["broken"])}
    d = r["damage"]
    return [name, f"{f[peak]:.1f}", f"{t[peak] * 1e6:.1f}", f"{impulse * 1e3:.2f}"] + \
        [f"{at.get(m, float('nan')):.4f}" for m in MARKS] + [f"{d.mean():.3f}", f"{(d > 0.5).mean():.3f}", f"{r['wall']:.1f}"]


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--peridot", required=True)
    ap.add_argument("--lmp", default="lmp")
    ap.add_argument("--out", default=str(HERE / "out"))
    ap.add_argument("--models", default="pmb,lps")
    ap.add_argument("--threads", type=int, default=1)
    ap.add_argument("--skip-lammps", action="store_true", help="Peridot only")
    ap.add_argument("--check", action="store_true", help="Peridot against the stored LAMMPS histories (no LAMMPS)")
    ap.add_argument("--rigid", action="store_true", help="also Peridot with a rigid ball (its own penalty) instead of "
                    "LAMMPS's indenter law")
    a = ap.parse_args()
    out = pathlib.Path(a.out).resolve()
    out.mkdir(parents=True, exist_ok=True)
    models = a.models.split(",")
    if a.check:
        sys.exit(0 if check(a.peridot, out, a.threads, models) else 1)
    results = {}
    for model in models:
        results[("Peridot", model)] = run_peridot(a.peridot, model, out, a.threads)
        results[("Peridot after_force", model)] = run_peridot(a.peridot, model, out, a.threads, "after_force")
        if a.rigid:
            results[("Peridot rigid ball", model)] = run_peridot(a.peridot, model, out, a.threads, "rigid")
        if a.skip_lammps:
            continue
        lmp = run_lammps.run(model, str(out / f"lammps_{model}"), lmp=a.lmp)
        results[("LAMMPS", model)] = {"time": lmp["time"], "force": lmp["force"][:, 1],
                                      "broken": lmp["broken_fraction"], "step": lmp["step"],
                                      "x": lmp["x0"], "damage": lmp["damage"], "wall": lmp["wall_s"]}
        lmp = run_lammps.run(model, str(out / f"lammps_{model}_alpha0"), lmp=a.lmp, alpha=0.0)
        results[("LAMMPS α=0", model)] = {"time": lmp["time"], "force": lmp["force"][:, 1],
                                         "broken": lmp["broken_fraction"], "step": lmp["step"],
                                         "x": lmp["x0"], "damage": lmp["damage"], "wall": lmp["wall_s"]}
    if not a.skip_lammps and set(models) == {"pmb", "lps"}:
        with open(REFERENCE, "w", newline="") as f:
            w = csv.writer(f)
            w.writerow(["model", "step", "time", "force_y", "broken_fraction"])
            for model in models:
                r = results[("LAMMPS α=0", model)]
                for row in zip(r["step"], r["time"], r["force"], r["broken"]):
                    w.writerow([model, int(row[0]), f"{row[1]:.10g}", f"{row[2]:.12g}", f"{row[3]:.12g}"])

    header = ["run", "peak force (N)", "at (µs)", "impulse (mN s)"] + [f"broken at {m // 10} µs" for m in MARKS] + \
        ["mean damage", "damage > 0.5", "wall (s)"]
    print("| " + " | ".join(header) + " |")
    print("|" + "---|" * len(header))
    for (code, model), r in results.items():
        print("| " + " | ".join(summary(f"{code} {model.upper()}", r)) + " |")

    styles = {"Peridot": "-", "LAMMPS": "--", "Peridot after_force": "-", "LAMMPS α=0": "--", "Peridot rigid ball": ":"}
    widths = {"Peridot after_force": 3, "LAMMPS α=0": 1}
    colors = {"pmb": "C0", "lps": "C3"}
    rigid = [key for key in results if key[0] == "Peridot rigid ball"]
    fig, axes = plt.subplots(1, 2 if rigid else 1, figsize=(12 if rigid else 7, 4.2), squeeze=False)
    ax = axes[0][0]
    for (code, model), r in results.items():
        if code in ("Peridot", "LAMMPS"):
            ax.plot(r["time"] * 1e6, r["force"], styles[code], color=colors[model], label=f"{code} {model.upper()}")
    ax.set_xlabel("time (µs)")
    ax.set_ylabel("force on the projectile, y (N)")
    ax.set_title("LAMMPS's indenter (K h², K = 1e17 N/m⁵) at 100 m/s")
    ax.grid(alpha=0.3)
    ax.legend()
    if rigid:
        ax = axes[0][1]
        for key in rigid:
            ax.plot(results[key]["time"] * 1e6, results[key]["force"], color=colors[key[1]], label=f"Peridot {key[1].upper()}")
        ax.set_xlabel("time (µs)")
        ax.set_title("a rigid ball (Peridot's penalty, 0.5 of a family's stiffness)")
        ax.grid(alpha=0.3)
        ax.legend()
    fig.tight_layout()
    fig.savefig(out / "force.png", dpi=120)

    fig, (a1, a2) = plt.subplots(1, 2, figsize=(11, 4.2))
    for (code, model), r in results.items():
        if code == "Peridot rigid ball":
            continue
        a1.plot(r["time"] * 1e6, r["broken"], styles[code], color=colors[model], label=f"{code} {model.upper()}",
                lw=widths.get(code, 1.5), alpha=0.45 if code == "Peridot after_force" else 1)
        if code not in ("Peridot", "LAMMPS"):
            continue
        a2.hist(r["damage"], bins=np.linspace(0, 1, 21), histtype="step", linestyle=styles[code], color=colors[model],
                label=f"{code} {model.upper()}")
    a1.set_xlabel("time (µs)")
    a1.set_ylabel("broken bonds / all bonds")
    a1.grid(alpha=0.3)
    a1.legend()
    a2.set_xlabel("damage at 100 µs")
    a2.set_ylabel("points")
    a2.set_yscale("log")
    a2.legend()
    fig.tight_layout()
    fig.savefig(out / "damage.png", dpi=120)

    keys = [key for key in results if key[0] in ("Peridot", "LAMMPS")]
    fig, axes = plt.subplots(1, len(keys), figsize=(2.9 * len(keys) + 1, 2.4), squeeze=False, constrained_layout=True)
    for ax, key in zip(axes[0], keys):
        r = results[key]
        section = np.abs(r["x"][:, 2]) < 1e-5  # the plane z = 0
        sc = ax.scatter(r["x"][section, 0] * 1e3, r["x"][section, 1] * 1e3, c=r["damage"][section], s=14, vmin=0, vmax=1,
                        cmap="viridis")
        ax.set_title(f"{key[0]} {key[1].upper()}")
        ax.set_aspect("equal")
        ax.set_xlabel("x (mm)")
    axes[0][0].set_ylabel("y (mm)")
    fig.colorbar(sc, ax=axes[0].tolist(), label="damage at 100 µs")
    fig.savefig(out / "damage_maps.png", dpi=120)
    print(f"wrote {out / 'force.png'}, {out / 'damage.png'}, {out / 'damage_maps.png'}")


if __name__ == "__main__":
    main()
