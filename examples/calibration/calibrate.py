#!/usr/bin/python3
"""Calibrates the yield stress of lps_plastic against a stress-strain curve, through Peridot's Python module,
and studies how the curve depends on each material parameter.

  1. The target: the strip of deck.yaml pulled to 1 % strain with a known yield stress (250 MPa unless
     --true-yield), optionally with measurement noise (--noise, a fraction of the largest stress; seeded).
  2. The calibration: scipy.optimize.minimize_scalar (bounded Brent) on the yield stress, from the bracket
     [--low, --high], minimising the RMS difference between the model's curve and the target. Each evaluation
     builds the problem with parameters={"materials.alloy.yield_stress": Y} and runs it with write_files=False.
  3. The sensitivity study: each of E, nu, yield stress and hardening modulus moved by +-5 % about the calibrated
     point; the normalised sensitivity (p / sigma) d sigma / d p at every strain by central differences.

Writes calibration.png (the curves, the objective against the yield stress, the sensitivities) and prints a
table. --check exits 1 unless the recovered yield stress is within 1 % of the true one.

    PYTHONPATH=build/python /usr/bin/python3 examples/calibration/calibrate.py [--noise 0.005] [--check]

Runs in about 15 s on one core (about 25 runs of an 80-point strip, 20 load steps of dynamic relaxation each).
"""
import argparse
import os
import sys
import time

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
WIDTH, THICKNESS, GAUGE = 0.004, 0.001, 0.017  # m: the deck's strip width, thickness and grip separation


def import_peridot(module_dir):
    """The module from --module-dir, else from the build tree next to this example, else an installed one."""
    for folder in filter(None, [module_dir, os.path.join(HERE, "..", "..", "build", "python")]):
        if os.path.isdir(folder):
            sys.path.insert(0, os.path.abspath(folder))
            break
    import peridot

    return peridot


class Model:
    """The deck's stress-strain curve for given material parameters (deck key → value)."""

    def __init__(self, peridot, deck):
        self.peridot, self.deck, self.runs, self.seconds = peridot, deck, 0, 0.0

    def curve(self, **material):
        start = time.perf_counter()
        parameters = {f"materials.alloy.{key}": value for key, value in material.items()}
        run = self.peridot.Problem(self.deck, parameters=parameters).start(write_files=False)
        run.advance()
        history = run.history()
        self.runs += 1
        self.seconds += time.perf_counter() - start
        # The load factor goes 0 … 1 over the load steps; the grips separate by 1 % of the gauge length at 1.
        strain = 0.01 * history["load_factor"]
        stress = history["reaction_right_grip_x"] / (WIDTH * THICKNESS)
        return strain, stress


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--deck", default=os.path.join(HERE, "deck.yaml"))
    parser.add_argument("--module-dir", help="folder holding the peridot module (default: build/python)")
    parser.add_argument("--true-yield", type=float, default=250e6, help="Pa, the target's yield stress")
    parser.add_argument("--low", type=float, default=100e6, help="Pa, the search bracket's lower end")
    parser.add_argument("--high", type=float, default=500e6, help="Pa, the search bracket's upper end")
    parser.add_argument("--noise", type=float, default=0.0, help="noise on the target, a fraction of its largest stress")
    parser.add_argument("--seed", type=int, default=1)
    parser.add_argument("--plot", default=os.path.join(HERE, "calibration.png"))
    parser.add_argument("--check", action="store_true", help="exit 1 unless the yield stress is recovered to 1 %%")
    args = parser.parse_args()

    from scipy.optimize import minimize_scalar

    peridot = import_peridot(args.module_dir)
    peridot.set_threads(1)
    model = Model(peridot, args.deck)
    baseline = {"youngs_modulus": 70e9, "poisson_ratio": 0.33, "hardening_modulus": 2e9}

    # 1. The synthetic measurement.
    strain, target = model.curve(yield_stress=args.true_yield, **baseline)
    rng = np.random.default_rng(args.seed)
    measured = target + args.noise * np.max(np.abs(target)) * rng.standard_normal(target.shape) * (strain > 0)

    # 2. The calibration.
    trials = []

    def misfit(yield_stress):
        _, stress = model.curve(yield_stress=yield_stress, **baseline)
        value = np.sqrt(np.mean((stress - measured) ** 2)) / np.max(np.abs(measured))
        trials.append((yield_stress, value))
        return value

    runs_before = model.runs
    result = minimize_scalar(misfit, bounds=(args.low, args.high), method="bounded", options={"xatol": 1e4})
    recovered = result.x
    error = (recovered - args.true_yield) / args.true_yield
    calibration_runs = model.runs - runs_before
    print(f"target: yield stress {args.true_yield / 1e6:.1f} MPa, noise {100 * args.noise:.2f} % of the largest stress "
          f"({len(strain) - 1} load steps to 1 % strain)")
    print(f"recovered: {recovered / 1e6:.3f} MPa ({100 * error:+.3f} %) in {calibration_runs} runs, "
          f"RMS misfit {100 * result.fun:.4f} % of the largest stress")

    # 3. Sensitivities about the calibrated point: (p / sigma) d sigma / d p by central differences of +-5 %.
    point = dict(baseline, yield_stress=recovered)
    _, at_point = model.curve(**point)
    sensitivities = {}
    for key in ("youngs_modulus", "poisson_ratio", "yield_stress", "hardening_modulus"):
        up, down = dict(point), dict(point)
        up[key], down[key] = 1.05 * point[key], 0.95 * point[key]
        _, s_up = model.curve(**up)
        _, s_down = model.curve(**down)
        with np.errstate(invalid="ignore", divide="ignore"):
            sensitivities[key] = np.where(at_point != 0, (s_up - s_down) / (0.1 * at_point), 0.0)
    print("normalised sensitivity (p/sigma) dsigma/dp of the stress at strain 0.2 %, 0.6 %, 1.0 %:")
    picks = [int(np.argmin(np.abs(strain - e))) for e in (0.002, 0.006, 0.010)]
    for key, s in sensitivities.items():
        print(f"  {key:18s} " + "  ".join(f"{s[k]:+.3f}" for k in picks))
    print(f"{model.runs} runs in {model.seconds:.1f} s ({model.seconds / model.runs:.2f} s each)")

    plot(args, strain, measured, model, baseline, trials, recovered, sensitivities)
    if args.check:
        ok = abs(error) <= 0.01
        print(f"check: yield stress recovered to {100 * abs(error):.3f} % (limit 1 %): {'ok' if ok else 'FAILED'}")
        return 0 if ok else 1
    return 0


def plot(args, strain, measured, model, baseline, trials, recovered, sensitivities):
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, axes = plt.subplots(1, 3, figsize=(15, 4.4))
    ax = axes[0]
    ax.plot(100 * strain, measured / 1e6, "ko", ms=4, label=f"target (yield {args.true_yield / 1e6:.0f} MPa"
            + (f", noise {100 * args.noise:.1f} %)" if args.noise else ")"))
    for y, style, label in ((args.low, "C1--", "bracket ends"), (args.high, "C1--", None),
                            (recovered, "C0-", f"calibrated: {recovered / 1e6:.2f} MPa")):
        e, s = model.curve(yield_stress=y, **baseline)
        ax.plot(100 * e, s / 1e6, style, label=label)
    ax.set(xlabel="nominal strain (%)", ylabel="nominal stress (MPa)", title="stress-strain curve of the strip")
    ax.legend(fontsize=8)
    ax = axes[1]
    order = np.argsort([t[0] for t in trials])
    ys = np.array([trials[k][0] for k in order]) / 1e6
    fs = np.array([trials[k][1] for k in order])
    ax.semilogy(ys, np.maximum(fs, 1e-9), "C0.-")
    ax.axvline(args.true_yield / 1e6, color="k", lw=0.8, ls=":", label="true yield stress")
    ax.set(xlabel="yield stress (MPa)", ylabel="RMS misfit / largest stress",
           title=f"objective at the {len(trials)} evaluations")
    ax.legend(fontsize=8)
    ax = axes[2]
    labels = {"youngs_modulus": "E", "poisson_ratio": "ν", "yield_stress": "σY", "hardening_modulus": "H"}
    for key, s in sensitivities.items():
        ax.plot(100 * strain[1:], s[1:], label=labels[key])
    ax.axhline(0, color="k", lw=0.5)
    ax.set(xlabel="nominal strain (%)", ylabel="(p/σ) ∂σ/∂p", title="normalised sensitivity (±5 %)")
    ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(args.plot, dpi=110)
    print(f"wrote {args.plot}")


if __name__ == "__main__":
    sys.exit(main())
