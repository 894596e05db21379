#!/usr/bin/python3
"""The implicit solver's assembled bond tangent against a finite-difference Jacobian (PETSc's -snes_test_jacobian,
which builds the whole Jacobian column by column from the residual): for pmb the tangent is exact (axial springs
c0 ω G V/ξ and the geometric stiffness of forces that turn with their bonds), so ||J − J_fd||_F/||J||_F sits at
the finite difference's error (measured 2.9e-6 with ω = 1, 3.3e-6 with ω = δ/ξ); for lps it is the pmb-like
preconditioner, not the tangent (measured 0.19: its dilatation couples every pair of a family). A small 3D bar
(12 × 5 × 5 points), held at one end and pulled and sheared at the other, one Newton solve with
`jacobian: bond_tangent`. Exits 1 if pmb's difference exceeds 1e-4 or lps's is below 1e-2."""
import argparse
import os
import re
import subprocess
import sys

DECK = """discretization: {{dimension: 3, spacing: 1 mm, horizon_factor: 3.015}}
materials:
  solid: {{model: {model}, density: 7800, youngs_modulus: 200 GPa{extra}}}
bodies:
  bar: {{material: solid, shape: {{box: {{min: [0, 0, 0], max: [0.012, 0.005, 0.005]}}}}}}
node_sets:
  left: {{shape: {{box: {{min: [-1, -1, -1], max: [0.003, 1, 1]}}}}}}
  right: {{shape: {{box: {{min: [0.009, -1, -1], max: [1, 1, 1]}}}}}}
boundary_conditions:
  - {{node_set: left, displacement: {{x: "0", y: "0", z: "0"}}}}
  - {{node_set: right, displacement: {{x: "2.4e-4", y: "1e-4", z: "0"}}}}
solver: {{type: implicit, load_steps: 1, tolerance: 1e-6, jacobian: bond_tangent, max_iterations: 200}}
output: {{directory: {out}, progress: false}}
"""

CASES = [  # (name, model, extra keys, bound, the difference must be below (True) or above (False) it)
    ("pmb", "pmb", "", 1e-4, True),
    ("pmb_inverse_distance", "pmb", ", influence: inverse_distance", 1e-4, True),
    ("lps", "lps", ", poisson_ratio: 0.3", 1e-2, False),
]


def main():
    p = argparse.ArgumentParser()
    p.add_argument("--peridot", required=True)
    p.add_argument("--source")
    p.add_argument("--work", default="/tmp/peridot_test_bond_tangent_jacobian")
    a = p.parse_args()
    os.makedirs(a.work, exist_ok=True)
    failures = []
    for name, model, extra, bound, below in CASES:
        deck = os.path.join(a.work, name + ".yaml")
        with open(deck, "w") as f:
            f.write(DECK.format(model=model, extra=extra, out=os.path.join(a.work, name)))
        env = dict(os.environ, PETSC_OPTIONS="-snes_test_jacobian", OMP_NUM_THREADS="1")
        r = subprocess.run([a.peridot, "run", deck], capture_output=True, text=True, env=env)
        found = re.findall(r"\|\|J - Jfd\|\|_F/\|\|J\|\|_F = ([0-9.eE+-]+)", r.stdout + r.stderr)
        if r.returncode != 0 or not found:
            failures.append(f"{name}: run failed or printed no comparison (exit {r.returncode})\n{r.stdout[-2000:]}{r.stderr[-2000:]}")
            continue
        first = float(found[0])  # at the first Newton iterate
        ok = first < bound if below else first > bound
        print(f"{name}: ||J - J_fd||_F / ||J||_F = {first:.3e} ({'below' if below else 'above'} {bound:g}: "
              f"{'ok' if ok else 'FAIL'})")
        if not ok:
            failures.append(f"{name}: {first:.3e}")
    if failures:
        print("\n".join(failures))
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
