#!/usr/bin/python3
"""Creep and recovery of the viscoelastic bar (deck.yaml, the 1D thermoviscoelastic model) against the closed form.

The bar's solid: Young's modulus E(t) = E∞ + Σ E_k exp(−t/τ_k) (the paper's Table 1). Under a stress history σ(t) its
strain is ε(t) = ∫ D(t − s) dσ(s), D the creep compliance, the inverse of E in the Laplace domain (docs/algorithms.md
§11, with E for μ): for σ0 on [0, t1), ε(t) = σ0 [D(t) − H(t − t1) D(t − t1)]. Two measures of the bar's strain:

- the middle: the displacement difference of the points at L/4 and 3L/4 over their distance (no end within δ);
- the whole bar: the last point's displacement over its distance to the held first point (both ends' boundary
  layers included).

    bar.py --peridot PATH [--out DIR] [--threads N] [--spacing MM] [--horizon MM] [--check TOL] [--check-whole TOL]
    bar.py --peridot PATH --convergence [--out DIR]

The first form runs deck.yaml (Δx = 3 mm, δ = 9 mm, or the given ones), writes DIR/creep.png and prints the table;
--check TOL exits 1 unless the middle is within TOL (a fraction of the largest closed-form strain) at every output
time, --check-whole TOL the same for the whole bar. The second runs m = δ/Δx = 1, 2, 3 at δ = 15 mm and Δx = 6, 3,
1.5 mm at m = 3 and prints both measures' largest differences."""
import argparse
import csv
import os
import re
import subprocess
import sys

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
SIGMA, RELEASE, L = 2000.0, 0.005, 0.3
E_INF = 700e6
E_TERMS = [200, 800, 1500, 1000, 1100, 2700, 2900, 2500, 900, 950, 600, 120, 180, 200, 250]  # MPa, Table 1
TAUS = [1e-4, 1e-3, 1e-2, 1, 10, 100, 1e3, 1e4, 1e5, 1e6, 1e7, 1e8, 1e9, 1e11, 3e12]


def creep_compliance():
    """D(t) of E(t): 1/E∞ + Σ_k exp(ρ_k t)/(ρ_k g′(ρ_k)), ρ_k the roots of g(s) = E∞ + Σ E_i s/(s + λ_i), one
    between each pair of consecutive −λ (and in (−λ_min, 0)), found by bisection."""
    E = np.array(E_TERMS) * 1e6
    lam = 1 / np.array(TAUS)
    g = lambda s: E_INF + np.sum(E * s / (s + lam))
    dg = lambda s: np.sum(E * lam / (s + lam) ** 2)
    order = np.argsort(lam)
    roots = []
    for k, idx in enumerate(order):
        lo, hi = -lam[idx], (0.0 if k == 0 else -lam[order[k - 1]])
        for _ in range(400):
            mid = 0.5 * (lo + hi)
            if mid <= lo or mid >= hi:
                break
            if g(mid) < 0:
                lo = mid
            else:
                hi = mid
        roots.append(0.5 * (lo + hi))
    amplitude = [1 / (r * dg(r)) for r in roots]
    return lambda t: 1 / E_INF + sum(a * np.exp(r * t) for a, r in zip(amplitude, roots))


def closed_form(t):
    D = creep_compliance()
    return np.array([SIGMA * (D(s) - (D(s - RELEASE) if s >= RELEASE - 1e-12 else 0.0)) for s in t])


def deck_text(spacing, horizon):
    """deck.yaml with Δx and δ replaced (m), its node sets and probes moved to the points of that lattice (at
    (i + ½)Δx within [0, L]); returns it and the distances the middle and the whole bar span."""
    with open(os.path.join(HERE, "deck.yaml")) as f:
        text = f.read()
    count = int(np.floor(L / spacing - 0.5 + 1e-9)) + 1
    x = (np.arange(count) + 0.5) * spacing
    quarter, three_quarters = x[round((count - 1) / 4)], x[count - 1 - round((count - 1) / 4)]
    replace = [
        (r"spacing: 3 mm", f"spacing: {spacing!r}"),
        (r"horizon: 9 mm", f"horizon: {horizon!r}"),
        (r"max: \[0.003\]", f"max: [{spacing!r}]"),
        (r"min: \[0.297\]", f"min: [{x[-1] - spacing / 2!r}]"),
        (r"point: \[0.0765\]", f"point: [{quarter!r}]"),
        (r"point: \[0.2235\]", f"point: [{three_quarters!r}]"),
        (r"point: \[0.2985\]", f"point: [{x[-1]!r}]"),
    ]
    for pattern, new in replace:
        text, n = re.subn(pattern, new, text)
        assert n == 1, pattern
    return text, three_quarters - quarter, x[-1] - x[0]


def run(peridot, out, threads, spacing, horizon):
    """Runs the bar; returns the output times, the middle's and the whole bar's strain."""
    os.makedirs(out, exist_ok=True)
    text, middle_span, whole_span = deck_text(spacing, horizon)
    deck = os.path.join(out, "deck.yaml")
    with open(deck, "w") as f:
        f.write(text)
    subprocess.run([peridot, "run", "-q", "-t", str(threads), "-o", out, deck], check=True)
    with open(os.path.join(out, "history.csv")) as f:
        rows = list(csv.DictReader(f))
    column = lambda name: np.array([float(r[name]) for r in rows])
    t = column("time")
    return t, (column("u_three_quarters") - column("u_quarter")) / middle_span, column("u_end") / whole_span


def plot(path, t, middle, whole):
    try:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
    except ImportError:
        return
    fine = np.linspace(0, t.max(), 400)
    fig, ax = plt.subplots(figsize=(6, 4))
    ax.plot(1e3 * fine, 1e6 * closed_form(fine), "k-", label="closed form σ0 [D(t) − H(t − t1) D(t − t1)]")
    ax.plot(1e3 * t, 1e6 * middle, "o", ms=3, label="Peridot, middle of the bar")
    ax.plot(1e3 * t, 1e6 * whole, "x", ms=3, label="Peridot, whole bar")
    ax.set_xlabel("t (ms)")
    ax.set_ylabel("strain (µε)")
    ax.set_title("1D bar, Table 1 epoxy, σ0 = 2 kPa released at 5 ms")
    ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(path, dpi=120)


def main():
    p = argparse.ArgumentParser()
    p.add_argument("--peridot", required=True)
    p.add_argument("--out", default=os.path.join(HERE, "out"))
    p.add_argument("--threads", type=int, default=1)
    p.add_argument("--spacing", type=float, default=3.0, help="Δx (mm)")
    p.add_argument("--horizon", type=float, default=9.0, help="δ (mm)")
    p.add_argument("--check", type=float, default=None, help="largest allowed difference of the middle (fraction)")
    p.add_argument("--check-whole", type=float, default=None, help="largest allowed difference of the whole bar")
    p.add_argument("--convergence", action="store_true")
    a = p.parse_args()
    if a.convergence:
        cases = [(15.0, 15.0), (7.5, 15.0), (5.0, 15.0), (6.0, 18.0), (3.0, 9.0), (1.5, 4.5)]  # (Δx, δ) mm
        print(f"{'dx (mm)':>8} {'delta (mm)':>10} {'m':>3} {'middle':>10} {'whole bar':>10}")
        for dx, delta in cases:
            t, middle, whole = run(a.peridot, os.path.join(a.out, f"dx{dx:g}_delta{delta:g}"), a.threads, 1e-3 * dx, 1e-3 * delta)
            exact = closed_form(t)
            scale = np.abs(exact).max()
            print(f"{dx:8.2f} {delta:10.2f} {delta / dx:3.0f} {100 * np.abs(middle - exact).max() / scale:9.3f}% "
                  f"{100 * np.abs(whole - exact).max() / scale:9.3f}%", flush=True)
        return
    t, middle, whole = run(a.peridot, a.out, a.threads, 1e-3 * a.spacing, 1e-3 * a.horizon)
    exact = closed_form(t)
    scale = np.abs(exact).max()
    print(f"{'t (ms)':>8} {'middle':>14} {'whole bar':>14} {'closed form':>14}")
    for s, m, w, e in zip(t, middle, whole, exact):
        print(f"{1e3 * s:8.2f} {m:14.6e} {w:14.6e} {e:14.6e}")
    worst_middle = np.abs(middle - exact).max() / scale
    worst_whole = np.abs(whole - exact).max() / scale
    print(f"largest difference, as a fraction of the largest closed-form strain: middle {100 * worst_middle:.3f} %, "
          f"whole bar {100 * worst_whole:.3f} %")
    plot(os.path.join(a.out, "creep.png"), t, middle, whole)
    failed = False
    if a.check is not None and worst_middle > a.check:
        print(f"FAIL: the middle is more than {100 * a.check:g} % from the closed form")
        failed = True
    if a.check_whole is not None and worst_whole > a.check_whole:
        print(f"FAIL: the whole bar is more than {100 * a.check_whole:g} % from the closed form")
        failed = True
    sys.exit(1 if failed else 0)


if __name__ == "__main__":
    main()
