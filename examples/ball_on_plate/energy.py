#!/usr/bin/python3
"""A free rigid steel ball striking an aluminium plate (deck.yaml): its velocity history and the energy balance.

    energy.py --peridot PATH [--out DIR] [--threads N] [--check TOL]

The balance: the ball's kinetic energy ½ M v² (M from the deck, v from the history's body_ball_vz) plus the
plate's kinetic and stored (strain) energy plus the energy in the contact penalty (contact_energy), less the work
of the clamped rim's supports (external_work less the contact's part: the penalty's work on the plate is
−Δcontact_energy − Δ(ball's kinetic energy)), against the ball's kinetic energy at t = 0. Nothing breaks, so the
sum is constant up to the integrator's error. Writes DIR/ball.png (velocity; energies) and prints the balance;
--check TOL exits 1 unless the sum stays within TOL (a fraction) of the initial energy at every output."""
import argparse
import csv
import os
import pathlib
import subprocess
import sys

import numpy as np

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

HERE = pathlib.Path(__file__).resolve().parent
MASS = 4.084e-3  # kg, the deck's


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--peridot", required=True)
    ap.add_argument("--out", default=str(HERE / "out"))
    ap.add_argument("--threads", type=int, default=1)
    ap.add_argument("--check", type=float)
    a = ap.parse_args()
    out = pathlib.Path(a.out).resolve()
    out.mkdir(parents=True, exist_ok=True)
    deck = out / "deck.yaml"
    deck.write_text((HERE / "deck.yaml").read_text().replace("directory: out", f"directory: {out}"))
    subprocess.run([a.peridot, "run", "-q", str(deck)], check=True, env=dict(os.environ, OMP_NUM_THREADS=str(a.threads)))
    with open(out / "history.csv") as f:
        rows = list(csv.DictReader(f))
    col = lambda key: np.array([float(r[key]) for r in rows])  # noqa: E731
    t, v = col("time"), col("body_ball_vz")
    ball = 0.5 * MASS * v ** 2
    plate_kinetic, stored, contact = col("kinetic_energy"), col("strain_energy"), col("contact_energy")
    # external_work = the supports' work + the contact's work on the plate; the latter is what the ball and the
    # penalty lost: ball[0] − ball − contact. So the supports' work is external_work − (ball[0] − ball − contact).
    supports = col("external_work") - (ball[0] - ball - contact)
    total = ball + plate_kinetic + stored + contact - supports
    e0 = total[0]
    drift = np.abs(total - e0).max() / e0
    print(f"ball: {v[0]:.3f} m/s → {v[-1]:.3f} m/s (restitution {-v[-1] / v[0]:.3f}); peak force {col('body_ball_fz').max():.1f} N")
    print(f"energy at the end: ball {ball[-1] / e0:.4f}, plate kinetic {plate_kinetic[-1] / e0:.4f}, stored "
          f"{stored[-1] / e0:.4f}, contact {contact[-1] / e0:.2e} of the initial {e0:.4f} J")
    print(f"largest |sum − initial| over the run: {drift * 100:.3f} % of the initial energy; the supports' work at the "
          f"end {supports[-1] / e0:.2e}")
    fig, (a1, a2) = plt.subplots(1, 2, figsize=(11, 4))
    a1.plot(t * 1e6, v)
    a1.set_xlabel("time (µs)")
    a1.set_ylabel("ball velocity, z (m/s)")
    a1.grid(alpha=0.3)
    for values, label in ((ball, "ball, kinetic"), (plate_kinetic, "plate, kinetic"), (stored, "plate, stored"),
                          (contact, "contact penalty"), (total, "sum")):
        a2.plot(t * 1e6, values / e0, label=label)
    a2.set_xlabel("time (µs)")
    a2.set_ylabel("energy / initial")
    a2.grid(alpha=0.3)
    a2.legend()
    fig.suptitle("Free rigid steel ball (4.08 g) at 50 m/s on a 4 mm aluminium plate")
    fig.tight_layout()
    fig.savefig(out / "ball.png", dpi=120)
    print(f"wrote {out / 'ball.png'}")
    if a.check is not None:
        ok = drift <= a.check
        print(("ok" if ok else "FAIL") + f": energy within {a.check * 100:g} %")
        sys.exit(0 if ok else 1)


if __name__ == "__main__":
    main()
