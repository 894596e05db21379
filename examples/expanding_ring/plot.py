#!/usr/bin/python3
"""Expanding ring, ductile (deck.yaml) against brittle (deck_brittle.yaml).

Writes ring.png (the deformed rings at the last frame: equivalent plastic strain and damage of the
elastic-plastic ring, damage of the brittle one) and history.png (kinetic energy, plastic work and the
number of fragments against time), and prints the fragment counts of both rings.

A fragment is a connected set of points through intact bonds (Peridot's `fragment` field labels each
point with the smallest input id of its fragment). Single points or small clusters torn off a crack face
count as fragments too, so the count is also given for pieces of at least MIN_POINTS points.

Run from this folder after both simulations:  /usr/bin/python3 plot.py [out_dir brittle_out_dir]
"""

import csv
import pathlib
import sys

import numpy as np

HERE = pathlib.Path(__file__).resolve().parent
sys.path.insert(0, str(HERE.parents[1] / "tools"))
import peridot_results as pr  # noqa: E402
import matplotlib.pyplot as plt  # noqa: E402

MIN_POINTS = 50  # a "piece": at least this many points (the cross-section has 64)


def fragments(res):
    labels = res.field("fragment")
    _, sizes = np.unique(labels, return_counts=True)
    sizes = np.sort(sizes)[::-1]
    return len(sizes), int(np.sum(sizes >= MIN_POINTS)), sizes


def history(path):
    rows = list(csv.DictReader(open(path)))
    return {k: np.array([float(r[k]) for r in rows]) for k in rows[0]}


def main(ductile_dir, brittle_dir):
    runs = [("elastic-plastic (lps_plastic)", ductile_dir), ("brittle (lps)", brittle_dir)]
    fig, axes = plt.subplots(1, 3, figsize=(17, 5.8))
    summary = []
    for k, (name, folder) in enumerate(runs):
        with pr.Results(folder / "ring.e") as res:
            y = res.positions()
            t = res.times[-1]
            total, pieces, sizes = fragments(res)
            summary.append((name, total, pieces, sizes[:8].tolist(), t))
            fields = [("equivalent_plastic_strain", "magma"), ("damage", "viridis")] if k == 0 else [("damage", "viridis")]
            for field, cmap in fields:
                ax = axes[0 if field == "equivalent_plastic_strain" else (1 if k == 0 else 2)]
                values = res.field(field)
                order = np.argsort(values)  # draw the highest values last
                sc = ax.scatter(1e3 * y[order, 0], 1e3 * y[order, 1], c=values[order], s=0.4, cmap=cmap,
                                vmin=0, vmax=1 if field == "damage" else None)
                fig.colorbar(sc, ax=ax, shrink=0.8)
                ax.set_title(f"{name}: {field.replace('_', ' ')}\n{pieces} pieces of ≥ {MIN_POINTS} points, "
                             f"{total} fragments in all, t = {t * 1e6:.0f} µs", fontsize=10)
                ax.set_aspect("equal")
                ax.set_xlabel("x (mm)")
                ax.set_ylabel("y (mm)")
    fig.tight_layout()
    fig.savefig(HERE / "ring.png", dpi=90)

    fig, axes = plt.subplots(1, 2, figsize=(12, 4.5))
    for name, folder in runs:
        h = history(folder / "history.csv")
        line, = axes[0].plot(1e6 * h["time"], h["kinetic_energy"], label=f"{name}: kinetic")
        if np.any(h["dissipated_energy"] > 0):
            axes[0].plot(1e6 * h["time"], h["dissipated_energy"], "--", color=line.get_color(),
                         label=f"{name}: plastic work")
        axes[0].plot(1e6 * h["time"], h["kinetic_energy"] + h["strain_energy"] + h["dissipated_energy"], ":",
                     color=line.get_color(), label=f"{name}: kinetic + stored + plastic")
        axes[1].plot(1e6 * h["time"], h["fragments"], label=name)
    axes[0].set_xlabel("time (µs)")
    axes[0].set_ylabel("energy (J)")
    axes[0].legend(fontsize=8)
    axes[1].set_xlabel("time (µs)")
    axes[1].set_ylabel("fragments (connected sets of points)")
    axes[1].set_yscale("log")
    axes[1].legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(HERE / "history.png", dpi=90)

    for name, total, pieces, largest, t in summary:
        print(f"{name}: {pieces} pieces of at least {MIN_POINTS} points, {total} fragments in all "
              f"(largest: {largest}) at t = {t * 1e6:.0f} µs")
    print(f"wrote {HERE / 'ring.png'} and {HERE / 'history.png'}")


if __name__ == "__main__":
    args = [pathlib.Path(a) for a in sys.argv[1:3]]
    main(*(args if len(args) == 2 else [HERE / "out", HERE / "out_brittle"]))
