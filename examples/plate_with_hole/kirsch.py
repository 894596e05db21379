#!/usr/bin/python3
"""Plate with a hole against Kirsch: runs deck.yaml (a square of side 8a whose outer frame, one horizon deep,
is given Kirsch's infinite-plate displacement) at a/Δx = 4, 8, 16, 32, 48 with δ = 3.015Δx, computes the hoop
stress σ_xx on the axis x = 0 above the hole from the relaxed displacements, and compares it with Kirsch,
σ_θθ(r) = S(1 + a²/2r² + 3a⁴/2r⁴) on that axis (3S at the edge), S = 70 MPa the remote stress.

Stress from displacements (plane stress Hooke): σ_xx = E/(1 − ν²)(ε_xx + ν ε_yy), ε_xx by central differences
along x, ε_yy by differences along y (one-sided at the first row). Two edge values:
- the row nearest the hole (r = a + Δx/2) against Kirsch there: inside the hole surface's boundary layer,
  where the incomplete families of LPS (no surface correction) stiffen the surface;
- the outer solution, more than a horizon from the hole, fitted by the form every plane-elasticity
  solution for a circular hole has on this axis, c0 + c2 (a/r)² + c4 (a/r)⁴, and evaluated at r = a.

    kirsch.py --peridot PATH [--sizes 4,8,16,32,48] [--threads N] [--out DIR] [--reuse] [--check-short]

--check-short (ctest): a/Δx = 16 only; passes when the outer fit's edge value is within 5 % of 3S and the
outer points follow Kirsch within 4 %."""
import argparse
import os
import re
import subprocess
import sys

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
A, E, NU, HALF_SIDE, REMOTE = 5e-3, 70e9, 0.3, 0.02, 70e6


def kirsch(r):
    return 1 + 0.5 * (A / r) ** 2 + 1.5 * (A / r) ** 4


def deck_for(n):
    dx = A / n
    text = open(os.path.join(HERE, "deck.yaml")).read()
    text = re.sub(r"spacing: .*", f"spacing: {dx!r}", text)
    text = re.sub(r"lattice_origin: .*", f"lattice_origin: [{-dx / 2!r}, 0]", text)
    inner = HALF_SIDE - 3.015 * dx
    return text.replace("[-0.0181, -0.0181], max: [0.0181, 0.0181]", f"[{-inner!r}, {-inner!r}], max: [{inner!r}, {inner!r}]")


def read(path):
    import netCDF4
    d = netCDF4.Dataset(path)
    names = [str(n).strip() for n in netCDF4.chartostring(d.variables["name_nod_var"][:])]
    x, y = np.asarray(d.variables["coordx"][:]), np.asarray(d.variables["coordy"][:])
    ux = np.asarray(d.variables[f"vals_nod_var{names.index('displacement_x') + 1}"][-1])
    uy = np.asarray(d.variables[f"vals_nod_var{names.index('displacement_y') + 1}"][-1])
    return x, y, ux, uy


def axis_stress(n, out, peridot, threads, reuse=False):
    dx = A / n
    work = os.path.join(out, f"n{n}")
    os.makedirs(work, exist_ok=True)
    deck = os.path.join(work, "deck.yaml")
    if not (reuse and os.path.exists(os.path.join(work, "plate.e")) and open(deck).read() == deck_for(n)):
        open(deck, "w").write(deck_for(n))
        subprocess.run([peridot, "run", "-q", "-t", str(threads), "-o", work, deck], check=True)
    rows = list(open(os.path.join(work, "history.csv")))
    header, last = rows[0].strip().split(","), rows[-1].strip().split(",")
    iterations = int(float(last[header.index("iterations")]))
    sigma_inf = REMOTE
    x, y, ux, uy = read(os.path.join(work, "plate.e"))
    key = {(int(round(a / dx * 2)), int(round(b / dx * 2))): i for i, (a, b) in enumerate(zip(x, y))}
    rs, sigma = [], []
    for k in range(2 * n):  # rows above the hole on x = 0 up to r = 3a: y = a + (k + ½)Δx, keys in half-spacings
        yk = 2 * n + 2 * k + 1
        c, xl, xr, up, dn = key.get((0, yk)), key.get((-2, yk)), key.get((2, yk)), key.get((0, yk + 2)), key.get((0, yk - 2))
        exx = (ux[xr] - ux[xl]) / (2 * dx)
        eyy = (uy[up] - uy[dn]) / (2 * dx) if dn is not None else (uy[up] - uy[c]) / dx
        rs.append(A + (k + 0.5) * dx)
        sigma.append(E / (1 - NU ** 2) * (exx + NU * eyy) / sigma_inf)
    rs, sigma = np.array(rs), np.array(sigma)
    # The outer solution: beyond a horizon from the hole's surface (whose incomplete families make a boundary
    # layer) fitted by the form every plane-elasticity solution of a circular hole has on this axis,
    # c0 + c2 (a/r)² + c4 (a/r)⁴, and evaluated at r = a.
    outer = rs > A + 3.015 * dx
    basis = lambda r: np.stack([np.ones_like(r), (A / r) ** 2, (A / r) ** 4], axis=1)
    coefficients = np.linalg.lstsq(basis(rs[outer]), sigma[outer], rcond=None)[0]
    edge = float(basis(np.array([A])) @ coefficients)
    follow = float(np.max(np.abs(sigma[outer] / kirsch(rs[outer]) - 1)))
    return {"n": n, "dx": dx, "points": len(x), "iterations": iterations, "sigma_inf": sigma_inf, "r": rs,
            "ratio": sigma, "edge": edge, "outer_error": follow}


def main():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--peridot", required=True)
    p.add_argument("--sizes", default="4,8,16,32,48")
    p.add_argument("--out", default=os.path.join(HERE, "out"))
    p.add_argument("--threads", type=int, default=1)
    p.add_argument("--check-short", action="store_true")
    p.add_argument("--reuse", action="store_true", help="read the outputs of an earlier run in --out where its deck is the same")
    a = p.parse_args()
    sizes = [16] if a.check_short else [int(s) for s in a.sizes.split(",")]
    results = [axis_stress(n, a.out, a.peridot, a.threads, a.reuse) for n in sizes]
    print("| a/Δx | δ/a | points | ADR iterations | σ/S at r = a + Δx/2 | Kirsch there | error | "
          "outer points vs Kirsch, largest error | edge from the outer fit | error vs 3 |")
    print("|---|---|---|---|---|---|---|---|---|---|")
    for r in results:
        kirsch_first = kirsch(r["r"][0])
        print(f"| {r['n']} | {3.015 / r['n']:.3f} | {r['points']} | {r['iterations']} | "
              f"{r['ratio'][0]:.3f} | {kirsch_first:.3f} | {100 * (r['ratio'][0] / kirsch_first - 1):+.1f} % | "
              f"{100 * r['outer_error']:.2f} % | {r['edge']:.3f} | {100 * (r['edge'] / 3 - 1):+.2f} % |")
    if a.check_short:
        r = results[0]
        edge = abs(r["edge"] / 3 - 1) < 0.05
        outer = r["outer_error"] < 0.04
        print(("ok   " if edge else "FAIL ") + f"edge hoop stress from the outer solution {r['edge']:.3f} S within 5 % of 3S")
        print(("ok   " if outer else "FAIL ") + f"outer points within 4 % of Kirsch (largest {100 * r['outer_error']:.2f} %)")
        return 0 if edge and outer else 1
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, (left, right) = plt.subplots(1, 2, figsize=(11, 4.2))
    r = np.linspace(A, 3 * A, 200)
    left.plot(r / A, kirsch(r), "k-", label="Kirsch")
    for res in results:
        left.plot(res["r"] / A, res["ratio"], "o--", ms=4, label=f"Peridot LPS, a/Δx = {res['n']}")
    left.set_xlabel("r / a on the axis across the load")
    left.set_ylabel("σ_xx / S")
    left.set_xlim(1, 3)
    left.legend()
    left.grid(alpha=0.3)
    dxs = np.array([res["dx"] for res in results]) / A
    first = np.array([abs(res["ratio"][0] / kirsch(res["r"][0]) - 1) for res in results])
    edge = np.array([max(abs(res["edge"] / 3 - 1), 1e-4) for res in results])
    right.loglog(dxs, 100 * first, "o-", label="row nearest the hole vs Kirsch at its r")
    right.loglog(dxs, 100 * edge, "s--", label="outer solution at r = a vs 3")
    right.set_xlabel("Δx / a (δ = 3.015Δx)")
    right.set_ylabel("relative error (%)")
    right.legend()
    right.grid(alpha=0.3, which="both")
    fig.suptitle("Plate with a hole, adaptive dynamic relaxation: hoop stress against Kirsch")
    fig.tight_layout()
    fig.savefig(os.path.join(HERE, "kirsch.png"), dpi=110)
    print("wrote", os.path.join(HERE, "kirsch.png"))
    return 0


if __name__ == "__main__":
    sys.exit(main())
