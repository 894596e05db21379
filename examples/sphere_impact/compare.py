#!/usr/bin/python3
"""LAMMPS's peridynamic impact example (examples/peri: a sphere of radius 1.5 mm at 100 m/s into a brittle
cylinder of radius 5 mm, Δx = 0.5 mm, 1000 steps of 0.1 µs), run in Peridot (deck.yaml: PMB, deck_lps.yaml: LPS)
and in the installed LAMMPS (lammps/in.pmb, lammps/in.lps) side by side, in one command:

    compare.py --peridot PATH [--lmp lmp] [--out DIR] [--models pmb,lps] [--skip-lammps]

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


def run_peridot(peridot, model, out, threads):
    """Runs the deck into out/peridot_<model>; returns time, force on the ball (N), broken fraction, the final
    points (reference positions), their damage and the wall time."""
    deck = HERE / DECKS[model]
    text = deck.read_text().replace(f"directory: out_{model}", f"directory: {out / ('peridot_' + model)}")
    local = out / f"peridot_{model}.yaml"
    local.write_text(text)
    env = dict(os.environ, OMP_NUM_THREADS=str(threads))
    start = time.perf_counter()
    subprocess.run([peridot, "run", str(local)], check=True, env=env, stdout=subprocess.DEVNULL)
    wall = time.perf_counter() - start
    with open(out / f"peridot_{model}" / "history.csv") as f:
        rows = list(csv.DictReader(f))
    col = lambda name: np.array([float(r[name]) for r in rows])  # noqa: E731
    with pr.Results(out / f"peridot_{model}" / "impact.e") as res:
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
    a = ap.parse_args()
    out = pathlib.Path(a.out).resolve()
    out.mkdir(parents=True, exist_ok=True)
    models = a.models.split(",")
    results = {}
    for model in models:
        results[("Peridot", model)] = run_peridot(a.peridot, model, out, a.threads)
        if a.skip_lammps:
            continue
        lmp = run_lammps.run(model, str(out / f"lammps_{model}"), lmp=a.lmp)
        results[("LAMMPS", model)] = {"time": lmp["time"], "force": lmp["force"][:, 1],
                                      "broken": lmp["broken_fraction"], "step": lmp["step"],
                                      "x": lmp["x0"], "damage": lmp["damage"], "wall": lmp["wall_s"]}

    header = ["run", "peak force (N)", "at (µs)", "impulse (mN s)"] + [f"broken at {m // 10} µs" for m in MARKS] + \
        ["mean damage", "damage > 0.5", "wall (s)"]
    print("| " + " | ".join(header) + " |")
    print("|" + "---|" * len(header))
    for (code, model), r in results.items():
        print("| " + " | ".join(summary(f"{code} {model.upper()}", r)) + " |")

    styles = {"Peridot": "-", "LAMMPS": "--"}
    colors = {"pmb": "C0", "lps": "C3"}
    fig, ax = plt.subplots(figsize=(7, 4.2))
    for (code, model), r in results.items():
        ax.plot(r["time"] * 1e6, r["force"], styles[code], color=colors[model], label=f"{code} {model.upper()}")
    ax.set_xlabel("time (µs)")
    ax.set_ylabel("force on the projectile, y (N)")
    ax.set_title("Sphere at 100 m/s into a PMB/LPS cylinder (LAMMPS examples/peri)")
    ax.grid(alpha=0.3)
    ax.legend()
    fig.tight_layout()
    fig.savefig(out / "force.png", dpi=120)

    fig, (a1, a2) = plt.subplots(1, 2, figsize=(11, 4.2))
    for (code, model), r in results.items():
        a1.plot(r["time"] * 1e6, r["broken"], styles[code], color=colors[model], label=f"{code} {model.upper()}")
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

    keys = list(results)
    fig, axes = plt.subplots(1, len(keys), figsize=(3.2 * len(keys), 3.4), squeeze=False)
    for ax, key in zip(axes[0], keys):
        r = results[key]
        section = np.abs(r["x"][:, 2]) < 1e-5  # the plane z = 0
        sc = ax.scatter(r["x"][section, 0] * 1e3, r["x"][section, 1] * 1e3, c=r["damage"][section], s=14, vmin=0, vmax=1,
                        cmap="viridis")
        ax.set_title(f"{key[0]} {key[1].upper()}")
        ax.set_aspect("equal")
        ax.set_xlabel("x (mm)")
    axes[0][0].set_ylabel("y (mm)")
    fig.colorbar(sc, ax=axes[0].tolist(), label="damage at 100 µs", shrink=0.8)
    fig.savefig(out / "damage_maps.png", dpi=120)
    print(f"wrote {out / 'force.png'}, {out / 'damage.png'}, {out / 'damage_maps.png'}")


if __name__ == "__main__":
    main()
