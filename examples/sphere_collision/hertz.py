#!/usr/bin/python3
"""Two elastic spheres colliding head on (deck.yaml) against Hertz's theory, at several resolutions.

    hertz.py --peridot PATH [--ratios 10,15,20] [--threads N] [--out DIR] [--check TOL]

Hertz, for two spheres of radius R, Young's modulus E, Poisson ratio ν (1/4 for bond-based PMB), density ρ, closing
at relative speed v: with E* = E / (2(1 − ν²)), R* = R/2, m* = m/2 (m = 4πR³ρ/3), the largest approach is
δ_max = (15 m* v² / (16 E* √R*))^(2/5), the peak force F_max = (4/3) E* √R* δ_max^(3/2), and the contact lasts
t_c = 2.9432 δ_max / v. For each R/Δx the script runs deck.yaml (the spacing R/ratio, the gap between the
spheres kept at 3 mm), takes the force on the right sphere from the history (contact_right_x, every step), and
prints the peak force, the contact duration (first to last step with a force) and the largest momentum
(relative to m v/2). Writes DIR/hertz.png. --check TOL exits 1 unless the finest run's peak force and contact
time are both within TOL (a fraction) of Hertz's."""
import argparse
import csv
import math
import os
import pathlib
import re
import subprocess
import sys

import numpy as np

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

HERE = pathlib.Path(__file__).resolve().parent
R, E, NU, RHO, V = 5e-3, 70e9, 0.25, 2700.0, 100.0


def hertz():
    m = 4 / 3 * math.pi * R ** 3 * RHO
    e_star, r_star, m_star = E / (2 * (1 - NU ** 2)), R / 2, m / 2
    delta = (15 * m_star * V ** 2 / (16 * e_star * math.sqrt(r_star))) ** 0.4
    force = 4 / 3 * e_star * math.sqrt(r_star) * delta ** 1.5
    duration = 2.9432 * delta / V
    return m, delta, force, duration


def hertz_force(t, delta_max, duration):
    """F(t) of the Hertz impact, from the approach δ(t) ≈ δ_max sin(π t / t_c)^(1/1.0) (the quasi-static
    solution's shape is close to a sine; used only for the plot)."""
    m, _, fmax, _ = hertz()
    s = np.clip(np.sin(np.pi * t / duration), 0, None)
    return fmax * s ** 1.5


def run(peridot, ratio, out, threads, pole):
    spacing = R / ratio
    text = (HERE / "deck.yaml").read_text()
    text = text.replace("spacing: 0.5 mm             # R/dx = 10", f"spacing: {spacing * 1e3:.10g} mm")
    # The surfaces about 3 mm apart; the centres on lattice planes (multiples of Δx: a flat facet of points at
    # each pole) or, with pole == "point", on lattice points ((i + ½)Δx: one point at each pole).
    half = 0.5 if pole == "point" else 0.0
    centre = (round((R + 1.5e-3) / spacing - half) + half) * spacing
    off = half * spacing * 1e3
    text = text.replace("center: [-6.5 mm, 0, 0]", f"center: [{-centre * 1e3:.10g} mm, {off:.10g} mm, {off:.10g} mm]")
    text = text.replace("center: [6.5 mm, 0, 0]", f"center: [{centre * 1e3:.10g} mm, {off:.10g} mm, {off:.10g} mm]")
    name = f"ratio{ratio:g}_{pole}"
    text = text.replace("directory: out", f"directory: {out / name}")
    deck = out / f"{name}.yaml"
    deck.write_text(text)
    env = dict(os.environ, OMP_NUM_THREADS=str(threads))
    subprocess.run([peridot, "run", "-q", str(deck)], check=True, env=env)
    with open(out / name / "history.csv") as f:
        rows = list(csv.DictReader(f))
    col = lambda key: np.array([float(r[key]) for r in rows])  # noqa: E731
    return col("time"), col("contact_right_x"), col("momentum_x"), 2 * (centre - R)


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--peridot", required=True)
    ap.add_argument("--ratios", default="10,15,20")
    ap.add_argument("--threads", type=int, default=1)
    ap.add_argument("--out", default=str(HERE / "out"))
    ap.add_argument("--check", type=float)
    ap.add_argument("--pole", choices=["facet", "point"], default="facet",
                    help="centres on lattice planes (a flat facet at each pole) or on lattice points (one pole point)")
    a = ap.parse_args()
    out = pathlib.Path(a.out).resolve()
    out.mkdir(parents=True, exist_ok=True)
    m, delta, fmax, duration = hertz()
    print(f"Hertz: δ_max = {delta * 1e3:.4f} mm, F_max = {fmax:.1f} N, t_c = {duration * 1e6:.3f} µs")
    print("| R/Δx | peak force (N) | vs Hertz | contact time (µs) | vs Hertz | largest momentum / (m v/2) |")
    print("|---|---|---|---|---|---|")
    fig, ax = plt.subplots(figsize=(7, 4.2))
    errors = None
    for ratio in [float(r) for r in a.ratios.split(",")]:
        t, force, momentum, gap = run(a.peridot, ratio, out, a.threads, a.pole)
        touching = np.nonzero(force > 0)[0]
        dt = t[1] - t[0]
        start, end = t[touching[0]] - 0.5 * dt, t[touching[-1]] + 0.5 * dt
        peak = force.max()
        errors = (peak / fmax - 1, (end - start) / duration - 1)
        print(f"| {ratio:g} | {peak:.1f} | {errors[0] * 100:+.1f} % | {(end - start) * 1e6:.3f} | {errors[1] * 100:+.1f} % | "
              f"{np.abs(momentum).max() / (m * V / 2):.2g} |")
        ax.plot((t - start) * 1e6, force / 1e3, label=f"Peridot, R/Δx = {ratio:g}")
    tt = np.linspace(0, duration, 200)
    ax.plot(tt * 1e6, hertz_force(tt, delta, duration) / 1e3, "k--", label="Hertz (F_max, t_c; sine-shaped)")
    ax.set_xlabel("time from first contact (µs)")
    ax.set_ylabel("contact force (kN)")
    ax.set_title("Two aluminium spheres, R = 5 mm, closing at 100 m/s")
    ax.grid(alpha=0.3)
    ax.legend()
    fig.tight_layout()
    fig.savefig(out / "hertz.png", dpi=120)
    print(f"wrote {out / 'hertz.png'}")
    if a.check is not None:
        ok = abs(errors[0]) <= a.check and abs(errors[1]) <= a.check
        print(f"{'ok' if ok else 'FAIL'}: finest run within {a.check * 100:g} % of Hertz: {ok}")
        sys.exit(0 if ok else 1)


if __name__ == "__main__":
    main()
