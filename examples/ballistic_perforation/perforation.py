#!/usr/bin/python3
"""Ballistic perforation of a 6061-T6 plate by a rigid steel sphere (README.md): runs deck.yaml next to this script at a
range of impact speeds, measures the sphere's residual velocity, fits the Recht–Ipson curve and draws the damage.

    /usr/bin/python3 examples/ballistic_perforation/perforation.py --peridot build/peridot --out perforation_runs \\
        --plot perforation.png --pictures perforation_damage.png

Each shot changes only the sphere's velocity and the end time (30 µs plus the time to cross 6 mm). The residual
velocity is the sphere's downward speed at the end (its history columns body_ball_vz); a sphere that has stopped or
bounced back counts as 0. Recht–Ipson: v_r = a (v_i^p − v_bl^p)^(1/p) above the ballistic limit v_bl, 0 below; a, v_bl
and p are fitted by least squares (scipy), and also a and v_bl with p = 2 (the rigid-plug energy balance, where
a = m/(m + m_plug)).
A shot whose folder already holds results.e is measured again, not rerun (delete the folder to rerun it).
--check-short: two shots at Δx = 0.4 mm (100 and 600 m/s), always run; passes when the slow one does not perforate
and the fast one does, with a residual velocity below the impact velocity, and in both the work done on the plate
equals the energy the sphere lost to within 1 % of its initial energy.
"""
import argparse
import csv
import os
import re
import subprocess
import sys

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(HERE, "..", "..", "tools"))
import peridot_results as pr  # noqa: E402

SPEEDS = [100, 125, 150, 175, 200, 250, 300, 400, 500, 600]  # m/s
PICTURES = [200, 300, 500]


def make_deck(speed, spacing=None):
    text = open(os.path.join(HERE, "deck.yaml")).read()
    text = re.sub(r"velocity: \[0, 0, -[0-9.]+\]", f"velocity: [0, 0, -{speed}]", text, count=1)
    end = 30 + 6e-3 / speed * 1e6
    text = re.sub(r"end_time: [^\n]*", f"end_time: {end:.1f} us", text, count=1)
    if spacing:
        text = re.sub(r"spacing: [^\n]*", f"spacing: {spacing} mm", text, count=1)
    return text


def run(peridot, out, speed, threads, spacing=None, again=False):
    folder = os.path.join(out, f"v{speed}" + (f"_dx{spacing}" if spacing else ""))
    os.makedirs(folder, exist_ok=True)
    deck = os.path.join(folder, "deck.yaml")
    open(deck, "w").write(make_deck(speed, spacing))
    results = os.path.join(folder, "output")
    if again or not os.path.exists(os.path.join(results, "results.e")):
        cmd = [peridot, "run", "-q", deck, "-o", results] + (["-t", str(threads)] if threads else [])
        subprocess.run(cmd, check=True)
    rows = list(csv.DictReader(open(os.path.join(results, "history.csv"))))
    last = rows[-1]
    residual = max(0.0, -float(last["body_ball_vz"]))
    # Energy: what the sphere lost is what the contact forces did on the plate (external_work, which also holds
    # the work of the plate's own short-range contact, zero net when that creates no energy).
    mass = float(re.search(r"mass: ([0-9.eE+-]+) g", make_deck(speed, spacing)).group(1)) * 1e-3
    ball = [0.5 * mass * sum(float(r[f"body_ball_v{c}"]) ** 2 for c in "xyz") for r in (rows[0], last)]
    imbalance = (float(last["external_work"]) - (ball[0] - ball[1])) / ball[0]
    exo = os.path.join(results, "results.e")
    D = pr.read_field(exo, "material_damage")
    return {"speed": speed, "residual": residual, "ball_z_mm": float(last["body_ball_z"]) * 1e3,
            "failed": int((D >= 1).sum()), "broken": float(last["broken_fraction"]),
            "fragments": int(float(last["fragments"])), "imbalance": imbalance, "exodus": exo}


def recht_ipson(v, a, vbl, p):
    return np.where(v > vbl, a * np.clip(v ** p - vbl ** p, 0, None) ** (1 / p), 0.0)


def fit(shots):
    from scipy.optimize import curve_fit
    v = np.array([s["speed"] for s in shots], float)
    vr = np.array([s["residual"] for s in shots], float)
    first = v[vr > 0].min() if (vr > 0).any() else v.max()
    guess_bl = 0.5 * (first + (v[vr == 0].max() if (vr == 0).any() else 0))
    two, _ = curve_fit(lambda x, a, vbl: recht_ipson(x, a, vbl, 2.0), v, vr, p0=[0.9, guess_bl], maxfev=20000)
    free, _ = curve_fit(recht_ipson, v, vr, p0=[two[0], two[1], 2.0], maxfev=20000,
                        bounds=([0, 0, 1.0], [1.5, v.max(), 6.0]))
    return {"a2": two[0], "vbl2": two[1], "a": free[0], "vbl": free[1], "p": free[2]}


def plot_curve(shots, f, path):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, ax = plt.subplots(figsize=(6, 4.5))
    v = np.array([s["speed"] for s in shots], float)
    ax.plot(v, [s["residual"] for s in shots], "ko", label="Peridot")
    grid = np.linspace(0, v.max() * 1.05, 400)
    ax.plot(grid, recht_ipson(grid, f["a"], f["vbl"], f["p"]), "C0-",
            label=f"Recht–Ipson: a = {f['a']:.3f}, v_bl = {f['vbl']:.0f} m/s, p = {f['p']:.2f}")
    ax.plot(grid, recht_ipson(grid, f["a2"], f["vbl2"], 2.0), "C1--",
            label=f"p = 2: a = {f['a2']:.3f}, v_bl = {f['vbl2']:.0f} m/s")
    ax.plot(grid, grid, "k:", lw=0.8, label="v_r = v_i")
    ax.set_xlabel("impact velocity v_i (m/s)")
    ax.set_ylabel("residual velocity v_r (m/s)")
    ax.set_title("4 mm rigid steel sphere on a 1.6 mm 6061-T6 plate (Johnson–Cook damage)", fontsize=9)
    ax.grid(alpha=0.3)
    ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(path, dpi=120)


def plot_pictures(shots, path):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    chosen = [s for s in shots if s["speed"] in PICTURES]
    fig, axes = plt.subplots(1, len(chosen), figsize=(5 * len(chosen), 4), squeeze=False)
    for ax, s in zip(axes[0], chosen):
        with pr.Results(s["exodus"]) as res:
            x = res.coords.T
            y = res.positions().T
            D = res.field("material_damage")
        spacing = np.diff(np.unique(np.round(x[0], 9)))[0]
        slab = np.abs(x[1] - 0.5 * spacing) < 0.25 * spacing  # the lattice row next to the plane y = 0
        mm = 1e3
        alive = slab & (D < 1)
        sc = ax.scatter(y[0][alive] * mm, y[2][alive] * mm, c=D[alive], s=5, cmap="viridis", vmin=0, vmax=1)
        dead = slab & (D >= 1)
        ax.scatter(y[0][dead] * mm, y[2][dead] * mm, s=5, c="red", label="failed (D = 1)")
        ax.set_aspect("equal")
        ax.set_xlim(-6.5, 6.5)
        ax.set_ylim(-8, 3)
        ax.set_xlabel("x (mm)")
        ax.set_ylabel("z (mm)")
        ax.legend(fontsize=7, loc="upper right")
        ax.set_title(f"{s['speed']} m/s: residual {s['residual']:.0f} m/s, section y = Δx/2", fontsize=9)
        fig.colorbar(sc, ax=ax, label="D", shrink=0.7)
    fig.tight_layout()
    fig.savefig(path, dpi=110)


def main():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--peridot", required=True)
    p.add_argument("--out", required=True)
    p.add_argument("--threads", type=int, default=0)
    p.add_argument("--speeds", help="comma-separated impact speeds (m/s); default " + ",".join(map(str, SPEEDS)))
    p.add_argument("--plot")
    p.add_argument("--pictures")
    p.add_argument("--spacing", type=float, help="lattice spacing in mm instead of the deck's 0.2 mm")
    p.add_argument("--check-short", action="store_true")
    a = p.parse_args()
    spacing = 0.4 if a.check_short else a.spacing
    speeds = [100, 600] if a.check_short else ([float(s) for s in a.speeds.split(",")] if a.speeds else SPEEDS)
    shots = []
    print(f"{'v_i m/s':>8s} {'v_r m/s':>8s} {'ball z mm':>9s} {'failed':>7s} {'broken':>7s} {'fragments':>9s} "
          f"{'(W - ΔKE_ball)/KE0':>18s}")
    for v in speeds:
        v = int(v) if float(v).is_integer() else v
        s = run(a.peridot, a.out, v, a.threads, spacing, again=a.check_short)
        shots.append(s)
        print(f"{v:8} {s['residual']:8.1f} {s['ball_z_mm']:9.2f} {s['failed']:7d} {s['broken']:7.4f} {s['fragments']:9d} "
              f"{s['imbalance']:18.2e}", flush=True)
    if a.check_short:
        slow, fast = shots
        balanced = all(abs(s["imbalance"]) < 0.01 for s in shots)
        ok = slow["residual"] == 0 and 0 < fast["residual"] < fast["speed"] and balanced
        print(("ok" if ok else "FAIL") + f": 100 m/s residual {slow['residual']:.1f}, 600 m/s residual {fast['residual']:.1f}; "
              f"work on the plate against the sphere's lost energy within {max(abs(s['imbalance']) for s in shots):.2e} "
              "of its initial energy (at most 1e-2)")
        return 0 if ok else 1
    if sum(s["residual"] > 0 for s in shots) >= 2 and any(s["residual"] == 0 for s in shots):
        f = fit(shots)
        print(f"Recht–Ipson: a = {f['a']:.3f}, v_bl = {f['vbl']:.1f} m/s, p = {f['p']:.2f};  "
              f"with p = 2: a = {f['a2']:.3f}, v_bl = {f['vbl2']:.1f} m/s")
        if a.plot:
            plot_curve(shots, f, a.plot)
    if a.pictures:
        plot_pictures(shots, a.pictures)
    return 0


if __name__ == "__main__":
    sys.exit(main())
