#!/usr/bin/python3
"""Taylor impact of 6061-T6 rods on a rigid anvil: runs Peridot for a set of shots, measures the final length
Lf/L0 and the impact-face diameter Df/D0 from the last Exodus frame, checks the energy balance from the
history, and compares with House et al. (1995) (../shared/reference/taylor_6061T6_house1995.csv beside the repository, or --data).

    /usr/bin/python3 examples/taylor_impact/taylor.py --peridot build/peridot --set ld5 --out taylor_runs
    /usr/bin/python3 examples/taylor_impact/taylor.py --peridot build/peridot --set all --out taylor_runs --plot taylor.png

Sets: short (one coarse rod: the ctest case), ld5 (the three L0/D0 = 5 shots), other (L0/D0 = 2 and 10),
convergence (244 m/s at 20 and 30 points across, δ = 3 and 4 spacings), all (ld5 + other + convergence).
Every deck is made from deck.yaml next to this script by changing spacing, horizon factor, length, speed
and end time; the anvil passes through the centres of the first layer of points.

Measures (points are cell centres on a lattice of spacing Δx):
  Lf = (max z − min z of the points) + Δx, the same formula giving L0 at t = 0;
  Df = 2 max r + Δx over all points (the widest section, the mushroom: the data's "max diameter"), normalised
       by the same quantity at t = 0 (2 max r₀ + Δx), since a lattice cylinder is not exactly D0 wide;
  also reported: the same over the first layer of points only (those whose reference z is the smallest).
Energy balance: kinetic + elastic + plastic (dissipated) + hourglass work − work of the anvil = initial
kinetic energy, from the last history row, reported as a fraction of the initial kinetic energy.
"""
import argparse
import csv
import os
import re
import subprocess
import sys

import numpy as np
import netCDF4

HERE = os.path.dirname(os.path.abspath(__file__))
D0 = 7.595e-3  # m


def make_deck(template, across, horizon_factor, ld, speed, end_time_us):
    dx = D0 / across
    text = template
    text = re.sub(r"spacing: [^\n]*", f"spacing: {dx!r}", text, count=1)
    text = re.sub(r"horizon_factor: [^\n]*", f"horizon_factor: {horizon_factor}", text, count=1)
    text = re.sub(r"length: [0-9.]+ mm", f"length: {ld * D0!r}", text, count=1)
    text = re.sub(r'z: "-[0-9.]+"', f'z: "-{speed}"', text, count=1)
    text = re.sub(r"point: \[0, 0, [^\]]*\]", f"point: [0, 0, {0.5 * dx!r}]", text, count=1)
    text = re.sub(r"end_time: [^\n]*", f"end_time: {end_time_us} us", text, count=1)
    text = re.sub(r"every: 500", "every: 100000", text, count=1)  # first and last frames only
    return text


def nodal(ds, names, name, step):
    k = names.index(name)
    return np.array(ds.variables[f"vals_nod_var{k + 1}"][step, :])


def measure(exodus_path, spacing):
    ds = netCDF4.Dataset(exodus_path, "r")
    ds.set_auto_mask(False)
    names = [s.strip() for s in netCDF4.chartostring(ds.variables["name_nod_var"][:]).tolist()]
    x = np.array([ds.variables["coord" + a][:] for a in "xyz"])
    last = ds.dimensions["time_step"].size - 1
    y = x + np.array([nodal(ds, names, "displacement_" + a, last) for a in "xyz"])
    eqps = nodal(ds, names, "equivalent_plastic_strain", last)
    ds.close()
    first_layer = x[2] < x[2].min() + 0.5 * spacing
    length0 = x[2].max() - x[2].min() + spacing
    length = y[2].max() - y[2].min() + spacing
    diameter0 = 2 * np.hypot(x[0], x[1])[first_layer].max() + spacing
    radius = np.hypot(y[0], y[1])
    face = (2 * radius[first_layer].max() + spacing) / diameter0
    widest = (2 * radius.max() + spacing) / diameter0
    return length / length0, widest, face, float(eqps.max())


def energy_balance(history_path):
    rows = list(csv.DictReader(open(history_path)))
    first, last = rows[0], rows[-1]
    ke0 = float(first["kinetic_energy"])
    total = sum(float(last[k]) for k in ("kinetic_energy", "strain_energy", "dissipated_energy", "hourglass_work"))
    return (total - float(last["external_work"])) / ke0 - 1, float(last["kinetic_energy"]) / ke0, float(last["dissipated_energy"]) / ke0


def experiment(path):
    shots = []
    for row in csv.DictReader(line for line in open(path) if not line.startswith("#")):
        shots.append({"ld": float(row["L0_over_D0"]), "speed": float(row["U0_m_s"]),
                      "lf": float(row["Lf_over_L0"]), "df": float(row["Df_over_D0"])})
    return shots


# (name, across, horizon factor, L0/D0, speed m/s, end time µs)
SETS = {
    "short": [("short", 8, 3.015, 5, 244, 60)],
    "ld5": [(f"ld5_{v}", 20, 3.015, 5, v, 80) for v in (170, 244, 295)],
    "other": [("ld2_240", 20, 3.015, 2, 240, 60), ("ld10_256", 20, 3.015, 10, 256, 140)],
    # 50 µs: the rod has left the anvil by 47 µs at 244 m/s (its kinetic energy is then 0.6 % of the initial)
    "convergence": [("conv_n20_d3", 20, 3.015, 5, 244, 50), ("conv_n20_d4", 20, 4.015, 5, 244, 50),
                    ("conv_n30_d3", 30, 3.015, 5, 244, 50)],
}
SETS["all"] = SETS["ld5"] + SETS["other"] + SETS["convergence"]


def main():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--peridot", required=True)
    p.add_argument("--set", choices=sorted(SETS), default="ld5")
    p.add_argument("--out", default="taylor_runs")
    p.add_argument("--threads", type=int, default=2)
    # The shared reference data sits beside the repository (../shared/reference).
    p.add_argument("--data", default=os.path.join(HERE, "..", "..", "..", "shared", "reference",
                                                  "taylor_6061T6_house1995.csv"))
    p.add_argument("--plot", help="write a figure of Lf/L0 and Df/D0 against the experiment")
    p.add_argument("--reuse", action="store_true", help="measure existing runs instead of running again")
    p.add_argument("--check-short", action="store_true",
                   help="exit 1 unless the short run's Lf/L0 is in [0.83, 0.89] and its energy balance within 1 %%")
    a = p.parse_args()
    template = open(os.path.join(HERE, "deck.yaml")).read()
    shots = experiment(a.data) if os.path.exists(a.data) else []
    results = []
    for name, across, hf, ld, speed, end in SETS[a.set]:
        run_dir = os.path.join(os.path.abspath(a.out), name)
        os.makedirs(run_dir, exist_ok=True)
        deck = os.path.join(run_dir, "deck.yaml")
        open(deck, "w").write(make_deck(template, across, hf, ld, speed, end))
        if not (a.reuse and os.path.exists(os.path.join(run_dir, "output", "results.e"))):
            r = subprocess.run([a.peridot, "run", "-q", "-t", str(a.threads), deck], capture_output=True, text=True)
            if r.returncode != 0:
                print(f"{name}: peridot failed ({r.returncode})\n{r.stdout}{r.stderr}")
                return 2
        lf, df, face, eqps = measure(os.path.join(run_dir, "output", "results.e"), D0 / across)
        balance, ke_left, plastic = energy_balance(os.path.join(run_dir, "output", "history.csv"))
        match = [s for s in shots if s["ld"] == ld and abs(s["speed"] - speed) < 0.5]
        exp = match[0] if match else None
        results.append((name, across, hf, ld, speed, lf, df, face, eqps, balance, ke_left, plastic, exp))
        line = (f"{name:12s} N={across:2d} δ/Δx={hf:5.3f} L0/D0={ld:4.1f} v={speed:5.0f} m/s  Lf/L0={lf:.4f}  Df/D0={df:.4f}"
                f" (first layer {face:.4f})  max εp={eqps:.3f}  energy balance {100 * balance:+.2f} % (KE left {100 * ke_left:.2f} %, plastic {100 * plastic:.1f} %)")
        if exp:
            line += (f"  | exp Lf/L0={exp['lf']:.4f} ({100 * (lf / exp['lf'] - 1):+.1f} %)"
                     f"  Df/D0={exp['df']:.4f} ({100 * (df / exp['df'] - 1):+.1f} %)")
        print(line, flush=True)
    with open(os.path.join(os.path.abspath(a.out), f"results_{a.set}.csv"), "w") as f:
        f.write("name,across,horizon_factor,L0_over_D0,speed_m_s,Lf_over_L0,Df_over_D0,Df_first_layer_over_D0,max_eqps,"
                "energy_balance,exp_Lf_over_L0,exp_Df_over_D0\n")
        for name, across, hf, ld, speed, lf, df, face, eqps, balance, _, _, exp in results:
            f.write(f"{name},{across},{hf},{ld},{speed},{lf:.5f},{df:.5f},{face:.5f},{eqps:.4f},{balance:.5f},"
                    f"{exp['lf'] if exp else ''},{exp['df'] if exp else ''}\n")
    if a.plot:
        plot(results, shots, a.plot)
    if a.check_short:
        name, _, _, _, _, lf, _, _, _, balance, *_ = results[0]
        ok = 0.83 <= lf <= 0.89 and abs(balance) < 0.01
        print(("ok" if ok else "FAIL") + f": short rod Lf/L0 = {lf:.4f} (band [0.83, 0.89]), energy balance {100 * balance:+.2f} %")
        return 0 if ok else 1
    return 0


def plot(results, shots, path):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, axes = plt.subplots(1, 2, figsize=(10, 4))
    colours = {1.5: "C5", 2: "C0", 3: "C4", 4: "C3", 5: "C1", 7.5: "C6", 10: "C2"}
    for ax, key, label in ((axes[0], "lf", "Lf/L0"), (axes[1], "df", "Df/D0")):
        for ld in sorted({s["ld"] for s in shots}):
            pts = [s for s in shots if s["ld"] == ld]
            ax.plot([s["speed"] for s in pts], [s[key] for s in pts], "o", mfc="none", color=colours.get(ld, "k"),
                    label=f"House 1995, L0/D0 = {ld:g}")
        for name, across, hf, ld, speed, lf, df, *_ in results:
            ax.plot(speed, lf if key == "lf" else df, "x" if across == 20 and hf < 3.5 else "+", ms=9,
                    color=colours.get(ld, "k"))
        ax.set_xlabel("impact speed (m/s)")
        ax.set_ylabel(label)
        ax.grid(alpha=0.3)
    axes[0].legend(fontsize=7)
    axes[0].set_title("Peridot (x: 20 across, δ = 3Δx; +: convergence runs)", fontsize=9)
    fig.tight_layout()
    fig.savefig(path, dpi=120)


if __name__ == "__main__":
    sys.exit(main())
