#!/usr/bin/python3
"""Two elastic spheres colliding head on (deck.yaml) against Hertz's theory, at several resolutions.

    hertz.py --peridot PATH [--ratios 10,15,20] [--stiffness S --safety F] [--threads N] [--out DIR] [--check TOL] [--reuse]

Hertz, for two spheres of radius R, Young's modulus E, Poisson ratio ν (1/4 for bond-based PMB), density ρ, closing
at relative speed v: with E* = E / (2(1 − ν²)), R* = R/2, m* = m/2 (m = 4πR³ρ/3), the largest approach is
δ_max = (15 m* v² / (16 E* √R*))^(2/5), the peak force F_max = (4/3) E* √R* δ_max^(3/2), and the contact lasts
t_c = 2.9432 δ_max / v; the script also integrates m* δ'' = −(4/3) E* √R* δ^(3/2) for the whole force history. For
each R/Δx it runs deck.yaml (the spacing R/ratio, the spheres a little more than a horizon apart, until 14 µs after
they touch), takes the force on
the right sphere from the history (contact_right_x, every step), and prints the peak force, the contact time (the
time the force exceeds 5 % of its peak, against the same for Hertz: the first and last touches of a few surface
points are too faint to time) and the largest momentum (relative to m v/2). --stiffness S sets the contact's
stiffness_factor (15 by default) and --safety F the time step's safety factor (0.7 in the deck). Writes
DIR/hertz.png. --check TOL exits 1 unless the finest run's peak force and contact time are both within TOL (a
fraction) of Hertz's and it did not give way (a force below −1 % of its peak, or the energy KE + W + contact off
by more than 0.2 %: points passed each other, and the peak and duration measure the collapse)."""
import argparse
import csv
import math
import os
import pathlib
import re
import subprocess
import sys

import numpy as np

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

HERE = pathlib.Path(__file__).resolve().parent
R, E, NU, RHO, V = 5e-3, 70e9, 0.25, 2700.0, 100.0
THRESHOLD = 0.05  # the contact time compared: the force above this fraction of its peak


def hertz():
    m = 4 / 3 * math.pi * R ** 3 * RHO
    e_star, r_star, m_star = E / (2 * (1 - NU ** 2)), R / 2, m / 2
    delta = (15 * m_star * V ** 2 / (16 * e_star * math.sqrt(r_star))) ** 0.4
    force = 4 / 3 * e_star * math.sqrt(r_star) * delta ** 1.5
    duration = 2.9432 * delta / V
    return m, delta, force, duration


def hertz_history(steps=20000):
    """The Hertz impact in time: m* δ'' = −K δ^(3/2), K = (4/3) E* √R*, δ(0) = 0, δ'(0) = v, integrated by velocity
    Verlet until δ returns to 0; returns t and F = K δ^(3/2)."""
    m, delta_max, _, duration = hertz()
    e_star, r_star, m_star = E / (2 * (1 - NU ** 2)), R / 2, m / 2
    k = 4 / 3 * e_star * math.sqrt(r_star)
    dt = 1.2 * duration / steps
    t, delta, rate = [0.0], [0.0], V
    d = 0.0
    while True:
        a = -k * max(d, 0) ** 1.5 / m_star
        rate += 0.5 * dt * a
        d += dt * rate
        rate += 0.5 * dt * (-k * max(d, 0) ** 1.5 / m_star)
        t.append(t[-1] + dt)
        delta.append(d)
        if d <= 0:
            break
    t, delta = np.array(t), np.clip(np.array(delta), 0, None)
    return t, k * delta ** 1.5


def time_above(t, force, fraction):
    """Time during which the force exceeds fraction × its peak (linear interpolation at the crossings)."""
    level = fraction * force.max()
    above = np.nonzero(force > level)[0]
    i, j = above[0], above[-1]
    start = t[i - 1] + (level - force[i - 1]) / (force[i] - force[i - 1]) * (t[i] - t[i - 1]) if i > 0 else t[i]
    end = t[j] + (force[j] - level) / (force[j] - force[j + 1]) * (t[j + 1] - t[j]) if j + 1 < len(t) else t[j]
    return start, end


def replaced(text, old, new):
    """text with old (which must be there: the deck and this script must not drift apart) replaced by new."""
    assert old in text, f"deck.yaml has no {old!r}"
    return text.replace(old, new)


def run(peridot, ratio, out, threads, reuse=False, stiffness=None, safety=None):
    spacing = R / ratio
    text = (HERE / "deck.yaml").read_text()
    text = replaced(text, "spacing: 0.5 mm             # R/dx = 10", f"spacing: {spacing * 1e3:.10g} mm")
    # The surfaces about a horizon and a spacing apart (never bonded), the centres on lattice planes (multiples
    # of Δx), so that the spheres are mirror images. (Centres on lattice points instead leave one lone point at
    # each pole, which the other sphere pushes in: worse.) The run ends 14 µs after the spheres touch (when the
    # surfaces, half a spacing beyond the outer points, meet): Hertz's contact lasts 12.3 µs.
    horizon = float(re.search(r"horizon_factor: ([0-9.]+)", text).group(1)) * spacing
    centre = round((R + 0.5 * (horizon + spacing)) / spacing) * spacing
    assert 2 * (centre - R) > horizon
    end = math.ceil(((2 * (centre - R) - spacing) / V + 14e-6) * 1e6)
    text = replaced(text, "end_time: 60 us", f"end_time: {end} us")
    if stiffness is not None:
        text = replaced(text, "contact:\n", f"contact:\n  stiffness_factor: {stiffness:g}\n")
    if safety is not None:
        text = replaced(text, "safety_factor: 0.7", f"safety_factor: {safety:g}")
    text = replaced(text, "center: [-6.5 mm, 0, 0]", f"center: [{-centre * 1e3:.10g} mm, 0, 0]")
    text = replaced(text, "center: [6.5 mm, 0, 0]", f"center: [{centre * 1e3:.10g} mm, 0, 0]")
    name = f"ratio{ratio:g}" + (f"_stiffness{stiffness:g}" if stiffness is not None else "")
    text = replaced(text, "directory: out", f"directory: {out / name}")
    deck = out / f"{name}.yaml"
    deck.write_text(text)
    env = dict(os.environ, OMP_NUM_THREADS=str(threads))
    if not (reuse and (out / name / "history.csv").exists()):
        subprocess.run([peridot, "run", "-q", str(deck)], check=True, env=env)
    with open(out / name / "history.csv") as f:
        rows = list(csv.DictReader(f))
    col = lambda key: np.array([float(r[key]) for r in rows])  # noqa: E731
    energy = col("kinetic_energy") + col("strain_energy") + col("contact_energy")
    return col("time"), col("contact_right_x"), col("momentum_x"), np.abs(energy / energy[0] - 1).max()


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--peridot", required=True)
    ap.add_argument("--ratios", default="10,15,20")
    ap.add_argument("--stiffness", type=float, help="the contact's stiffness_factor (default: the deck's, 15)")
    ap.add_argument("--safety", type=float, help="the time step's safety factor (default: the deck's, 0.7)")
    ap.add_argument("--threads", type=int, default=1)
    ap.add_argument("--out", default=str(HERE / "out"))
    ap.add_argument("--check", type=float)
    ap.add_argument("--reuse", action="store_true", help="analyse the histories already in DIR")
    a = ap.parse_args()
    out = pathlib.Path(a.out).resolve()
    out.mkdir(parents=True, exist_ok=True)
    m, delta, fmax, duration = hertz()
    th, fh = hertz_history()
    hs, he = time_above(th, fh, THRESHOLD)
    above_hertz = he - hs
    print(f"Hertz: δ_max = {delta * 1e3:.4f} mm, F_max = {fmax:.1f} N (integrated: {fh.max():.1f} N), t_c = "
          f"{duration * 1e6:.3f} µs (integrated: {th[-1] * 1e6:.3f} µs), above {THRESHOLD * 100:g} % of the peak "
          f"{above_hertz * 1e6:.3f} µs")
    print(f"| R/Δx | peak force (N) | vs Hertz | time above {THRESHOLD * 100:g} % of the peak (µs) | vs Hertz | "
          "largest momentum / (m v/2) | most negative force / peak | largest energy drift |")
    print("|---|---|---|---|---|---|---|---|")
    fig, ax = plt.subplots(figsize=(7, 4.2))
    errors = None
    for ratio in [float(r) for r in a.ratios.split(",")]:
        t, force, momentum, drift = run(a.peridot, ratio, out, a.threads, a.reuse, a.stiffness, a.safety)
        peak = force.max()
        start, end = time_above(t, force, THRESHOLD)
        errors = (peak / fmax - 1, (end - start) / above_hertz - 1)
        # Points that passed each other push apart the wrong way (the force turns negative), and the energy no
        # longer closes: then the peak and the duration measure the collapse, not the contact.
        gave_way = force.min() < -0.01 * peak or drift > 2e-3
        print(f"| {ratio:g} | {peak:.1f} | {errors[0] * 100:+.1f} % | {(end - start) * 1e6:.3f} | {errors[1] * 100:+.1f} % | "
              f"{np.abs(momentum).max() / (m * V / 2):.2g} | {force.min() / peak:.3f} | {drift:.2g} |"
              + (" gave way" if gave_way else ""))
        middle = 0.5 * (start + end)
        ax.plot((t - middle) * 1e6, force / 1e3, label=f"Peridot, R/Δx = {ratio:g}" + (f", stiffness {a.stiffness:g}" if a.stiffness is not None else ""))
    ax.plot((th - 0.5 * (hs + he)) * 1e6, fh / 1e3, "k--", label="Hertz")
    ax.set_xlim(-12, 12)
    ax.set_xlabel("time from the middle of the contact (µs)")
    ax.set_ylabel("contact force (kN)")
    ax.set_title("Two aluminium spheres, R = 5 mm, closing at 100 m/s")
    ax.grid(alpha=0.3)
    ax.legend()
    fig.tight_layout()
    fig.savefig(out / "hertz.png", dpi=120)
    print(f"wrote {out / 'hertz.png'}")
    if a.check is not None:
        ok = abs(errors[0]) <= a.check and abs(errors[1]) <= a.check and not gave_way
        print(f"{'ok' if ok else 'FAIL'}: finest run within {a.check * 100:g} % of Hertz: {ok}")
        sys.exit(0 if ok else 1)


if __name__ == "__main__":
    main()
