#!/usr/bin/python3
"""Measure the crack angle of the Kalthoff-Winkler example from its final damage field.

For each notch tip it takes the damage averaged through the thickness (one value per x-y
lattice column), keeps the columns with damage > THRESHOLD that lie between R_MIN and R_MAX
from the tip and are not beside the notch faces (the pre-crack itself damages its neighbours),
fits a straight line through them (total least squares, through their centroid) and prints
the angle between that line, oriented away from the tip, and the notch direction (+x).
The experiment (Kalthoff & Winkler 1988) shows about 70 degrees, the cracks running away
from the impacted strip between the notches.

Run from this folder after the simulation:  /usr/bin/python3 measure_crack_angle.py [out/kalthoff.e [PNG]]
Writes crack_angle.png, or PNG (damage map, notches, selected crack points, fitted lines and angles).
Pre-crack bonds are removed before the run and do not count as damage, so the notches
themselves carry no damage; the band beside them is still excluded in case they do.
"""

import pathlib
import sys

import numpy as np

HERE = pathlib.Path(__file__).resolve().parent
sys.path.insert(0, str(HERE.parents[1] / "tools"))
import peridot_results as pr  # noqa: E402
import matplotlib.pyplot as plt  # noqa: E402

# Geometry of deck.yaml (metres): notches along +x from the impacted edge x = 0 to the tips.
TIPS = {"upper": (0.050, +0.025), "lower": (0.050, -0.025)}
HORIZON = 0.002
THRESHOLD = 0.35          # damage of a crack column (a fully cut column is ~0.5)
R_MIN = 2 * HORIZON       # skip the damage zone around the notch tip itself
R_MAX = 0.025             # fit over the first 25 mm of the crack
NOTCH_BAND = 1.5 * HORIZON  # beside a notch face (x < tip) closer than this: pre-crack damage


def column_average(coords, values, spacing):
    """Average a field over the thickness: one value per (x, y) lattice column."""
    key = np.floor(coords[:, :2] / spacing).astype(np.int64)  # lattice points sit at (i + 1/2)·spacing
    cols, inverse = np.unique(key, axis=0, return_inverse=True)
    inverse = inverse.ravel()
    count = np.bincount(inverse)
    mean = np.bincount(inverse, weights=values) / count
    xy = np.column_stack([np.bincount(inverse, weights=coords[:, k]) / count for k in (0, 1)])
    return xy, mean


def fit_crack(xy, dmg, tip):
    """Select the crack columns near ``tip`` and fit a line; returns (angle_deg, direction, selected mask)."""
    tx, ty = tip
    rel = xy - np.array(tip)
    r = np.hypot(rel[:, 0], rel[:, 1])
    beside_notch = (xy[:, 0] < tx) & (np.abs(xy[:, 1] - ty) < NOTCH_BAND)
    sel = (dmg > THRESHOLD) & (r >= R_MIN) & (r <= R_MAX) & ~beside_notch
    if sel.sum() < 5:
        return None, None, sel
    pts = rel[sel]
    centroid = pts.mean(axis=0)
    _, _, vt = np.linalg.svd(pts - centroid, full_matrices=False)
    direction = vt[0]
    if direction @ centroid < 0:  # orient away from the tip
        direction = -direction
    angle = np.degrees(np.arctan2(abs(direction[1]), direction[0]))
    return angle, direction, sel


def main(path, out):
    with pr.Results(path) as res:
        coords = res.coords
        damage = res.field("damage")
        t_end = res.times[-1]
        spacing = np.cbrt(np.median(res.field("volume", 0)))
        xy, dmg = column_average(coords, damage, spacing)

        ncols = [len(np.unique(np.floor(coords[:, k] / spacing))) for k in (0, 1)]
        fig, ax = plt.subplots(figsize=(6.5, 10))
        pr.plot_field(res, "damage", out=None, ax=ax, vmin=0, vmax=1, length_unit="mm", bins=ncols,
                      title=f"Kalthoff-Winkler: damage at t = {t_end * 1e6:.0f} µs\n"
                            "(mean through the thickness; white: notches, fitted lines; red: points fitted)")

    print(f"{path}: t = {t_end * 1e6:.1f} us, spacing {spacing * 1e3:.3f} mm, "
          f"max damage {damage.max():.3f}")
    results = {}
    for name, tip in TIPS.items():
        angle, direction, sel = fit_crack(xy, dmg, tip)
        tx, ty = tip
        if angle is None:
            print(f"{name} notch tip ({tx * 1e3:.0f}, {ty * 1e3:.0f}) mm: no crack found "
                  f"(fewer than 5 columns with damage > {THRESHOLD})")
            continue
        outward = np.sign(direction[1]) == np.sign(ty)
        results[name] = angle
        print(f"{name} notch tip ({tx * 1e3:.0f}, {ty * 1e3:.0f}) mm: crack angle {angle:.1f} deg to the notch, "
              f"running {'away from' if outward else 'towards'} the impacted strip "
              f"({sel.sum()} columns, r = {R_MIN * 1e3:.0f}-{R_MAX * 1e3:.0f} mm)")
        ax.scatter(1e3 * xy[sel, 0], 1e3 * xy[sel, 1], s=3, c="red", linewidths=0)
        # the fitted line, through the centroid of the selected points, over their extent
        rel = xy[sel] - np.array(tip)
        c = rel.mean(axis=0)
        t = (rel - c) @ direction
        a, b = np.array(tip) + c + t.min() * direction, np.array(tip) + c + t.max() * direction
        ax.plot(1e3 * np.array([a[0], b[0]]), 1e3 * np.array([a[1], b[1]]), "w-", lw=1.5)
        ax.plot(1e3 * np.array([0, tx]), 1e3 * np.array([ty, ty]), "w-", lw=2.5)   # the notch
        ax.plot(1e3 * np.array([tx, tx + R_MAX]), 1e3 * np.array([ty, ty]), "w:", lw=1)
        ax.annotate(f"{angle:.0f}°", xy=(1e3 * b[0], 1e3 * b[1]), color="white", fontsize=13,
                    ha="left", va="center", xytext=(8, 0), textcoords="offset points",
                    bbox=dict(fc="black", alpha=0.5, lw=0))
    ax.set_xlim(0, 1e3 * (xy[:, 0].max() + spacing / 2))
    if results:
        mean = np.mean(list(results.values()))
        print(f"mean crack angle {mean:.1f} deg (experiment: about 70 deg)")
    fig.savefig(out, dpi=110, bbox_inches="tight")
    print(f"wrote {out}")


if __name__ == "__main__":
    main(sys.argv[1] if len(sys.argv) > 1 else str(HERE / "out" / "kalthoff.e"),
         pathlib.Path(sys.argv[2]) if len(sys.argv) > 2 else HERE / "crack_angle.png")
