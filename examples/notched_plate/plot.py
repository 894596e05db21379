#!/usr/bin/python3
"""Load–displacement curve and final damage of the notched plate (out/history.csv, out/notched_plate.e):
writes load_displacement.png. With --check, also verifies that the curve rises, peaks and falls."""
import argparse
import csv
import os
import sys

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
GRIP = 8e-6  # m, each grip's displacement at the last load step (deck.yaml)


def main():
    p = argparse.ArgumentParser()
    p.add_argument("--out", default=os.path.join(HERE, "out"))
    p.add_argument("--check", action="store_true")
    p.add_argument("--png", default=os.path.join(HERE, "load_displacement.png"))
    a = p.parse_args()
    rows = list(csv.DictReader(open(os.path.join(a.out, "history.csv"))))
    opening = np.array([2 * GRIP * float(r["load_factor"]) for r in rows]) * 1e6  # µm, grip to grip
    load = np.array([float(r["reaction_top_y"]) for r in rows])
    damage = np.array([float(r["max_damage"]) for r in rows])
    broken = np.array([float(r["bonds_broken"]) for r in rows])
    iterations = np.array([float(r["iterations"]) for r in rows])
    print("| opening (µm) | load (N) | bonds broken | iterations |")
    print("|---|---|---|---|")
    for o, f, b, it in zip(opening, load, broken, iterations):
        print(f"| {o:.2f} | {f:.1f} | {int(b)} | {int(it)} |")
    peak = int(np.argmax(load))
    rises = peak > 1 and all(np.diff(load[: peak + 1]) > 0)
    falls = peak < len(load) - 1 and load[-1] < 0.5 * load[peak]
    print(("ok   " if rises else "FAIL ") + f"the load rises to its peak {load[peak]:.1f} N at {opening[peak]:.2f} µm")
    print(("ok   " if falls else "FAIL ") + f"then falls to {load[-1]:.1f} N as the crack grows")

    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    import netCDF4
    d = netCDF4.Dataset(os.path.join(a.out, "notched_plate.e"))
    names = [str(n).strip() for n in netCDF4.chartostring(d.variables["name_nod_var"][:])]
    x, y = np.asarray(d.variables["coordx"][:]), np.asarray(d.variables["coordy"][:])
    phi = np.asarray(d.variables[f"vals_nod_var{names.index('damage') + 1}"][-1])
    fig, (left, right) = plt.subplots(1, 2, figsize=(11, 4))
    left.plot(opening, load, "o-")
    left.set_xlabel("grip opening (µm)")
    left.set_ylabel("grip reaction (N)")
    left.set_title("load steps relaxed to equilibrium")
    left.grid(alpha=0.3)
    sc = right.scatter(x * 1e3, y * 1e3, c=phi, s=4, cmap="inferno", vmin=0, vmax=1)
    right.set_aspect("equal")
    right.set_xlabel("x (mm)")
    right.set_ylabel("y (mm)")
    right.set_title("damage at the last load step")
    fig.colorbar(sc, ax=right, label="damage")
    fig.tight_layout()
    fig.savefig(a.png, dpi=110)
    print("wrote", a.png)
    return 0 if (rises and falls) or not a.check else 1


if __name__ == "__main__":
    sys.exit(main())
