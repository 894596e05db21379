#!/usr/bin/python3
"""Taylor impact of 6061-T6 rods on a rigid anvil: runs Peridot for a set of shots, measures the final length
Lf/L0 and the impact-face diameter Df/D0 from the last Exodus frame, checks the energy balance from the
history, and compares with House et al. (1995) (data/taylor_6061T6_house1995.csv next to this script, or --data;
data/README.md says where the numbers come from).

    /usr/bin/python3 examples/taylor_impact/taylor.py --peridot build/peridot --set ld5 --out taylor_runs
    /usr/bin/python3 examples/taylor_impact/taylor.py --peridot build/peridot --set figure --out taylor_runs --plot taylor.png

Sets: short (one coarse rod: the ctest case), ld5 (the three L0/D0 = 5 shots), other (L0/D0 = 2 and 10),
convergence (295 m/s at 20 and 30 points across, δ = 3 and 4 spacings), all (ld5 + other + convergence),
figure (what taylor.png shows); the longer studies are listed in SETS below and in README.md.
Every deck is made from deck.yaml next to this script by changing spacing, horizon factor, length, speed
and end time; the anvil is a symmetry plane on the impact face (--contact symmetry, the deck's) or a penalty
plane through the centres of the first layer of points (--contact penalty, the earlier versions).

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

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(HERE, "..", "..", "tools"))
import peridot_results as pr  # noqa: E402
D0 = 7.595e-3  # m


# Johnson–Cook 6061-T6 (A, B, n, C, m from Uintah's JCPlastic6061T6Al.xml as read in the project's reference table;
# ε̇0 = 1 /s, the common reading, where that file gives 1e-6 /s) in place of Foster's J2 fit; the thermal section
# (its exponent is JC's m = 1.34) stays.
JOHNSON_COOK = """constitutive_law: johnson_cook
    yield_stress: 324 MPa
    strain_hardening_coefficient: 114 MPa
    strain_hardening_exponent: 0.42
    strain_rate_coefficient: 0.002
    reference_strain_rate: 1 1/s
"""
# Johnson–Cook failure strain of 6061-T6 (D1 … D5 as widely quoted after Lesuer, LLNL 2000; not in the project's
# reference table and not checked against the primary source: examples/notched_bar/README.md), acting through the
# influence function (Tupek et al. 2013; docs/correspondence.md).
DAMAGE = "    johnson_cook_damage: {d1: -0.77, d2: 1.45, d3: -0.47, d4: 0, d5: 1.6}\n"


def make_deck(template, across, horizon_factor, ld, speed, end_time_us, hourglass=None, thermal=True, viscosity=None,
              contact="penalty", law="j2_viscoplastic", damage=False, bulk_viscosity=None):
    dx = D0 / across
    text = template
    if bulk_viscosity is not None:  # (C_l, C_q) of the shock viscosity (the deck has none)
        text = re.sub(r"(\n( *)hourglass_coefficient: [^\n]*)",
                      rf"\1\n\2bulk_viscosity_linear: {bulk_viscosity[0]}\n\2bulk_viscosity_quadratic: {bulk_viscosity[1]}",
                      text, count=1)
    if damage:
        text = re.sub(r"(\n *hourglass_coefficient:)", "\n" + DAMAGE.rstrip("\n") + r"\1", text, count=1)
    if law == "johnson_cook":
        text = re.sub(r"constitutive_law: j2_viscoplastic\n(    [a-z_]+: [^\n]*\n)*?    reference_strain_rate: [^\n]*\n",
                      JOHNSON_COOK, text, count=1)
    if viscosity is not None:  # hourglass dashpots, C_HV (the deck has none)
        text = re.sub(r"(\n( *)hourglass_coefficient: [^\n]*)", rf"\1\n\2hourglass_viscosity: {viscosity}", text, count=1)
    if not thermal:  # Foster's law as published: drop the thermal_softening section
        text = re.sub(r"\n    thermal_softening:[^\n]*(\n      [^\n]*)+", "", text, count=1)
    if hourglass is not None:
        text = re.sub(r"hourglass_coefficient: [^\n]*", f"hourglass_coefficient: {hourglass}", text, count=1)
    text = re.sub(r"spacing: [^\n]*", f"spacing: {dx!r}", text, count=1)
    text = re.sub(r"horizon_factor: [^\n]*", f"horizon_factor: {horizon_factor}", text, count=1)
    text = re.sub(r"length: [0-9.]+ mm", f"length: {ld * D0!r}", text, count=1)
    text = re.sub(r'z: "-[0-9.]+"', f'z: "-{speed}"', text, count=1)
    # The anvil: a symmetry plane on the impact face (z = 0, half a cell below the first layer of points), or a
    # penalty plane through the centres of the first layer.
    anvil = ("{name: anvil, point: [0, 0, 0], normal: [0, 0, 1], contact: symmetry}" if contact == "symmetry"
             else f"{{name: anvil, point: [0, 0, {0.5 * dx!r}], normal: [0, 0, 1]}}")
    text = re.sub(r"\{name: anvil, [^\n]*\}", anvil, text, count=1)
    text = re.sub(r"end_time: [^\n]*", f"end_time: {end_time_us} us", text, count=1)
    text = re.sub(r"every: 500", "every: 100000", text, count=1)  # first and last frames only
    return text


def last_frame(exodus_path, with_deformation_gradient=False):
    """Reference positions x, deformed positions y (3 × points) and εp of the last frame (and F, 3 × 3 ×
    points, if asked)."""
    with pr.Results(exodus_path) as res:
        x = res.coords.T
        y = res.positions().T
        eqps = res.field("equivalent_plastic_strain")
        F = (np.array([[res.field(f"deformation_gradient_{a}{b}") for b in "xyz"] for a in "xyz"])
             if with_deformation_gradient else None)
    return x, y, eqps, F


def measure(exodus_path, spacing):
    """Lf/L0; Df/D0 three ways (the area-equivalent diameter of the face layer, the reported one; the outermost
    deformed cell of the face layer; outermost centres + Δx, face layer and widest section); the largest εp."""
    x, y, eqps, F = last_frame(exodus_path, with_deformation_gradient=True)
    first_layer = x[2] < x[2].min() + 0.5 * spacing
    length0 = x[2].max() - x[2].min() + spacing
    length = y[2].max() - y[2].min() + spacing
    r0 = np.hypot(x[0], x[1])
    diameter0 = 2 * r0[first_layer].max() + spacing
    radius = np.hypot(y[0], y[1])
    face = (2 * radius[first_layer].max() + spacing) / diameter0
    widest = (2 * radius.max() + spacing) / diameter0
    # Deformed cell: a point stands for a cube of side Δx around its reference position; the outer face of the
    # cell of a point is Δx/2 from its centre along the reference radial direction e_R, and after the motion it
    # sits at y + F (Δx/2) e_R (F the point's deformation gradient). At t = 0 this is r0 + Δx/2, so the
    # reference diameter is the same 2 max r0 + Δx as above.
    e_r = np.where(r0 > 0, x[:2] / np.where(r0 > 0, r0, 1), 0)
    edge = y[:2] + 0.5 * spacing * np.einsum("abi,bi->ai", F[:2, :2], e_r)
    face_cell = 2 * np.hypot(edge[0], edge[1])[first_layer].max() / diameter0
    # Area-equivalent diameter of the face layer: each point's cell has the horizontal cross-section Δx² at
    # t = 0 and Δx² (F_xx F_yy − F_xy F_yx) after the motion (the z component of the area vector, J F⁻ᵀ e_z);
    # the face's area is their sum, its diameter √(4A/π), normalised by the same at t = 0 (√(4NΔx²/π): the
    # lattice disc, within 0.3 % of D0 at 20 points across). Unlike a maximum it averages over the azimuth, so
    # the lattice's diagonal corners (the outermost centres at 20 across sit at 9.92Δx, not 9.5Δx) do not count.
    cofactor = F[0, 0] * F[1, 1] - F[0, 1] * F[1, 0]
    face_area = cofactor[first_layer].sum() / first_layer.sum()
    with pr.Results(exodus_path) as res:
        damage = res.field("material_damage") if "material_damage" in res.names else np.zeros(len(eqps))
        temperature = res.field("temperature") if "temperature" in res.names else None
    return {"max_t": None if temperature is None else float(temperature.max()),
            "failed": int((damage >= 1).sum()), "max_damage": float(damage.max()),
            "lf": length / length0, "df": float(np.sqrt(face_area)), "face_cell": face_cell, "face_centres": face,
            "widest_centres": widest, "eqps": float(eqps.max())}


def energy_balance(history_path):
    rows = list(csv.DictReader(open(history_path)))
    first, last = rows[0], rows[-1]
    ke0 = float(first["kinetic_energy"])
    total = sum(float(last[k]) for k in ("kinetic_energy", "strain_energy", "dissipated_energy", "hourglass_work"))
    return ((total - float(last["external_work"])) / ke0 - 1, float(last["kinetic_energy"]) / ke0,
            float(last["dissipated_energy"]) / ke0, float(last["hourglass_work"]) / ke0)


def experiment(path):
    shots = []
    for row in csv.DictReader(line for line in open(path) if not line.startswith("#")):
        shots.append({"ld": float(row["L0_over_D0"]), "speed": float(row["U0_m_s"]),
                      "lf": float(row["Lf_over_L0"]), "df": float(row["Df_over_D0"])})
    return shots


# (name, across, horizon factor, L0/D0, speed m/s, end time µs[, hourglass coefficient[, hourglass viscosity]]);
# without them the shot uses --hourglass and --hourglass-viscosity (or, without those, the deck's settings)
SETS = {
    "short": [("short", 8, 3.015, 5, 244, 60)],
    "ld5": [(f"ld5_{v}", 20, 3.015, 5, v, 80) for v in (170, 244, 295)],
    "other": [("ld2_240", 20, 3.015, 2, 240, 60), ("ld10_256", 20, 3.015, 10, 256, 140)],
    # The fastest L0/D0 = 5 shot (the largest strains): 20 and 30 points across at δ = 3.015Δx, 20 across at
    # δ = 4.015Δx. 50 µs: the rod has left the anvil (Df/D0 and Lf/L0 at 50 and 80 µs agree to 2e-4).
    "convergence": [("conv_n20_d3", 20, 3.015, 5, 295, 50), ("conv_n20_d4", 20, 4.015, 5, 295, 50),
                    ("conv_n30_d3", 30, 3.015, 5, 295, 50)],
    # the L0/D0 = 5 shots at 30 points across, to 50 µs (about 25 min each on one core); not part of "all"
    "ld5_n30": [("ld5_n30_170", 30, 3.015, 5, 170, 50), ("ld5_n30_244", 30, 3.015, 5, 244, 50),
                ("conv_n30_d3", 30, 3.015, 5, 295, 50)],
    # 40 points across (252 800 points, 2 356 steps): about 70 min on one core; not part of "all"; with the
    # penalty anvil (--contact penalty) the face runs away here unless damped (convergence40_damped)
    "convergence40": [("conv_n40_d3", 40, 3.015, 5, 295, 50)],
    # 50 across (about 490 000 points): about 2 h on two threads; to 55 µs, so that the face is measured after
    # the symmetry plane has let go (40 across: about 50.3 µs); not part of "all"
    "convergence50": [("conv_n50_d3", 50, 3.015, 5, 295, 55)],
    # the other two L0/D0 = 10 shots of House et al. (235 and 271 m/s; 256 m/s is in "other"), 20 across
    "ld10": [(f"ld10_{v}", 20, 3.015, 10, v, 140) for v in (235, 271)],
    # the 256 m/s L0/D0 = 10 shot at 30 across (214 800 points, 3 534 steps): about 75 min on one core; to
    # 100 µs, since the rod leaves the anvil before (20 across: the anvil's force is 0 from 97.6 µs)
    "ld10_n30": [("ld10_n30_256", 30, 3.015, 10, 256, 100)],
    # 40 across with hourglass dashpots C_HV = 0.05 (with --contact penalty the face layers ring without them):
    # about 85 min on one core
    "convergence40_damped": [("conv_n40_d3_hv", 40, 3.015, 5, 295, 50, 0.02, 0.05)],
    # above the speed at which the L0/D0 = 5 rods of paper 000's experiments failed at the impact end (363 m/s):
    # with --damage the mushroom edge cracks (README, "High-speed failure"); 20 across, to 60 µs
    "failure": [(f"fail_{v}", 20, 3.015, 5, v, 60) for v in (295, 400, 450)],
    # Df/D0 at a fixed horizon δ with Δx refined (δ-convergence), 295 m/s, to 50 µs: δ = 1.525 mm (conv_n20_d4's)
    # at 10 and 15 across, δ = 1.145 mm (conv_n20_d3's) at 15 across, δ = 0.572 mm (conv_n40_d3's) at 30 across
    # and larger horizons at 15 across (δ = 2.025 and 2.532 mm); about 10 min in all
    "horizon": [("fixd_n10_d2", 10, 2.0075, 5, 295, 50), ("fixd_n15_d3", 15, 3.0113, 5, 295, 50),
                ("fixd_n15_d2", 15, 2.2613, 5, 295, 50), ("fixd_n30_d2", 30, 2.2613, 5, 295, 50),
                ("fixd_n15_d4", 15, 4.0, 5, 295, 50), ("fixd_n15_d5", 15, 5.0, 5, 295, 50)],
    # δ = 0.458 mm (conv_n50_d3's) at 30 and 40 across, to 50 µs: at these δ/Δx a point of the face layer next to
    # the axis turns inside out soon after the anvil lets go (50.3 µs at 30 across, 50.7 µs at 40; README)
    "horizon_small": [("fixd_n30_d1", 30, 1.809, 5, 295, 50), ("fixd_n40_d2", 40, 2.412, 5, 295, 50)],
    # δ = 0.344 mm (1.809Δx at 40 across), to 44 µs: a face-layer point next to the axis turns inside out at 44.5 µs
    "horizon_smaller": [("fixd_n40_d1", 40, 1.809, 5, 295, 44)],
    # every shot of the issue at δ = 0.458 mm (1.809Δx, 30 across): about 5 min per L0/D0 = 5 shot on two threads
    "horizon_shots": [("h458_ld5_170", 30, 1.809, 5, 170, 50), ("h458_ld5_244", 30, 1.809, 5, 244, 50),
                      ("fixd_n30_d1", 30, 1.809, 5, 295, 50), ("h458_ld2_240", 30, 1.809, 2, 240, 50),
                      ("h458_ld10_256", 30, 1.809, 10, 256, 95)],
    # the same at 40 across (2.412Δx): with Johnson–Cook, 30 across (1.809Δx) melts the centre of the impact face
    "horizon_shots40": [("h458_n40_ld5_170", 40, 2.412, 5, 170, 50), ("h458_n40_ld5_244", 40, 2.412, 5, 244, 50),
                        ("fixd_n40_d2", 40, 2.412, 5, 295, 50), ("h458_n40_ld2_240", 40, 2.412, 2, 240, 50),
                        ("h458_n40_ld10_256", 40, 2.412, 10, 256, 95)],
    # sensitivity of Df/D0 to the hourglass coefficient (a study, one shot; not a per-shot setting)
    "hourglass": [(f"hg{c}_n20_d3", 20, 3.015, 5, 244, 50, c) for c in (0.01, 0.02, 0.05)],
}
SETS["all"] = SETS["ld5"] + SETS["other"] + SETS["convergence"]
# what taylor.png shows: the five shots at 20 across, δ = 4Δx and 30 across at 295 m/s, L0/D0 = 10 at 30 across
# and 295 m/s at 40 and 50 across (about 7 h on one core; the 50-across run alone about 2 h on two threads)
SETS["figure"] = (SETS["ld5"] + SETS["other"] + SETS["convergence"][1:] + SETS["ld10_n30"] + SETS["convergence40"]
                  + SETS["convergence50"])


def main():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--peridot", required=True)
    p.add_argument("--set", choices=sorted(SETS), default="ld5")
    p.add_argument("--out", default="taylor_runs")
    p.add_argument("--threads", type=int, default=2)
    p.add_argument("--law", choices=("j2_viscoplastic", "johnson_cook"), default="j2_viscoplastic",
                   help="the constitutive law: Foster's J2 fit (the deck's) or Johnson–Cook 6061-T6")
    p.add_argument("--damage", action="store_true",
                   help="add Johnson–Cook damage acting through the influence function (the DAMAGE constants above)")
    p.add_argument("--damage-picture", help="write a figure of the damage on the deformed rod of every shot of the set "
                                            "(one panel each; needs --damage)")
    p.add_argument("--no-thermal", action="store_true",
                   help="without thermal softening (Foster's law as published); the deck's default has it")
    p.add_argument("--hourglass", type=float, help="hourglass coefficient C_HG for every shot (default: the deck's)")
    p.add_argument("--hourglass-viscosity", type=float,
                   help="hourglass dashpots C_HV for every shot (default: none, as in the deck)")
    p.add_argument("--bulk-viscosity", metavar="C_L,C_Q",
                   help="shock (bulk) viscosity for every shot: linear and quadratic coefficients, e.g. 0.06,1.5 "
                        "(default: none, as in the deck)")
    p.add_argument("--contact", choices=("penalty", "symmetry"), default="symmetry",
                   help="the anvil's contact: symmetry (the deck's: a symmetry plane on the impact face; README, "
                        "\"The face layers\") or penalty (a penalty plane through the first layer's centres, the "
                        "earlier versions of this example)")
    p.add_argument("--data", default=os.path.join(HERE, "data", "taylor_6061T6_house1995.csv"),
                   help="the House et al. (1995) shots (default: data/taylor_6061T6_house1995.csv next to this script)")
    p.add_argument("--plot", help="write a figure of Lf/L0 and Df/D0 against the experiment")
    p.add_argument("--profile", help="write a figure of the final profile of one shot of the set (see --profile-shot)")
    p.add_argument("--profile-shot", default="ld5_244", help="the shot drawn by --profile (default ld5_244)")
    p.add_argument("--horizon-plot", metavar="PNG",
                   help="write the figure of Df/D0 against the horizon δ at 295 m/s from the measured runs in "
                        "data/df_against_horizon.csv (README, \"What Df/D0 depends on\") and exit; runs nothing")
    p.add_argument("--reuse", action="store_true", help="measure existing runs instead of running again")
    p.add_argument("--only", help="comma-separated shot names of the set to run (default: all of them)")
    p.add_argument("--check-short", action="store_true",
                   help="exit 1 unless the short run's Lf/L0 is in [0.83, 0.89] and its energy balance within 1 %%")
    a = p.parse_args()
    if a.horizon_plot:
        plot_horizon(os.path.join(HERE, "data", "df_against_horizon.csv"), a.horizon_plot)
        return 0
    template = open(os.path.join(HERE, "deck.yaml")).read()
    deck_hourglass = float(re.search(r"hourglass_coefficient: ([0-9.eE+-]+)", template).group(1))
    shots = experiment(a.data) if os.path.exists(a.data) else []
    results = []
    bulk_viscosity = tuple(float(c) for c in a.bulk_viscosity.split(",")) if a.bulk_viscosity else None
    chosen = [shot for shot in SETS[a.set] if not a.only or shot[0] in a.only.split(",")]
    for name, across, hf, ld, speed, end, *rest in chosen:
        chg = rest[0] if rest else (a.hourglass if a.hourglass is not None else deck_hourglass)
        chv = rest[1] if len(rest) > 1 else a.hourglass_viscosity
        run_dir = os.path.join(os.path.abspath(a.out), name)
        os.makedirs(run_dir, exist_ok=True)
        deck = os.path.join(run_dir, "deck.yaml")
        open(deck, "w").write(make_deck(template, across, hf, ld, speed, end, chg, not a.no_thermal, chv, a.contact, a.law,
                                         a.damage, bulk_viscosity))
        if not (a.reuse and os.path.exists(os.path.join(run_dir, "output", "results.e"))):
            r = subprocess.run([a.peridot, "run", "-q", "-t", str(a.threads), deck], capture_output=True, text=True)
            if r.returncode != 0:
                print(f"{name}: peridot failed ({r.returncode})\n{r.stdout}{r.stderr}")
                return 2
        m = measure(os.path.join(run_dir, "output", "results.e"), D0 / across)
        balance, ke_left, plastic, hourglass = energy_balance(os.path.join(run_dir, "output", "history.csv"))
        match = [s for s in shots if s["ld"] == ld and abs(s["speed"] - speed) < 0.5]
        exp = match[0] if match else None
        results.append(dict(name=name, across=across, hf=hf, ld=ld, speed=speed, chg=chg, balance=balance,
                            ke_left=ke_left, plastic=plastic, hourglass=hourglass, exp=exp, **m))
        line = (f"{name:12s} N={across:2d} δ/Δx={hf:5.3f} C_HG={chg:g} L0/D0={ld:4.1f} v={speed:5.0f} m/s  "
                f"Lf/L0={m['lf']:.4f}  Df/D0={m['df']:.4f} (face area; outermost cell {m['face_cell']:.4f}; centres+Δx: face "
                f"{m['face_centres']:.4f}, widest {m['widest_centres']:.4f})  max εp={m['eqps']:.3f}  energy balance "
                f"{100 * balance:+.2f} % (KE left {100 * ke_left:.2f} %, plastic {100 * plastic:.1f} %, hourglass "
                f"{100 * hourglass:.2f} %)")
        if m["max_t"] is not None:
            line += f"  max T {m['max_t']:.1f} K"
        if a.damage:
            line += f"  max D {m['max_damage']:.3f}, {m['failed']} failed points"
        if exp:
            line += (f"  | exp Lf/L0={exp['lf']:.4f} ({100 * (m['lf'] / exp['lf'] - 1):+.1f} %)"
                     f"  Df/D0={exp['df']:.4f} ({100 * (m['df'] / exp['df'] - 1):+.1f} %)")
        print(line, flush=True)
    with open(os.path.join(os.path.abspath(a.out), f"results_{a.set}.csv"), "w") as f:
        f.write("name,across,horizon_factor,hourglass_coefficient,L0_over_D0,speed_m_s,Lf_over_L0,Df_over_D0,"
                "Df_outer_cell_over_D0,Df_centres_face_over_D0,Df_centres_widest_over_D0,max_eqps,energy_balance,hourglass_work_fraction,"
                "exp_Lf_over_L0,exp_Df_over_D0\n")
        for r in results:
            exp = r["exp"]
            f.write(f"{r['name']},{r['across']},{r['hf']},{r['chg']},{r['ld']},{r['speed']},{r['lf']:.5f},{r['df']:.5f},"
                    f"{r['face_cell']:.5f},{r['face_centres']:.5f},{r['widest_centres']:.5f},{r['eqps']:.4f},{r['balance']:.5f},"
                    f"{r['hourglass']:.5f},{exp['lf'] if exp else ''},{exp['df'] if exp else ''}\n")
    if a.plot:
        plot(results, shots, a.plot, not a.no_thermal)
    if a.profile:
        r = next((r for r in results if r["name"] == a.profile_shot), None)
        if r is None:
            print(f"--profile: shot {a.profile_shot} is not in this run")
            return 2
        plot_profile(os.path.join(os.path.abspath(a.out), r["name"], "output", "results.e"), D0 / r["across"], r,
                     a.profile)
    if a.damage_picture:
        plot_damage([(r, os.path.join(os.path.abspath(a.out), r["name"], "output", "results.e")) for r in results],
                    a.damage_picture)
    if a.check_short:
        r = results[0]
        ok = 0.83 <= r["lf"] <= 0.89 and abs(r["balance"]) < 0.01
        print(("ok" if ok else "FAIL") + f": short rod Lf/L0 = {r['lf']:.4f} (band [0.83, 0.89]), energy balance "
              f"{100 * r['balance']:+.2f} %")
        return 0 if ok else 1
    return 0


def plot(results, shots, path, thermal=True):
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
        for r in results:
            marker = "*" if r["across"] >= 40 else "x" if r["across"] == 20 and r["hf"] < 3.5 else "+"
            ax.plot(r["speed"], r[key], marker, ms=9, color=colours.get(r["ld"], "k"))
        ax.set_xlabel("impact speed (m/s)")
        ax.set_ylabel(label)
        ax.grid(alpha=0.3)
    axes[0].legend(fontsize=7)
    heating = "thermal softening" if thermal else "no heating"
    axes[0].set_title(f"Peridot, C_HG = {results[0]['chg']:g}, {heating}\nx: 20 across, δ = 3Δx; "
                      "+: 30 across or δ = 4Δx; *: 40 and 50 across", fontsize=8)
    axes[1].set_title("Df: area-equivalent diameter of the face layer", fontsize=9)
    fig.tight_layout()
    fig.savefig(path, dpi=120)


def plot_horizon(data_path, path):
    """Df/D0 and the largest εp against the horizon δ (log scale), one marker per run, coloured by the points across
    the diameter; the runs at δ = 3.015Δx joined by a line, and the runs at one δ and different Δx side by side."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    rows = list(csv.DictReader(line for line in open(data_path) if not line.startswith("#")))
    fig, axes = plt.subplots(1, 2, figsize=(10, 4.2))
    colours = {10: "C0", 15: "C1", 20: "C2", 30: "C3", 40: "C4", 50: "C5"}
    limits = {"Df_over_D0": (1.2, 1.85), "max_eqps": (0.6, 2.2)}
    for ax, key, label in ((axes[0], "Df_over_D0", "Df/D0"), (axes[1], "max_eqps", "largest εp")):
        measured = [r for r in rows if r[key]]
        fixed_m = sorted((float(r["horizon_mm"]), float(r[key])) for r in measured
                         if abs(float(r["horizon_factor"]) - 3.015) < 1e-3 and r["law"] == "j2_viscoplastic")
        ax.plot(*zip(*fixed_m), "-", color="0.6", lw=1, zorder=1, label="J2, δ = 3.015Δx (Δx and δ refined together)")
        for r in measured:
            m, value, colour = float(r["horizon_factor"]), float(r[key]), colours.get(int(r["across"]), "k")
            if r["law"] == "johnson_cook":  # crosses, off-scale values (a thermal runaway) drawn at the top edge
                top = limits[key][1]
                ax.plot(float(r["horizon_mm"]), min(value, top), "X", color=colour, ms=9, zorder=3)
                if value > top:
                    ax.annotate(f"JC {r['across']} across: {value:g}\n(melting, off scale)",
                                (float(r["horizon_mm"]), top), textcoords="offset points", xytext=(6, -22), fontsize=7)
                continue
            marker = "v" if m < 2.0 else "s" if m < 2.5 else "o" if m < 3.5 else "^"
            ax.plot(float(r["horizon_mm"]), value, marker, color=colour, ms=7,
                    mfc="none" if m < 2.5 else colour, zorder=2)
        ax.set_ylim(*limits[key])
        ax.set_xscale("log")
        ax.set_xticks([0.3, 0.5, 0.7, 1, 1.5, 2, 3])
        ax.set_xticklabels(["0.3", "0.5", "0.7", "1", "1.5", "2", "3"])
        ax.minorticks_off()
        ax.set_xlim(0.25, 3)
        ax.set_xlabel("horizon δ (mm)")
        ax.set_ylabel(label)
        ax.grid(alpha=0.3)
    axes[0].axhline(1.7775, color="k", ls="--", lw=1, label="House et al. 1995 (shot at 295 m/s)")
    for n, c in colours.items():
        axes[0].plot([], [], "o", color=c, label=f"{n} points across")
    axes[0].plot([], [], "X", color="0.3", ms=8, label="Johnson–Cook")
    axes[0].legend(fontsize=7, loc="lower left", ncol=2)
    axes[0].set_title("Taylor rod, L0/D0 = 5, 295 m/s, J2 viscoplastic (Foster) and Johnson–Cook (X), symmetry anvil\n"
                      "J2 markers: ▼ δ = 1.8Δx, □ 2.0–2.4Δx, ● 3Δx, ▲ 4–5Δx", fontsize=8)
    axes[1].set_title("largest equivalent plastic strain (centre of the impact face)", fontsize=8)
    fig.tight_layout()
    fig.savefig(path, dpi=120)


def plot_profile(exodus_path, spacing, result, path):
    """The final rod beside its initial outline: the row of points at y = Δx/2 (reference), coloured by εp,
    and the outer radius of every reference layer against the deformed height, with the experiment's Lf and
    Df marked."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    x, y, eqps, _ = last_frame(exodus_path)
    mm = 1e3
    fig, (side, outline) = plt.subplots(1, 2, figsize=(10, 5.5), gridspec_kw={"width_ratios": [1.2, 1]})
    slab = np.abs(x[1] - 0.5 * spacing) < 0.25 * spacing  # the lattice row next to the axis plane y = 0
    sc = side.scatter(y[0][slab] * mm, y[2][slab] * mm, c=eqps[slab], s=6, cmap="viridis")
    fig.colorbar(sc, ax=side, label="equivalent plastic strain")
    L0, R0 = x[2].max() + 0.5 * spacing, np.hypot(x[0], x[1]).max() + 0.5 * spacing
    side.plot(np.array([-R0, -R0, R0, R0]) * mm, np.array([L0, 0, 0, L0]) * mm, "k--", lw=0.8, label="initial rod")
    side.set_aspect("equal")
    side.set_xlabel("x (mm)")
    side.set_ylabel("z (mm), anvil at z = 0")
    side.legend(fontsize=8, loc="upper right")
    side.set_title(f"L0/D0 = {result['ld']:g}, {result['speed']:g} m/s: the points at y = Δx/2, last frame", fontsize=9)
    layer = np.rint(x[2] / spacing - 0.5).astype(int)
    heights, radii = [], []
    for k in np.unique(layer):
        m = layer == k
        r0 = np.hypot(x[0][m], x[1][m])
        outer = r0 >= r0.max() - 1e-12  # the outermost reference ring of the layer
        heights.append(y[2][m].mean())
        radii.append(np.hypot(y[0][m], y[1][m])[outer].mean() + 0.5 * spacing)
    outline.plot(np.array(radii) * mm, np.array(heights) * mm, "C1-", label="Peridot: outermost ring + Δx/2")
    outline.plot([R0 * mm, R0 * mm], [0, L0 * mm], "k--", lw=0.8, label="initial radius")
    exp = result.get("exp")
    if exp:
        outline.axhline(exp["lf"] * L0 * mm, color="C0", lw=0.8, label=f"experiment Lf/L0 = {exp['lf']:.3f}")
        outline.plot([exp["df"] * D0 / 2 * mm], [0], "o", color="C0", mfc="none", ms=9,
                     label=f"experiment Df/D0 = {exp['df']:.3f}")
    outline.plot([result["df"] * D0 / 2 * mm], [0], "x", color="C1", ms=9,
                 label=f"Peridot Df/D0 = {result['df']:.3f} (face area)")
    outline.set_xlabel("radius (mm)")
    outline.set_ylabel("deformed height (mm)")
    outline.set_xlim(0, None)
    outline.grid(alpha=0.3)
    outline.legend(fontsize=7)
    outline.set_title(f"Lf/L0 = {result['lf']:.4f}; outer radius per layer", fontsize=9)
    fig.tight_layout()
    fig.savefig(path, dpi=120)



def plot_damage(runs, path):
    """Damage on the deformed rods: the points of the half rod y ≥ 0 seen from the side (x, z deformed), coloured
    by D, the failed points (D = 1, flown free) in red; one panel per run."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, axes = plt.subplots(1, len(runs), figsize=(5 * len(runs), 5), squeeze=False)
    for ax, (result, exodus) in zip(axes[0], runs):
        with pr.Results(exodus) as res:
            x = res.coords.T
            y = res.positions().T
            D = res.field("material_damage")
        mm = 1e3
        half = x[1] >= 0
        order = np.argsort(-y[1][half])  # nearest the viewer (largest y) drawn last
        xs, zs, ds = y[0][half][order[::-1]], y[2][half][order[::-1]], D[half][order[::-1]]
        alive = ds < 1
        sc = ax.scatter(xs[alive] * mm, zs[alive] * mm, c=ds[alive], s=4, cmap="viridis", vmin=0, vmax=1)
        outside = (np.abs(y[0]) > 1.6 * D0) | (y[2] > 0.45 * x[2].max())
        ax.scatter(xs[~alive] * mm, zs[~alive] * mm, s=4, c="red",
                   label=f"failed (D = 1): {(D >= 1).sum()} of {len(D)} points; {int(outside.sum())} outside the frame")
        ax.set_aspect("equal")
        # the rod's lower part; failed points thrown further are counted in the legend, not drawn to scale
        ax.set_xlim(-1.6 * D0 * mm, 1.6 * D0 * mm)
        ax.set_ylim(-1, 0.45 * (x[2].max()) * mm)
        ax.set_xlabel("x (mm)")
        ax.set_ylabel("z (mm), anvil at z = 0")
        ax.legend(fontsize=7, loc="upper right")
        ax.set_title(f"{result['speed']:g} m/s, L0/D0 = {result['ld']:g}, {result['across']} across: half rod y ≥ 0",
                     fontsize=9)
        fig.colorbar(sc, ax=ax, label="Johnson–Cook damage D")
    fig.tight_layout()
    fig.savefig(path, dpi=120)


if __name__ == "__main__":
    sys.exit(main())
