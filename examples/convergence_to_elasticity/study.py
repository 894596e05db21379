#!/usr/bin/python3
"""Convergence of peridynamics to classical elasticity (issue: implicit solver, must-show 3).

A manufactured smooth displacement field u on the unit square (2D, plane stress) or cube (3D), an LPS body with
the classical body force b = −(μ∇²u + (λ + μ)∇(∇·u)) of that field, and u itself prescribed on a layer of
thickness 2δ outside the body (the nonlocal volume constraint: a state-based force at a point reads the
dilatation of neighbours whose own families reach another δ). Solved by the implicit solver for a sequence of
horizons δ at fixed δ/Δx = 3.015; the error of the peridynamic solution against u over the body is reported in
the max norm and the root mean square, relative to max |u|, for both bond quadratures:

  one_point   the neighbour's volume (Peridot's default, as LAMMPS and Peridigm);
  isotropic   times the direction weight that makes the lattice family's fourth moment isotropic
              (discretization.quadrature: isotropic, docs/algorithms.md §19).

The field, with k = π and A = 1e-6 (a rotational part, divergence-free, and a gradient part):
  2D: u = A (sin ky, sin kx) + A (cos kx sin ky, sin kx cos ky),  b = A μk² (…) + 2A k²(λ′ + 2μ)(…)
  3D: u = A (sin ky sin kz, sin kz sin kx, sin kx sin ky) + A ∇(sin kx sin ky sin kz)/k,
      b = 2A μk² (…) + 3A k²(λ + 2μ)(…)
(λ′ = Eν/(1 − ν²) in plane stress). Writes convergence.png and prints a table; --short (ctest): 2D, three
horizons, and checks the orders: at least 1.8 with the isotropic quadrature, and the one-point quadrature's
error stalling (order below 1) as the lattice anisotropy takes over.

  /usr/bin/python3 study.py --peridot PATH            # 2D and 3D, about two minutes on 2 cores
  /usr/bin/python3 study.py --peridot PATH --short    # ctest
"""
import argparse
import math
import os
import subprocess
import sys

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
A = 1e-6
K_WAVE = math.pi
E, NU = 1e9, 0.25
FACTOR = 3.015  # δ/Δx
LAYER = 2       # constraint layer thickness in horizons


def field_terms(dim):
    """(rotational part, gradient part, their body-force factors) as muParser expressions of x, y, z."""
    k = K_WAVE
    mu = E / (2 * (1 + NU))
    if dim == 2:
        lam = E * NU / (1 - NU * NU)  # plane stress λ′
        rot = [f"sin({k}*y)", f"sin({k}*x)"]
        grad = [f"cos({k}*x)*sin({k}*y)", f"sin({k}*x)*cos({k}*y)"]
        return rot, grad, mu * k * k, 2 * k * k * (lam + 2 * mu)
    lam = E * NU / ((1 + NU) * (1 - 2 * NU))
    rot = [f"sin({k}*y)*sin({k}*z)", f"sin({k}*z)*sin({k}*x)", f"sin({k}*x)*sin({k}*y)"]
    grad = [f"cos({k}*x)*sin({k}*y)*sin({k}*z)", f"sin({k}*x)*cos({k}*y)*sin({k}*z)",
            f"sin({k}*x)*sin({k}*y)*cos({k}*z)"]
    return rot, grad, 2 * mu * k * k, 3 * k * k * (lam + 2 * mu)


def exact(dim, X):
    s, c, k = np.sin, np.cos, K_WAVE
    x, y = X[0], X[1]
    if dim == 2:
        return A * np.array([s(k * y) + c(k * x) * s(k * y), s(k * x) + s(k * x) * c(k * y)])
    z = X[2]
    return A * np.array([s(k * y) * s(k * z) + c(k * x) * s(k * y) * s(k * z),
                         s(k * z) * s(k * x) + s(k * x) * c(k * y) * s(k * z),
                         s(k * x) * s(k * y) + s(k * x) * s(k * y) * c(k * z)])


def deck(dim, n, quadrature, directory):
    dx = 1.0 / n
    delta = FACTOR * dx
    rot, grad, c_rot, c_grad = field_terms(dim)
    axes = "xyz"[:dim]
    u = {a: f"{A}*({r}) + {A}*({g})" for a, r, g in zip(axes, rot, grad)}
    b = {a: f"{A * c_rot!r}*({r}) + {A * c_grad!r}*({g})" for a, r, g in zip(axes, rot, grad)}
    inner_hi = [1.0] * dim + [0.0] * (3 - dim)
    v = lambda p: "[" + ", ".join(repr(float(t)) for t in p) + "]"
    plane = "\n  plane: stress" if dim == 2 else ""
    return f"""# Manufactured solution, {dim}D, {n} cells across the unit {'square' if dim == 2 else 'cube'}, quadrature {quadrature}
# (examples/convergence_to_elasticity/study.py writes it). The body is the unit {'square' if dim == 2 else 'cube'} and a layer
# of {LAYER:g}δ around it; the layer carries u (the volume constraint), the unit {'square' if dim == 2 else 'cube'} the body force.
discretization:
  dimension: {dim}
  spacing: {dx!r}
  horizon_factor: {FACTOR}{plane}
  quadrature: {quadrature}
materials:
  solid: {{model: lps, density: 1000, youngs_modulus: {E}, poisson_ratio: {NU}}}
bodies:
  body: {{material: solid, volume_constraint: {LAYER * delta!r}, shape: {{box: {{min: {v([0, 0, 0])}, max: {v(inner_hi)}}}}}}}
boundary_conditions:
  - node_set: body_constraint
    displacement: {{{", ".join(f'{a}: "{u[a]}"' for a in axes)}}}
body_forces:
  - {{{", ".join(f'{a}: "{b[a]}"' for a in axes)}}}
solver: {{type: implicit, load_steps: 1, ramp: false, tolerance: 1e-10}}
output:
  directory: {directory}
  progress: false
  exodus: {{every: 1, file: u.e}}
"""


def error(path, dim):
    import netCDF4
    with netCDF4.Dataset(path) as d:
        names = ["".join(ch.decode() for ch in row if ch) for row in d.variables["name_nod_var"][:]]
        X = np.array([d.variables["coord" + a][:] for a in "xyz"[:dim]])
        U = np.array([d.variables["vals_nod_var%d" % (names.index("displacement_" + a) + 1)][-1]
                      for a in "xyz"[:dim]])
    inside = np.all((X > 0) & (X < 1), axis=0)
    ue = exact(dim, X)
    e = np.linalg.norm(U - ue, axis=0)[inside]
    scale = np.max(np.linalg.norm(ue[:, inside], axis=0))
    return e.max() / scale, math.sqrt(np.mean(e ** 2)) / scale, int(inside.sum()), X.shape[1]


def run(peridot, dim, n, quadrature, out):
    directory = os.path.join(out, f"{dim}d_{quadrature}_{n}")
    os.makedirs(directory, exist_ok=True)
    path = os.path.join(directory, "deck.yaml")
    with open(path, "w") as f:
        f.write(deck(dim, n, quadrature, directory))
    done = subprocess.run([peridot, "run", "-q", path], capture_output=True, text=True)
    if done.returncode != 0:
        sys.exit(f"peridot failed on {path}:\n{done.stdout}{done.stderr}")
    return error(os.path.join(directory, "u.e"), dim)


def orders(deltas, errors):
    return [math.log(errors[i - 1] / errors[i]) / math.log(deltas[i - 1] / deltas[i]) for i in range(1, len(errors))]


def main():
    global LAYER
    p = argparse.ArgumentParser()
    p.add_argument("--peridot", default="peridot")
    p.add_argument("--out", default=os.path.join(HERE, "out"))
    p.add_argument("--png", default=os.path.join(HERE, "convergence.png"))
    p.add_argument("--short", action="store_true")
    p.add_argument("--layer", type=float, default=LAYER, help="constraint layer thickness in horizons (default 2)")
    p.add_argument("--dimensions", default="2,3", help="which studies to run (not with --short)")
    args = p.parse_args()
    LAYER = args.layer
    full = {2: [10, 20, 40, 80, 160], 3: [8, 12, 16, 24, 32]}
    cases = {2: [10, 20, 40]} if args.short else {d: full[d] for d in map(int, args.dimensions.split(","))}
    results = {}
    for dim, resolutions in cases.items():
        for quadrature in ("one_point", "isotropic"):
            rows = []
            for n in resolutions:
                e_max, e_rms, interior, total = run(args.peridot, dim, n, quadrature, args.out)
                rows.append((FACTOR / n, e_max, e_rms, interior, total))
            results[(dim, quadrature)] = rows
    print("| dimension | quadrature | δ | points (interior) | max error | order | rms error | order |")
    print("|---|---|---|---|---|---|---|---|")
    for (dim, quadrature), rows in results.items():
        deltas = [r[0] for r in rows]
        o_max = [None] + orders(deltas, [r[1] for r in rows])
        o_rms = [None] + orders(deltas, [r[2] for r in rows])
        for r, om, orms in zip(rows, o_max, o_rms):
            fmt = lambda o: "" if o is None else f"{o:.2f}"
            print(f"| {dim}D | {quadrature} | {r[0]:.4f} | {r[4]} ({r[3]}) | {r[1]:.3e} | {fmt(om)} | {r[2]:.3e} | {fmt(orms)} |")
    plot(results, args.png)
    if args.short:
        iso = results[(2, "isotropic")]
        plain = results[(2, "one_point")]
        d = [r[0] for r in iso]
        failures = []
        for label, column in (("max", 1), ("rms", 2)):
            order = orders(d, [r[column] for r in iso])[-1]
            if order < 1.8:
                failures.append(f"isotropic quadrature: {label} error order {order:.2f} < 1.8")
        stalled = orders(d, [r[2] for r in plain])[-1]
        if stalled >= 1.0:
            failures.append(f"one-point quadrature: rms order {stalled:.2f}, expected the anisotropy to stall it below 1")
        if failures:
            sys.exit("\n".join(failures))
        print("orders as expected")


def plot(results, png):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    dims = sorted({d for d, _ in results})
    fig, axes = plt.subplots(1, len(dims), figsize=(5.5 * len(dims), 4.5), squeeze=False)
    for ax, dim in zip(axes[0], dims):
        for quadrature, colour in (("one_point", "tab:red"), ("isotropic", "tab:blue")):
            rows = results.get((dim, quadrature))
            if not rows:
                continue
            d = np.array([r[0] for r in rows])
            ax.loglog(d, [r[1] for r in rows], "o-", color=colour, label=f"{quadrature}: max")
            ax.loglog(d, [r[2] for r in rows], "s--", color=colour, label=f"{quadrature}: rms")
        rows = results[(dim, "isotropic")]
        d = np.array([r[0] for r in rows])
        ref = rows[0][2] * (d / d[0]) ** 2
        ax.loglog(d, ref, "k:", label="δ²")
        ax.set_xlabel("horizon δ (body size 1), δ/Δx = 3.015")
        ax.set_ylabel("error / max |u|")
        ax.set_title(f"{dim}D LPS, manufactured solution, {LAYER:g}δ volume constraint")
        ax.grid(True, which="both", alpha=0.3)
        ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(png, dpi=110)


if __name__ == "__main__":
    main()
