#!/usr/bin/python3
"""Creep and recovery of the viscoelastic plate (deck.yaml) against the closed form of the same solid.

The solid of the 2D thermoviscoelastic model: in-plane bulk modulus κ elastic (from K and the glassy μ0, plane
stress κ = 9Kμ0/(3K + 4μ0)), shear modulus the Prony series μ(t). Under uniaxial stress σ(t) its strain is
ε_xx = ∫ [1/(4κ) + J(t − s)/4] dσ(s), J the shear creep compliance (docs/algorithms.md §11: the inverse of μ in the
Laplace domain: tools/prony.py). For σ0 on [0, t1): ε(t) = σ0 [D(t) − H(t − t1) D(t − t1)], D = 1/(4κ) +
J/4. The plate is free to contract laterally, so away from its ends u_x = ε_xx (x − x₀), x₀ the rollers' row.

    creep.py --peridot PATH [--out DIR] [--threads N] [--spacing MM] [--horizon MM] [--check TOL] [--case shear]
    creep.py --peridot PATH --convergence [--out DIR]

The first form runs deck.yaml (Δx = 5 mm, δ = 15 mm, or the given ones: the deck's lengths are replaced), writes
DIR/creep.png (u_x at (L, W/2) against time, Peridot and the closed form) and prints the table; --check TOL exits 1
unless every output time is within TOL (a fraction) of the closed form, relative to the largest displacement. The
--case shear runs the simple-shear case (b) instead: τ = σ0 on the four edges, γ_xy of the mid row and column
against τ J(t) (no PNG); --case hot_shear the same at a uniform 200 °C (§8.2: σ0 = 1 MPa, J with the WLF-shifted
relaxation times), and the mid row's thermal strain against α ΔT. The second form runs the convergence study of the paper's Figs 6–7 (m = δ/Δx = 1, 2, 3 at δ = 15 mm; Δx = 5, 2.5 mm at
m = 3) and writes DIR/convergence.png and the table (about 20 minutes on 2 cores)."""
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
SIGMA, RELEASE, L, W = 2000.0, 0.005, 0.3, 0.15
# §8.2: the shear case at a uniform 200 °C, σ0 = 1 MPa, WLF with the paper's eq 44 (c1 = 30, c2 = 100 K, T0 = 110 °C),
# α = 50e-6 /K from the reference temperature (20 °C: the paper does not give one).
HOT_SIGMA, HOT_T, REFERENCE_T, WLF_C1, WLF_C2, WLF_T0, ALPHA = 1e6, 473.15, 293.15, 30.0, 100.0, 383.15, 50e-6
HOT_SUBSTEPS = 8


def wlf_shift(case):
    """a_T of the case: τ_k → a_T τ_k (1 at the WLF reference temperature)."""
    if case != "hot_shear":
        return 1.0
    above = HOT_T - WLF_T0
    return 10 ** (-WLF_C1 * above / (WLF_C2 + above))
E_TERMS = [200, 800, 1500, 1000, 1100, 2700, 2900, 2500, 900, 950, 600, 120, 180, 200, 250]  # MPa, Table 1
TAUS = [1e-4, 1e-3, 1e-2, 1, 10, 100, 1e3, 1e4, 1e5, 1e6, 1e7, 1e8, 1e9, 1e11, 3e12]
E_INF, NU = 700.0, 0.3


def compliance(case="tension"):
    """The deck's solid: D(t) = 1/(4κ) + J(t)/4 (1/Pa), the uniaxial-stress creep compliance (tension), or J(t), the
    shear creep compliance (γ_xy = τ J for a held shear stress τ: shear)."""
    mu_inf = E_INF * 1e6 / (2 * (1 + NU))
    mu = np.array(E_TERMS) * 1e6 / (2 * (1 + NU))
    mu0 = mu_inf + mu.sum()
    K = (E_INF + sum(E_TERMS)) * 1e6 / (3 * (1 - 2 * NU))
    kappa = 9 * K * mu0 / (3 * K + 4 * mu0)
    J = prony.creep_compliance(mu_inf, mu, wlf_shift(case) * np.array(TAUS))

    def D(t):
        return 1 / (4 * kappa) + J(t) / 4 if case == "tension" else J(t)

    return D


def deck_text(spacing, horizon):
    """deck.yaml with Δx and δ replaced (m), its node sets and probe moved to the rows of that lattice."""
    with open(os.path.join(HERE, "deck.yaml")) as f:
        text = f.read()
    half = spacing / 2
    replace = [
        (r"spacing: 5 mm", f"spacing: {spacing!r}"),
        (r"horizon: 15 mm", f"horizon: {horizon!r}"),
        (r"left: \{shape: \{box: \{min: \[-1, -1\], max: \[0.005, 1\]\}\}\}",
         f"left: {{shape: {{box: {{min: [-1, -1], max: [{spacing!r}, 1]}}}}}}"),
        (r"right: \{shape: \{box: \{min: \[0.295, -1\], max: \[1, 1\]\}\}\}",
         f"right: {{shape: {{box: {{min: [{L - spacing!r}, -1], max: [1, 1]}}}}}}"),
        (r"pin: \{shape: \{box: \{min: \[-1, 0.0725\], max: \[0.005, 0.0775\]\}\}\}",
         f"pin: {{shape: {{box: {{min: [-1, {W / 2 - half!r}], max: [{spacing!r}, {W / 2 + half!r}]}}}}}}"),
        (r"point: \[0.3, 0.0751\]", f"point: [{L - half!r}, {W / 2 + 1e-6!r}]"),
    ]
    for pattern, new in replace:
        text, count = re.subn(pattern, new, text)
        assert count == 1, pattern
    return text


def shear_deck_text(spacing, horizon, hot=False):
    """The simple-shear case (b): the shear traction τ = σ0 on all four edges (right +y, left −y, top +x, bottom −x,
    each carried by its outer row), released at 5 ms; one point near the centre held, a second one of its row held
    in y (the loads have no moment: this only fixes the rigid motion). Probes on the mid row and the mid column."""
    text = deck_text(spacing, horizon)
    half = spacing / 2
    sigma = HOT_SIGMA if hot else SIGMA
    start, end = text.index("node_sets:"), text.index("solver:")
    loads = f"""node_sets:
  left: {{shape: {{box: {{min: [-1, -1], max: [{spacing!r}, 1]}}}}}}
  right: {{shape: {{box: {{min: [{L - spacing!r}, -1], max: [1, 1]}}}}}}
  bottom: {{shape: {{box: {{min: [-1, -1], max: [1, {spacing!r}]}}}}}}
  top: {{shape: {{box: {{min: [-1, {W - spacing!r}], max: [1, 1]}}}}}}
  centre: {{shape: {{box: {{min: [{L / 2 - spacing!r}, {W / 2 - spacing!r}], max: [{L / 2 - 1e-9!r}, {W / 2 - 1e-9!r}]}}}}}}
  aside: {{shape: {{box: {{min: [{0.75 * L - spacing!r}, {W / 2 - spacing!r}], max: [{0.75 * L - 1e-9!r}, {W / 2 - 1e-9!r}]}}}}}}
boundary_conditions:
  - {{node_set: centre, displacement: {{x: "0", y: "0"}}}}
  - {{node_set: aside, displacement: {{y: "0"}}}}
tractions:
  - {{node_set: right, y: "{sigma!r} * (t < 0.00495)"}}
  - {{node_set: left, y: "{-sigma!r} * (t < 0.00495)"}}
  - {{node_set: top, x: "{sigma!r} * (t < 0.00495)"}}
  - {{node_set: bottom, x: "{-sigma!r} * (t < 0.00495)"}}
"""
    if hot:  # §8.2: the uniform temperature, its thermal strain and the WLF shift
        loads += f"temperature: {{value: \"{HOT_T!r}\", reference: {REFERENCE_T!r}}}\n"
        text = text.replace("    prony_series:", f"    thermal_expansion: {ALPHA!r}\n"
                            f"    wlf: {{c1: {WLF_C1!r}, c2: {WLF_C2!r}, reference_temperature: {WLF_T0!r}}}\n    prony_series:")
        # Shifted, 13 of the 15 relaxation times are below 10 µs, far inside the first step after each load jump:
        # 8 substeps, each twice the one before (the first 0.4 µs), follow them there.
        text = text.replace("  load_history: steps", f"  creep_substeps: {HOT_SUBSTEPS}\n  load_history: steps")
        start, end = text.index("node_sets:"), text.index("solver:")
    text = text[:start] + loads + text[end:]
    probes = f"""    probes:
      - {{name: uy_right, point: [{L - half!r}, {W / 2 - half!r}], field: displacement_y}}
      - {{name: uy_left, point: [{half!r}, {W / 2 - half!r}], field: displacement_y}}
      - {{name: ux_top, point: [{L / 2 - half!r}, {W - half!r}], field: displacement_x}}
      - {{name: ux_bottom, point: [{L / 2 - half!r}, {half!r}], field: displacement_x}}
      - {{name: ux_right, point: [{L - half!r}, {W / 2 - half!r}], field: displacement_x}}
      - {{name: ux_left, point: [{half!r}, {W / 2 - half!r}], field: displacement_x}}
"""
    return text[:text.index("    probes:")] + probes


def run(peridot, out, threads, spacing, horizon, case="tension", solver="relaxation"):
    """Runs the plate; returns the output times, the measured quantity and its closed form: u_x at (L, W/2)
    (tension), or the engineering shear strain γ_xy of the mid row and column, from probe differences (shear)."""
    os.makedirs(out, exist_ok=True)
    deck = os.path.join(out, "deck.yaml")
    with open(deck, "w") as f:
        text = deck_text(spacing, horizon) if case == "tension" else shear_deck_text(spacing, horizon, case == "hot_shear")
        f.write(text.replace("  type: relaxation\n", f"  type: {solver}\n"))
    subprocess.run([peridot, "run", "-q", "-t", str(threads), "-o", out, deck], check=True)
    with open(os.path.join(out, "history.csv")) as f:
        rows = list(csv.DictReader(f))
    t = np.array([float(r["time"]) for r in rows])
    D = compliance(case)
    sigma = HOT_SIGMA if case == "hot_shear" else SIGMA
    if case != "tension":
        column = lambda name: np.array([float(r[name]) for r in rows])
        span = L - spacing  # between the probe points, along the row and (W − Δx) along the column
        u = (column("uy_right") - column("uy_left")) / span + (column("ux_top") - column("ux_bottom")) / (W - spacing)
        length = 1.0
    else:
        u = np.array([float(r["ux_end"]) for r in rows])
        length = (L - spacing / 2) - spacing / 2  # probe row minus the rollers' row
    exact = np.array([sigma * (D(s) - (D(s - RELEASE) if s >= RELEASE - 1e-12 else 0.0)) * length for s in t])
    if case == "hot_shear":  # the free thermal strain α ΔT along the mid row
        stretch = (np.array([float(r["ux_right"]) for r in rows]) - np.array([float(r["ux_left"]) for r in rows])) / (L - spacing)
        print(f"thermal strain of the mid row: {stretch[-1]:.6e} (α ΔT = {ALPHA * (HOT_T - REFERENCE_T):.6e}, "
              f"difference {100 * (stretch[-1] / (ALPHA * (HOT_T - REFERENCE_T)) - 1):.3f} %)")
    return t, u, exact


def plot(path, curves, title):
    try:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
    except ImportError:
        return
    D = compliance()
    fig, ax = plt.subplots(figsize=(6, 4))
    t_max = max(t.max() for _, t, _, _ in curves)
    fine = np.linspace(0, t_max, 400)
    length = curves[0][3]
    ax.plot(1e3 * fine, [SIGMA * (D(s) - (D(s - RELEASE) if s >= RELEASE else 0.0)) * length * 1e6 for s in fine],
            "k-", label="closed form (same solid)")
    for label, t, u, _ in curves:
        ax.plot(1e3 * t, 1e6 * u, "o", ms=3, label=label)
    ax.set_xlabel("t (ms)")
    ax.set_ylabel("u_x at (L, W/2) (µm)")
    ax.set_title(title)
    ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(path, dpi=120)


def main():
    p = argparse.ArgumentParser()
    p.add_argument("--peridot", required=True)
    p.add_argument("--out", default=os.path.join(HERE, "out"))
    p.add_argument("--threads", type=int, default=2)
    p.add_argument("--spacing", type=float, default=5.0, help="Δx (mm)")
    p.add_argument("--horizon", type=float, default=15.0, help="δ (mm)")
    p.add_argument("--check", type=float, default=None, help="largest allowed difference (fraction of the largest u)")
    p.add_argument("--convergence", action="store_true")
    p.add_argument("--case", choices=["tension", "shear", "hot_shear"], default="tension")
    p.add_argument("--solver", choices=["relaxation", "implicit"], default="relaxation",
                   help="the static solver of each load step (implicit: Newton–Krylov, for the fine lattices)")
    a = p.parse_args()
    if a.convergence:
        cases = [(15.0, 15.0), (7.5, 15.0), (5.0, 15.0), (2.5, 7.5)]  # (Δx, δ) mm: m = 1, 2, 3; then Δx/2 at m = 3
        print(f"{'dx (mm)':>8} {'delta (mm)':>10} {'m':>3} {'largest difference / max u':>28}")
        curves = []
        for dx, delta in cases:
            t, u, exact = run(a.peridot, os.path.join(a.out, f"dx{dx:g}_delta{delta:g}"), a.threads, 1e-3 * dx, 1e-3 * delta)
            worst = np.abs(u - exact).max() / np.abs(exact).max()
            print(f"{dx:8.2f} {delta:10.2f} {delta / dx:3.0f} {100 * worst:27.2f}%", flush=True)
            curves.append((f"Δx = {dx:g} mm, δ = {delta:g} mm", t, u, (L - 1e-3 * dx)))
        plot(os.path.join(a.out, "convergence.png"), curves, "Convergence in m = δ/Δx and in Δx")
        return
    t, u, exact = run(a.peridot, a.out, a.threads, 1e-3 * a.spacing, 1e-3 * a.horizon, a.case, a.solver)
    scale = np.abs(exact).max()
    error = (u - exact) / scale
    quantity = "u_x (m)" if a.case == "tension" else "gamma_xy"
    print(f"{'t (ms)':>8} {quantity + ' Peridot':>18} {'closed form':>16} {'error / max':>12}")
    for s, mine, ref, e in zip(t, u, exact, error):
        print(f"{1e3 * s:8.2f} {mine:18.6e} {ref:16.6e} {e:12.3e}")
    worst = np.abs(error).max()
    print(f"largest difference: {100 * worst:.2f} % of the largest closed-form value")
    if a.case == "tension":
        plot(os.path.join(a.out, "creep.png"), [("Peridot thermoviscoelastic", t, u, L - 1e-3 * a.spacing)],
             "Creep and recovery, σ0 = 2 kPa released at 5 ms")
    if a.check is not None and worst > a.check:
        print(f"FAIL: more than {100 * a.check:g} % from the closed form")
        sys.exit(1)


if __name__ == "__main__":
    main()
