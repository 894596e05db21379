#!/usr/bin/python3
"""The implicit solver (solver.type: implicit, Newton–Krylov through PETSc) against adaptive dynamic relaxation on
the static problems of the relaxation examples: the 3D LPS bar of bar.yaml, the plate with a hole
(examples/plate_with_hole) and the notched plate's load–displacement curve with its crack growing between
equilibria (examples/notched_plate). Each deck runs with both solvers at the same relative force tolerance; the
table gives the largest displacement difference over the largest displacement, the reactions, the broken bonds,
the iterations and the wall time, and implicit_solver.png shows each Newton iterate's relative residual (the
quadratic convergence) and both load–displacement curves. --short: the plate with a hole only (ctest)."""
import argparse
import csv
import os
import re
import subprocess
import sys
import time

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
EXAMPLES = os.path.dirname(HERE)
CASES = [  # (name, deck, reaction column or None, notes)
    ("bar", os.path.join(HERE, "bar.yaml"), "reaction_right_x", "3D lps, 8 640 points, ε = 1e-3"),
    ("plate_with_hole", os.path.join(EXAMPLES, "plate_with_hole", "deck.yaml"), None, "2D lps, 3 964 points, Kirsch frame"),
    ("notched_plate", os.path.join(EXAMPLES, "notched_plate", "deck.yaml"), "reaction_top_y",
     "2D lps, 1 891 points, 16 load steps, crack growing"),
]


def displacement(path):
    import netCDF4
    with netCDF4.Dataset(path) as d:
        names = [n.tobytes().decode().strip("\x00").strip() for n in d["name_nod_var"][:]]
        return np.array([d[f"vals_nod_var{names.index('displacement_' + c) + 1}"][-1]
                         for c in "xyz" if "displacement_" + c in names])


def run(peridot, deck, solver, out):
    """Runs the deck with this solver type (and the implicit one's iterations printed); returns wall time, the
    Newton residuals of each equilibrium and the history rows."""
    text = open(deck).read()
    replacement = f"  type: {solver}" + ("\n  print_iterations: true" if solver == "implicit" else "")
    text = re.sub(r"^  type: (relaxation|implicit)$", replacement, text, flags=re.M)
    os.makedirs(out, exist_ok=True)
    path = os.path.join(out, os.path.basename(deck))
    open(path, "w").write(text)
    start = time.perf_counter()
    r = subprocess.run([peridot, "run", "-o", out, path], capture_output=True, text=True,
                       env=dict(os.environ, OMP_NUM_THREADS=os.environ.get("OMP_NUM_THREADS", "2")))
    seconds = time.perf_counter() - start
    if r.returncode != 0:
        sys.exit(f"{solver} run of {deck} failed:\n{r.stdout}\n{r.stderr}")
    equilibria, current = [], []
    for line in r.stdout.splitlines():
        m = re.search(r"Newton iteration (\d+): relative residual ([0-9.e+-]+)", line)
        if m:
            if int(m.group(1)) == 0 and current:
                equilibria.append(current)
                current = []
            current.append(float(m.group(2)))
    if current:
        equilibria.append(current)
    rows = list(csv.DictReader(open(os.path.join(out, "history.csv"))))
    exodus = [f for f in os.listdir(out) if f.endswith(".e")][0]
    return seconds, equilibria, rows, os.path.join(out, exodus)


def main():
    p = argparse.ArgumentParser()
    p.add_argument("--peridot", default="peridot")
    p.add_argument("--out", default=os.path.join(HERE, "out"))
    p.add_argument("--short", action="store_true")
    p.add_argument("--png", default=os.path.join(HERE, "implicit_solver.png"))
    a = p.parse_args()
    cases = [c for c in CASES if c[0] == "plate_with_hole"] if a.short else CASES
    ok = True
    print("| problem | relaxation: iterations, s | implicit: Newton, Krylov iterations, s | max |Δu| / max |u| | "
          "reaction, relaxation → implicit | bonds broken |")
    print("|---|---|---|---|---|---|")
    results = {}
    for name, deck, reaction, notes in cases:
        r_s, _, r_rows, r_e = run(a.peridot, deck, "relaxation", os.path.join(a.out, name, "relaxation"))
        i_s, newton, i_rows, i_e = run(a.peridot, deck, "implicit", os.path.join(a.out, name, "implicit"))
        ur, ui = displacement(r_e), displacement(i_e)
        difference = np.abs(ur - ui).max() / np.abs(ur).max()
        total = lambda rows, column: sum(int(float(x[column])) for x in rows[1:])
        relax_iterations = total(r_rows, "iterations")
        newton_iterations, krylov = total(i_rows, "iterations"), total(i_rows, "linear_iterations")
        broken = [float(r.get("broken_fraction", "0")) for r in (r_rows[-1], i_rows[-1])]
        if reaction:
            fr, fi = float(r_rows[-1][reaction]), float(i_rows[-1][reaction])
            reaction_text = f"{fr:.6g} → {fi:.6g} N"
            reaction_ok = abs(fr - fi) <= 1e-5 * max(abs(float(x[reaction])) for x in r_rows)
        else:
            reaction_text, reaction_ok = "(frame)", True
        same_breaks = all(x.get("broken_fraction") == y.get("broken_fraction") for x, y in zip(r_rows, i_rows))
        # Both solvers stop at the deck's relative tolerance (1e-8 or 1e-6 here); the displacements then differ by
        # about that times the condition of the stiffness.
        tolerance = float(re.search(r"tolerance: ([0-9.e-]+)", open(deck).read()).group(1))
        agree = difference < 1e3 * tolerance and reaction_ok and same_breaks
        quadratic = all(len(e) < 3 or e[-1] < max(1e-12, 100 * e[-2] ** 2) for e in newton)
        ok &= agree and quadratic
        print(f"| {name} ({notes}) | {relax_iterations}, {r_s:.1f} | {newton_iterations}, {krylov}, {i_s:.1f} | "
              f"{difference:.1e} | {reaction_text} | {broken[0]:.5f} / {broken[1]:.5f} |", flush=True)
        print(("ok   " if agree else "FAIL ") + f"{name}: the same equilibria (displacements within {difference:.1e}, "
              f"reactions within 1e-5, the same bonds broken at every load step)", file=sys.stderr)
        print(("ok   " if quadratic else "FAIL ") + f"{name}: the last Newton step of every equilibrium at most "
              f"100 r² (or below 1e-12)", file=sys.stderr)
        results[name] = (newton, r_rows, i_rows, reaction)
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, axes = plt.subplots(1, 2, figsize=(11, 4.2))
    ax = axes[0]
    for name, (newton, _, _, _) in results.items():
        first = newton[0]
        ax.semilogy(range(len(first)), first, "o-", label=f"{name}, first equilibrium")
    ax.xaxis.get_major_locator().set_params(integer=True)
    ax.set_xlabel("Newton iteration")
    ax.set_ylabel("relative force residual")
    ax.set_title("Newton–Krylov: residual per iteration")
    ax.grid(True, which="both", alpha=0.3)
    ax.legend()
    ax = axes[1]
    if "notched_plate" in results:
        _, r_rows, i_rows, reaction = results["notched_plate"]
        opening = lambda rows: [2 * 8 * float(x["load_factor"]) for x in rows]  # µm, the grips' ±8 µm
        ax.plot(opening(r_rows), [float(x[reaction]) for x in r_rows], "s-", label="dynamic relaxation", ms=7, mfc="none")
        ax.plot(opening(i_rows), [float(x[reaction]) for x in i_rows], "x-", label="implicit (Newton–Krylov)")
        ax.set_xlabel("grip opening (µm)")
        ax.set_ylabel("load on the top grip (N)")
        ax.set_title("notched plate: load–displacement")
        ax.legend()
    else:
        ax.axis("off")
    fig.tight_layout()
    fig.savefig(a.png, dpi=110)
    print(f"wrote {a.png}", file=sys.stderr)
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main())
