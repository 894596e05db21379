#!/usr/bin/python3
"""Plate with a hole against Kirsch: runs deck.yaml at a/Δx = 4, 6, 8, 12 (δ = 3.015Δx, the same plate),
computes the hoop stress σ_xx on the axis x = 0 above the hole from the relaxed displacements, and compares
its value at the hole edge with Kirsch's 3σ∞ (σ∞: the right grip's reaction over the plate's section).

Stress from displacements (plane stress Hooke): σ_xx = E/(1 − ν²)(ε_xx + ν ε_yy), ε_xx by central differences
along x, ε_yy by differences along y (one-sided at the first row). The first row of points lies Δx/2 from the
hole; the edge value is the quadratic extrapolation to r = a of the first three rows.

    kirsch.py --peridot PATH [--sizes 4,6,8,12] [--out DIR] [--check-short]

--check-short (ctest): a/Δx = 4 only; passes when the edge value is within 8 % of 3σ∞ and the point values
follow Kirsch's σ_θθ(r) = σ∞(1 + a²/2r² + 3a⁴/2r⁴) within 8 % over the first three rows."""
import argparse
import os
import re
import subprocess
import sys

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
A, E, NU, WIDTH, THICKNESS = 5e-3, 70e9, 0.3, 0.1, 1e-3


def kirsch(r):
    return 1 + 0.5 * (A / r) ** 2 + 1.5 * (A / r) ** 4


def deck_for(n):
    dx = A / n
    text = open(os.path.join(HERE, "deck.yaml")).read()
    text = re.sub(r"spacing: .*", f"spacing: {dx!r}", text)
    text = re.sub(r"lattice_origin: .*", f"lattice_origin: [{-dx / 2!r}, 0]", text)
    grip = WIDTH / 2 - 3 * dx
    text = text.replace("-0.048", repr(-grip)).replace("0.048", repr(grip))
    return text


def read(path):
    import netCDF4
    d = netCDF4.Dataset(path)
    names = [str(n).strip() for n in netCDF4.chartostring(d.variables["name_nod_var"][:])]
    x, y = np.asarray(d.variables["coordx"][:]), np.asarray(d.variables["coordy"][:])
    ux = np.asarray(d.variables[f"vals_nod_var{names.index('displacement_x') + 1}"][-1])
    uy = np.asarray(d.variables[f"vals_nod_var{names.index('displacement_y') + 1}"][-1])
    return x, y, ux, uy


def axis_stress(n, out, peridot, threads):
    dx = A / n
    work = os.path.join(out, f"n{n}")
    os.makedirs(work, exist_ok=True)
    deck = os.path.join(work, "deck.yaml")
    open(deck, "w").write(deck_for(n))
    subprocess.run([peridot, "run", "-q", "-t", str(threads), "-o", work, deck], check=True)
    rows = list(open(os.path.join(work, "history.csv")))
    header, last = rows[0].strip().split(","), rows[-1].strip().split(",")
    reaction = float(last[header.index("reaction_right_x")])
    iterations = int(float(last[header.index("iterations")]))
    sigma_inf = reaction / (WIDTH * THICKNESS)
    x, y, ux, uy = read(os.path.join(work, "plate.e"))
    key = {(int(round(a / dx * 2)), int(round(b / dx * 2))): i for i, (a, b) in enumerate(zip(x, y))}
    rs, sigma = [], []
    for k in range(8):  # rows above the hole on x = 0: y = a + (k + ½)Δx, keys in half-spacings
        yk = 2 * n + 2 * k + 1
        c, xl, xr, up, dn = key.get((0, yk)), key.get((-2, yk)), key.get((2, yk)), key.get((0, yk + 2)), key.get((0, yk - 2))
        exx = (ux[xr] - ux[xl]) / (2 * dx)
        eyy = (uy[up] - uy[dn]) / (2 * dx) if dn is not None else (uy[up] - uy[c]) / dx
        rs.append(A + (k + 0.5) * dx)
        sigma.append(E / (1 - NU ** 2) * (exx + NU * eyy) / sigma_inf)
    rs, sigma = np.array(rs), np.array(sigma)
    edge = np.polyval(np.polyfit(rs[:3] - A, sigma[:3], 2), 0.0)
    return {"n": n, "dx": dx, "points": len(x), "iterations": iterations, "sigma_inf": sigma_inf, "r": rs,
            "ratio": sigma, "edge": edge}


def main():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--peridot", required=True)
    p.add_argument("--sizes", default="4,6,8,12")
    p.add_argument("--out", default=os.path.join(HERE, "out"))
    p.add_argument("--threads", type=int, default=1)
    p.add_argument("--check-short", action="store_true")
    a = p.parse_args()
    sizes = [4] if a.check_short else [int(s) for s in a.sizes.split(",")]
    results = [axis_stress(n, a.out, a.peridot, a.threads) for n in sizes]
    print("| a/Δx | Δx (mm) | points | ADR iterations | σ∞ (MPa) | σ_xx/σ∞ first row (Kirsch there) | edge, extrapolated | error vs 3 |")
    print("|---|---|---|---|---|---|---|---|")
    for r in results:
        print(f"| {r['n']} | {r['dx'] * 1e3:.4g} | {r['points']} | {r['iterations']} | {r['sigma_inf'] / 1e6:.2f} | "
              f"{r['ratio'][0]:.3f} ({kirsch(r['r'][0]):.3f}) | {r['edge']:.3f} | {100 * (r['edge'] / 3 - 1):+.1f} % |")
    if a.check_short:
        r = results[0]
        ok = abs(r["edge"] / 3 - 1) < 0.08
        follows = all(abs(s / kirsch(q) - 1) < 0.08 for s, q in zip(r["ratio"][:3], r["r"][:3]))
        print(("ok   " if ok else "FAIL ") + f"edge hoop stress {r['edge']:.3f} σ∞ within 8 % of 3σ∞")
        print(("ok   " if follows else "FAIL ") + "first three rows within 8 % of Kirsch's σ_θθ(r)")
        return 0 if ok and follows else 1
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, (left, right) = plt.subplots(1, 2, figsize=(11, 4.2))
    r = np.linspace(A, 3 * A, 200)
    left.plot(r / A, kirsch(r), "k-", label="Kirsch (infinite plate)")
    for res in results:
        left.plot(res["r"] / A, res["ratio"], "o--", ms=4, label=f"Peridot LPS, a/Δx = {res['n']}")
    left.set_xlabel("r / a on the axis across the load")
    left.set_ylabel("σ_xx / σ∞")
    left.set_xlim(1, 2.6)
    left.legend()
    left.grid(alpha=0.3)
    dxs = np.array([res["dx"] for res in results]) / A
    errors = np.array([abs(res["edge"] / 3 - 1) for res in results])
    right.loglog(dxs, 100 * errors, "o-")
    right.set_xlabel("Δx / a (δ = 3.015Δx)")
    right.set_ylabel("|σ_edge/σ∞ − 3| / 3 (%)")
    right.grid(alpha=0.3, which="both")
    fig.suptitle("Plate with a hole, adaptive dynamic relaxation: hoop stress against Kirsch")
    fig.tight_layout()
    fig.savefig(os.path.join(HERE, "kirsch.png"), dpi=110)
    print("wrote", os.path.join(HERE, "kirsch.png"))
    return 0


if __name__ == "__main__":
    sys.exit(main())
