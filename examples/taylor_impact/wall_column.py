#!/usr/bin/python3
"""Runs wall_column.yaml (an elastic column pressed onto the rigid wall, relaxed to equilibrium) at several
hourglass coefficients and prints, for the inner quarter of the cross-section, how much each of the first
layer gaps differs from Δx and the mean σ_zz of each layer. A uniform compression would shorten every gap by
the same ≈ 1.5–2 µm; the alternation is the zero-energy mode that the one-layer contact force drives.
With --contact symmetry the wall is a symmetry plane on the column's base (contact: symmetry) and the
alternation is gone (README, "The face layers").

    /usr/bin/python3 examples/taylor_impact/wall_column.py --peridot build/peridot --out wall_column_runs
"""
import argparse
import os
import re
import subprocess
import sys

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(HERE, "..", "..", "tools"))
import peridot_results as pr  # noqa: E402


def layer_profile(exodus_path, spacing, layers=10):
    with pr.Results(exodus_path) as res:
        x = res.coords.T
        z, szz = res.positions()[:, 2], res.field("cauchy_stress_zz")
    layer = np.rint((x[2] - x[2].min()) / spacing).astype(int)
    inner = (np.abs(x[0]) < 0.25 * np.ptp(x[0])) & (np.abs(x[1]) < 0.25 * np.ptp(x[1]))
    height = np.array([z[inner & (layer == k)].mean() for k in range(layers)])
    stress = np.array([szz[inner & (layer == k)].mean() for k in range(layers)])
    return np.diff(height) - spacing, stress


def main():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--peridot", required=True)
    p.add_argument("--out", default="wall_column_runs")
    p.add_argument("--hourglass", default="0.02,0.05", help="comma-separated hourglass coefficients")
    p.add_argument("--contact", choices=("penalty", "symmetry"), default="penalty",
                   help="the wall's contact: penalty (the plane through the first layer's centres) or symmetry "
                        "(the plane on the column's base, half a spacing below them)")
    a = p.parse_args()
    template = open(os.path.join(HERE, "wall_column.yaml")).read()
    if a.contact == "symmetry":
        template = template.replace("{name: anvil, point: [0, 0, 0.0005], normal: [0, 0, 1]}",
                                    "{name: anvil, point: [0, 0, 0], normal: [0, 0, 1], contact: symmetry}")
    spacing = 1e-3
    for c in a.hourglass.split(","):
        run_dir = os.path.join(os.path.abspath(a.out), f"{a.contact}_hg{c}")
        os.makedirs(run_dir, exist_ok=True)
        deck = os.path.join(run_dir, "deck.yaml")
        open(deck, "w").write(re.sub(r"hourglass_coefficient: [^\n]*", f"hourglass_coefficient: {c}", template))
        subprocess.run([a.peridot, "run", "-q", "-t", "1", deck], check=True)
        gaps, stress = layer_profile(os.path.join(run_dir, "output", "results.e"), spacing)
        print(f"C_HG = {c}, contact: {a.contact}")
        print("  gap − Δx (µm), from the wall:", " ".join(f"{g * 1e6:7.2f}" for g in gaps))
        print("  σ_zz (MPa), layer by layer:  ", " ".join(f"{s / 1e6:7.1f}" for s in stress))
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
