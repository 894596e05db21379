#!/usr/bin/python3
"""Width of the damaged band of a notched bar against the spacing, for the two couplings of Johnson–Cook damage
(README.md): the influence-function degradation of Tupek, Rimoli & Radovitzky (2013) and the local (1 − D) σ.

    /usr/bin/python3 examples/notched_bar/study.py --peridot build/peridot --out notched_runs --plot notched_bar.png

Every deck is deck.yaml next to this script with the spacing (and with --fixed-horizon, the horizon factor) and
the coupling changed. The band is measured on the last Exodus frame: the points are binned by their reference x
(one bin per lattice plane across the bar); a plane is "in the band" when the mean D of its points is at least
0.5, and the band width is (number of such planes) × Δx. Also reported: the x-extent of the points with D ≥ 0.5,
the failed points (D = 1), the fraction of broken bonds, the peak grip force, and the mean grip force over the
second half of the run ("late": about zero once the halves are apart and only ring).
--check-short: run the two couplings at the deck's spacing only and require that the influence-function band
is at most 1.5 δ wide with the bar separated, and the local band at least twice as wide.
"""
import argparse
import csv
import os
import subprocess
import sys

import numpy as np
import yaml

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(HERE, "..", "..", "tools"))
import peridot_results as pr  # noqa: E402

SPACINGS = [0.4e-3, 0.3e-3, 0.2e-3]  # m
COUPLINGS = ["influence_function", "local_stress"]


def run(peridot, out, spacing, coupling, threads, horizon=None):
    deck = yaml.safe_load(open(os.path.join(HERE, "deck.yaml")))
    deck["discretization"]["spacing"] = spacing
    if horizon:
        deck["discretization"]["horizon_factor"] = horizon / spacing
    deck["materials"]["al6061"]["johnson_cook_damage"]["coupling"] = coupling
    name = f"{coupling}_{spacing * 1e6:.0f}um" + (f"_delta{horizon * 1e6:.0f}um" if horizon else "")
    folder = os.path.join(out, name)
    os.makedirs(folder, exist_ok=True)
    path = os.path.join(folder, "deck.yaml")
    yaml.safe_dump(deck, open(path, "w"), sort_keys=False, allow_unicode=True)
    results = os.path.join(folder, "output")
    if not os.path.exists(os.path.join(results, "results.e")):
        cmd = [peridot, "run", "-q", path, "-o", results] + (["-t", str(threads)] if threads else [])
        subprocess.run(cmd, check=True)
    return name, results


def measure(results, spacing):
    exo = os.path.join(results, "results.e")
    x = pr.read_coordinates(exo)[:, 0]
    D = pr.read_field(exo, "material_damage")
    planes = np.round(x / spacing - 0.5).astype(int)
    keys = np.unique(planes)
    mean = np.array([D[planes == k].mean() for k in keys])
    centre = (keys + 0.5) * spacing
    band = int((mean >= 0.5).sum())
    half = D >= 0.5
    rows = list(csv.DictReader(open(os.path.join(results, "history.csv"))))
    last = rows[-1]
    return {
        "band_planes": band,
        "band_width_mm": band * spacing * 1e3,
        "extent_mm": (x[half].max() - x[half].min() + spacing) * 1e3 if half.any() else 0.0,
        "failed": int((D >= 1).sum()),
        "points": len(x),
        "broken_fraction": float(last.get("broken_fraction", 0) or 0),
        "final_reaction_N": float(last["reaction_right_x"]),
        "peak_reaction_N": max(float(r["reaction_right_x"]) for r in rows),
        "late_mean_N": float(np.mean([float(r["reaction_right_x"]) for r in rows
                                      if float(r["time"]) >= 0.5 * float(last["time"])])),
        "profile": (centre, mean),
    }


def main():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--peridot", required=True)
    p.add_argument("--out", required=True)
    p.add_argument("--threads", type=int, default=0)
    p.add_argument("--plot")
    p.add_argument("--fixed-horizon", type=float, help="δ (m) held fixed while Δx shrinks (δ-convergence)")
    p.add_argument("--check-short", action="store_true")
    a = p.parse_args()
    deck = yaml.safe_load(open(os.path.join(HERE, "deck.yaml")))
    spacings = [float(str(deck["discretization"]["spacing"]).split()[0]) * 1e-3] if a.check_short else SPACINGS
    table = {}
    print(f"{'coupling':20s} {'Δx mm':>6s} {'δ mm':>6s} {'points':>7s} {'band mm':>8s} {'band/δ':>6s} "
          f"{'D≥0.5 extent mm':>15s} {'failed':>6s} {'broken':>7s} {'peak N':>8s} {'late N':>8s}")
    for coupling in COUPLINGS:
        for spacing in spacings:
            horizon = a.fixed_horizon or 3.015 * spacing
            name, results = run(a.peridot, a.out, spacing, coupling, a.threads, a.fixed_horizon)
            m = measure(results, spacing)
            table[(coupling, spacing)] = m
            print(f"{coupling:20s} {spacing * 1e3:6.2f} {horizon * 1e3:6.3f} {m['points']:7d} {m['band_width_mm']:8.2f} "
                  f"{m['band_width_mm'] / (horizon * 1e3):6.2f} {m['extent_mm']:15.2f} {m['failed']:6d} "
                  f"{m['broken_fraction']:7.4f} {m['peak_reaction_N']:8.0f} {m['late_mean_N']:8.0f}", flush=True)
    if a.plot:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
        fig, axes = plt.subplots(1, 2, figsize=(11, 4))
        for coupling, style in zip(COUPLINGS, ["-", "--"]):
            for spacing in spacings:
                centre, mean = table[(coupling, spacing)]["profile"]
                axes[0].plot(centre * 1e3, mean, style, label=f"{coupling}, Δx = {spacing * 1e3:.2f} mm")
            horizons = [a.fixed_horizon or 3.015 * s for s in spacings]
            axes[1].plot([s * 1e3 for s in spacings],
                         [table[(coupling, s)]["band_width_mm"] / (h * 1e3) for s, h in zip(spacings, horizons)],
                         "o" + style, label=coupling)
        axes[0].set_xlim(-6, 6)
        axes[0].set_xlabel("x (mm), the notch at 0")
        axes[0].set_ylabel("mean D over the plane")
        axes[0].legend(fontsize=7)
        axes[1].set_xlabel("Δx (mm)")
        axes[1].set_ylabel("band width / δ (planes with mean D ≥ 0.5)")
        axes[1].set_ylim(bottom=0)
        axes[1].legend()
        axes[1].invert_xaxis()
        fig.suptitle("Notched 6061-T6 bar, Johnson–Cook damage: influence function vs local stress, "
                     + (f"δ = {a.fixed_horizon * 1e3:.3g} mm" if a.fixed_horizon else "δ = 3.015 Δx"), fontsize=10)
        fig.tight_layout()
        fig.savefig(a.plot, dpi=120)
    if a.check_short:
        spacing = spacings[0]
        horizon = 3.015 * spacing
        influence, local = table[("influence_function", spacing)], table[("local_stress", spacing)]
        ok = (influence["band_width_mm"] <= 1.5 * horizon * 1e3 and influence["failed"] > 0
              and local["band_width_mm"] >= 2 * influence["band_width_mm"])
        print("ok" if ok else "FAIL", "short check: influence band", influence["band_width_mm"], "mm, local band",
              local["band_width_mm"], "mm, δ", horizon * 1e3, "mm")
        sys.exit(0 if ok else 1)


if __name__ == "__main__":
    main()
