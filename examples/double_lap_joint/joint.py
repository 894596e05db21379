#!/usr/bin/python3
"""Runs the double-lap joint (deck.yaml) and draws where and when its adhesive fails.

    joint.py --peridot PATH [--out DIR] [--threads N] [--spacing MM] [--breaking once_per_step|until_stable]
             [--end-time MS] [--check]

Runs deck.yaml (Δx = 0.25 mm, δ = 3Δx, or the given spacing: the deck's lengths and its one-horizon symmetry
layers are rescaled), then writes DIR/damage.png (the damage on the configuration deformed ×100 at four times,
as the paper's Fig. 13) and DIR/crack_length.png (the crack's length along the bond line against time), and
prints the table. A run that stops because its inner adherend has come loose under the load (Peridot names
the piece) is reported with the time it came apart, and the script draws what came before; any other failure,
a relaxation that ran out of iterations included, is an error.

The crack along the bond line: the adhesive's rows within one horizon above the lower bond line (y = c), in
the columns 0 < x < a, hold a crack where their largest damage is at least CRACK_DAMAGE (a row of points beside
a crack loses about a third of its bonds; an intact row none). Two lengths are reported: the run of cracked
columns that starts at the strap's end (x = a), and the cracked columns over the whole overlap.

--check exits 1 unless damage nucleates within one horizon of a lower corner of the adhesive, a crack opens along
the lower bond line and never closes, and every damaged point stays within 2δ of that bond line."""
import argparse
import csv
import os
import re
import subprocess
import sys

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
A, C, H, T, B = 8e-3, 4e-3, 2e-3, 4e-3, 8e-3  # overlap, inner half-thickness, adhesive, strap, free length (m)
SPACING = 0.25e-3  # deck.yaml's Δx
CRACK_DAMAGE = 0.25


def deck_text(spacing, breaking, end_time):
    """deck.yaml with Δx (δ = 3Δx) replaced, its symmetry layers one horizon deep, the loaded column and
    the relaxation's breaking and end time replaced (load steps of 0.1 ms, as the paper)."""
    with open(os.path.join(HERE, "deck.yaml")) as f:
        text = f.read()
    horizon = 3 * spacing
    steps = int(round(end_time / 1e-4))
    replace = [
        (r"spacing: 0.25 mm", f"spacing: {spacing!r}"),
        (r"horizon: 0.75 mm", f"horizon: {horizon!r}"),
        (r"min: \[0, -0.00075\]", f"min: [0, {-horizon!r}]"),
        (r"min: \[-0.00075, 0.004\]", f"min: [{-horizon!r}, 0.004]"),
        (r"min: \[-0.00075, 0.006\]", f"min: [{-horizon!r}, 0.006]"),
        (r"min: \[0.01575, 0\]", f"min: [{A + B - spacing!r}, 0]"),
        (r"breaking: once_per_step", f"breaking: {breaking}"),
        (r"load_steps: 40", f"load_steps: {steps}"),
        (r"end_time: 4 ms", f"end_time: {end_time!r}"),
    ]
    for pattern, new in replace:
        text, count = re.subn(pattern, new, text)
        assert count == 1, pattern
    return text


def run(peridot, out, threads, spacing, breaking, end_time):
    """Runs the joint; returns the error line when the run stopped because the joint came apart."""
    os.makedirs(out, exist_ok=True)
    deck = os.path.join(out, "deck.yaml")
    with open(deck, "w") as f:
        f.write(deck_text(spacing, breaking, end_time))
    done = subprocess.run([peridot, "run", "-q", "-t", str(threads), "-o", out, deck], capture_output=True, text=True)
    if done.returncode == 0:
        return None
    message = done.stderr.strip().splitlines()[0] if done.stderr.strip() else ""
    if done.returncode == 3 and "has come apart" in message:
        return message
    sys.exit(f"peridot failed ({done.returncode}):\n{done.stderr}")


def read_frames(out):
    import netCDF4
    d = netCDF4.Dataset(os.path.join(out, "results.e"))
    names = [str(n).strip() for n in netCDF4.chartostring(d.variables["name_nod_var"][:])]
    field = lambda name: np.asarray(d.variables[f"vals_nod_var{names.index(name) + 1}"][:])
    x, y = np.asarray(d.variables["coordx"][:]), np.asarray(d.variables["coordy"][:])
    blocks = [str(n).strip() for n in netCDF4.chartostring(d.variables["eb_names"][:])]
    block = np.empty(len(x), dtype=object)
    for k, name in enumerate(blocks):
        block[np.asarray(d.variables[f"connect{k + 1}"][:]).ravel() - 1] = name
    return (np.asarray(d.variables["time_whole"][:]), x, y, block, field("damage"), field("displacement_x"),
            field("displacement_y"))


def crack_lengths(x, y, block, damage, spacing):
    """Per frame: the crack's length along the lower bond line from the strap's end, and over the whole overlap."""
    horizon = 3 * spacing
    band = (block == "adhesive") & (y > C) & (y < C + horizon) & (x > 0) & (x < A)
    columns = np.round((x[band] - spacing / 2) / spacing).astype(int)
    count = int(round(A / spacing))
    from_end, total = [], []
    for phi in damage:
        worst = np.zeros(count)
        np.maximum.at(worst, columns, phi[band])
        cracked = worst >= CRACK_DAMAGE
        run_length = 0
        for k in range(count - 1, -1, -1):
            if not cracked[k]:
                break
            run_length += 1
        from_end.append(run_length * spacing)
        total.append(cracked.sum() * spacing)
    return np.array(from_end), np.array(total)


def check(t, x, y, block, damage, total, spacing):
    horizon = 3 * spacing
    ok = True
    first = next((k for k, phi in enumerate(damage) if phi.max() > 0), None)
    if first is None:
        print("FAIL no damage at all")
        return False
    where = np.where(damage[first] > 0)[0]
    corners = np.array([[0.0, C], [A, C]])
    near = min(np.min(np.hypot(x[where] - cx, y[where] - cy)) for cx, cy in corners)
    good = near <= horizon
    print(("ok   " if good else "FAIL ") + f"damage nucleates at t = {t[first] * 1e3:.1f} ms, {near * 1e3:.2f} mm from a "
          f"lower corner of the adhesive (allowed: one horizon, {horizon * 1e3:.2f} mm)")
    ok &= good
    good = bool(np.all(np.diff(total) >= 0)) and total[-1] > 0
    print(("ok   " if good else "FAIL ") + f"a crack opens along the bond line and never closes: {total[-1] * 1e3:.2f} mm of "
          f"the overlap cracked at t = {t[-1] * 1e3:.1f} ms")
    ok &= good
    damaged = damage[-1] > 0
    height = float(np.max(np.abs(y[damaged] - C)))
    good = height <= 2 * horizon
    print(("ok   " if good else "FAIL ") + f"every damaged point lies within {height * 1e3:.2f} mm of the lower bond line "
          f"(allowed 2δ = {2 * horizon * 1e3:.2f} mm): the damage does not leave it")
    return ok and good


def plot(out, t, x, y, block, damage, ux, uy, from_end, total, separated_at):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    real = (x >= 0) & (y >= 0)  # the quarter itself, without its fictitious symmetry layers
    # The paper's Fig. 13 times, 1, 2, 3 and 4 ms; a shorter run, four frames up to its last (or up to the first
    # with the bond line cracked through).
    through = np.nonzero(from_end >= A - 1e-12)[0]
    last = int(through[0]) if len(through) else len(t) - 1
    paper = [int(np.argmin(np.abs(t - s))) for s in (1e-3, 2e-3, 3e-3, 4e-3)]
    if t[last] >= 4e-3 - 1e-9:
        picks = np.array(paper)
    else:
        picks = np.unique(np.linspace(0, last, 4).round().astype(int))
    fig, axes = plt.subplots(1, len(picks), figsize=(4.2 * len(picks), 3.6), constrained_layout=True)
    for ax, k in zip(np.atleast_1d(axes), picks):
        s = ax.scatter((x[real] + 100 * ux[k][real]) * 1e3, (y[real] + 100 * uy[k][real]) * 1e3, c=damage[k][real],
                       s=4, cmap="jet", vmin=0, vmax=0.5, linewidths=0)
        ax.set_aspect("equal")
        ax.set_title(f"t = {t[k] * 1e3:.1f} ms")
        ax.set_xlabel("x (mm)")
    np.atleast_1d(axes)[0].set_ylabel("y (mm), displacements ×100")
    fig.colorbar(s, ax=axes, label="damage", shrink=0.8)
    fig.savefig(os.path.join(out, "damage.png"), dpi=110)
    plt.close(fig)

    fig, ax = plt.subplots(figsize=(6, 4))
    ax.plot(t * 1e3, from_end * 1e3, "o-", label="from the strap's end (x = a)")
    ax.plot(t * 1e3, total * 1e3, "s--", label="all cracked columns of the overlap")
    if separated_at is not None:
        ax.axvline(separated_at * 1e3, color="k", lw=0.8)
        ax.text(separated_at * 1e3, 0.5 * A * 1e3, " joint apart", va="center")
    ax.axhline(A * 1e3, color="gray", lw=0.8, ls=":")
    ax.set_xlabel("t (ms)")
    ax.set_ylabel("crack length along the bond line (mm)")
    ax.set_ylim(0, A * 1e3 * 1.05)
    ax.grid(alpha=0.3)
    ax.legend()
    fig.tight_layout()
    fig.savefig(os.path.join(out, "crack_length.png"), dpi=110)
    plt.close(fig)


def main():
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--peridot", required=True)
    p.add_argument("--out", default=os.path.join(HERE, "out"))
    p.add_argument("--threads", type=int, default=2)
    p.add_argument("--spacing", type=float, default=SPACING * 1e3, help="Δx (mm)")
    p.add_argument("--breaking", default="once_per_step", choices=["once_per_step", "until_stable"])
    p.add_argument("--end-time", type=float, default=4.0, help="ms")
    p.add_argument("--check", action="store_true")
    a = p.parse_args()
    spacing = a.spacing * 1e-3
    failure = run(a.peridot, a.out, a.threads, spacing, a.breaking, a.end_time * 1e-3)
    t, x, y, block, damage, ux, uy = read_frames(a.out)
    separated_at = None
    if failure and len(t) == 0:
        print(f"the joint came apart in its first equilibrium (t = 0), nothing to draw:\n  {failure}")
        sys.exit(1 if a.check else 0)
    if failure:
        separated_at = t[-1] + 1e-4
        print(f"the joint came apart after t = {t[-1] * 1e3:.1f} ms:\n  {failure}")
    from_end, total = crack_lengths(x, y, block, damage, spacing)
    with open(os.path.join(a.out, "history.csv")) as f:
        rows = list(csv.DictReader(f))
    print("| t (ms) | bonds broken | crack from the strap's end (mm) | cracked overlap (mm) | iterations |")
    print("|---|---|---|---|---|")
    for k, r in enumerate(rows[:len(t)]):
        print(f"| {t[k] * 1e3:.1f} | {r['bonds_broken']} | {from_end[k] * 1e3:.2f} | {total[k] * 1e3:.2f} | {r['iterations']} |")
    plot(a.out, t, x, y, block, damage, ux, uy, from_end, total, separated_at)
    if a.check and not check(t, x, y, block, damage, total, spacing):
        sys.exit(1)


if __name__ == "__main__":
    main()
