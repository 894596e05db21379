#!/usr/bin/python3
"""Creep and recovery of the viscoelastic bar (deck.yaml, the 1D thermoviscoelastic model) against the closed form.

The bar's solid: Young's modulus E(t) = E∞ + Σ E_k exp(−t/τ_k) (the paper's Table 1). Under a stress history σ(t) its
strain is ε(t) = ∫ D(t − s) dσ(s), D the creep compliance, the inverse of E in the Laplace domain (docs/algorithms.md
§11 and tools/prony.py, with E for μ): for σ0 on [0, t1), ε(t) = σ0 [D(t) − H(t − t1) D(t − t1)]. Two measures of the bar's strain:

- the middle: the displacement difference of the points at L/4 and 3L/4 over their distance (no end within δ);
- the whole bar: the last point's displacement over its distance to the held first point (both ends' boundary
  layers included).

    bar.py --peridot PATH [--out DIR] [--threads N] [--spacing MM] [--horizon MM] [--case cold|hot] [--check TOL]
           [--check-whole TOL]
    bar.py --peridot PATH --convergence [--out DIR]

The first form runs deck.yaml (Δx = 3 mm, δ = 9 mm, or the given ones), writes DIR/creep.png and prints the table;
--case hot runs it at the paper's §8.2 conditions instead (200 °C, its WLF shift, α = 50e-6 /K, σ0 = 1 MPa,
8 creep substeps after each load jump), compares the strain less the free thermal strain α ΔT with the closed form
of the shifted times, and writes DIR/creep_hot.png;
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
sys.path.insert(0, os.path.join(HERE, "..", "..", "tools"))
import prony  # noqa: E402  (the closed-form creep compliance)
SIGMA, RELEASE, L = 2000.0, 0.005, 0.3
E_INF = 700e6
E_TERMS = [200, 800, 1500, 1000, 1100, 2700, 2900, 2500, 900, 950, 600, 120, 180, 200, 250]  # MPa, Table 1
TAUS = [1e-4, 1e-3, 1e-2, 1, 10, 100, 1e3, 1e4, 1e5, 1e6, 1e7, 1e8, 1e9, 1e11, 3e12]
# --case hot, the paper's §8.2 conditions on the bar: a uniform 200 °C, σ0 = 1 MPa, WLF c1 = 30, c2 = 100 K,
# T0 = 110 °C (its eq 44), α = 50e-6 /K from 20 °C. Shifted, 13 of the 15 times fall below 10 µs, far inside the
# first step after each load jump: 8 creep substeps follow them there.
HOT_SIGMA, HOT_T, REFERENCE_T, WLF_C1, WLF_C2, WLF_T0, ALPHA, HOT_SUBSTEPS = 1e6, 473.15, 293.15, 30.0, 100.0, 383.15, 50e-6, 8


def wlf_shift(hot):
    """a_T: τ_k → a_T τ_k (1 at the WLF reference temperature)."""
    if not hot:
        return 1.0
    above = HOT_T - WLF_T0
    return 10 ** (-WLF_C1 * above / (WLF_C2 + above))


def creep_compliance(hot=False):
    """D(t) of E(t), the relaxation times shifted in the hot case (tools/prony.py)."""
    return prony.creep_compliance(E_INF, np.array(E_TERMS) * 1e6, wlf_shift(hot) * np.array(TAUS))


def closed_form(t, hot=False):
    """The mechanical strain σ0 [D(t) − H(t − t1) D(t − t1)] (the hot case's thermal strain α ΔT not included)."""
    D = creep_compliance(hot)
    sigma = HOT_SIGMA if hot else SIGMA
    return np.array([sigma * (D(s) - (D(s - RELEASE) if s >= RELEASE - 1e-12 else 0.0)) for s in t])


def deck_text(spacing, horizon, hot=False):
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
    if hot:
        replace += [
            (r'x: "2000 \* \(t < 0.00495\)"', f'x: "{HOT_SIGMA!r} * (t < 0.00495)"'),
            (r"    prony_series:", f"    thermal_expansion: {ALPHA!r}\n"
                                    f"    wlf: {{c1: {WLF_C1!r}, c2: {WLF_C2!r}, reference_temperature: {WLF_T0!r}}}\n"
                                    "    prony_series:"),
            (r"boundary_conditions:", f'temperature: {{value: "{HOT_T!r}", reference: {REFERENCE_T!r}}}\n'
                                      "boundary_conditions:"),
            (r"  load_history: steps", f"  creep_substeps: {HOT_SUBSTEPS}\n  load_history: steps"),
        ]
    for pattern, new in replace:
        text, n = re.subn(pattern, new, text)
        assert n == 1, pattern
    return text, three_quarters - quarter, x[-1] - x[0]


def run(peridot, out, threads, spacing, horizon, hot=False):
    """Runs the bar; returns the output times, the middle's and the whole bar's strain (mechanical: the hot case's
    free thermal strain α ΔT taken off)."""
    os.makedirs(out, exist_ok=True)
    text, middle_span, whole_span = deck_text(spacing, horizon, hot)
    deck = os.path.join(out, "deck.yaml")
    with open(deck, "w") as f:
        f.write(text)
    subprocess.run([peridot, "run", "-q", "-t", str(threads), "-o", out, deck], check=True)
    with open(os.path.join(out, "history.csv")) as f:
        rows = list(csv.DictReader(f))
    column = lambda name: np.array([float(r[name]) for r in rows])
    t = column("time")
    thermal = ALPHA * (HOT_T - REFERENCE_T) if hot else 0.0
    return (t, (column("u_three_quarters") - column("u_quarter")) / middle_span - thermal,
            column("u_end") / whole_span - thermal)


def plot(path, t, middle, whole, hot=False):
    try:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
    except ImportError:
        return
    fine = np.linspace(0, t.max(), 400)
    fig, ax = plt.subplots(figsize=(6, 4))
    ax.plot(1e3 * fine, 1e6 * closed_form(fine, hot), "k-", label="closed form σ0 [D(t) − H(t − t1) D(t − t1)]")
    ax.plot(1e3 * t, 1e6 * middle, "o", ms=3, label="Peridot, middle of the bar")
    ax.plot(1e3 * t, 1e6 * whole, "x", ms=3, label="Peridot, whole bar")
    ax.set_xlabel("t (ms)")
    ax.set_ylabel("strain less α ΔT (µε)" if hot else "strain (µε)")
    ax.set_title("1D epoxy bar, " + ("200 °C (WLF), σ0 = 1 MPa" if hot else "σ0 = 2 kPa") + ", released at 5 ms")
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
    p.add_argument("--case", choices=["cold", "hot"], default="cold",
                   help="hot: §8.2's 200 °C, WLF shift and thermal strain, σ0 = 1 MPa")
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
    hot = a.case == "hot"
    t, middle, whole = run(a.peridot, a.out, a.threads, 1e-3 * a.spacing, 1e-3 * a.horizon, hot)
    exact = closed_form(t, hot)
    scale = np.abs(exact).max()
    print(f"{'t (ms)':>8} {'middle':>14} {'whole bar':>14} {'closed form':>14}")
    for s, m, w, e in zip(t, middle, whole, exact):
        print(f"{1e3 * s:8.2f} {m:14.6e} {w:14.6e} {e:14.6e}")
    worst_middle = np.abs(middle - exact).max() / scale
    worst_whole = np.abs(whole - exact).max() / scale
    print(f"largest difference, as a fraction of the largest closed-form strain: middle {100 * worst_middle:.3f} %, "
          f"whole bar {100 * worst_whole:.3f} %")
    plot(os.path.join(a.out, "creep_hot.png" if hot else "creep.png"), t, middle, whole, hot)
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
