#!/usr/bin/python3
"""High-rate tension of 6061-T6 (Foster, Silling & Chen 2010, §10, Figure 2): the figure and the comparison
numbers of the gtest CorrespondenceSolver.HighRateTensionFollowsTheMaterialPointDriver
(tests/verification/correspondence_solver_test.cpp: a 4 mm round bar, 12 mm long, pulled from both ends at
8300 /s nominal; J2 viscoplastic, Foster's parameters).

Runs that gtest with PERIDOT_TENSION_CSV set (it then writes its curves), and plots true stress against the
Green–Lagrange strain E_zz (eq 62) for
  * the peridynamic gauge section: the cross-section through the bar's centre (two layers of points), its
    volume-weighted mean σ_zz (axial force over current area) against its mean E_zz, raw and 1 µs-averaged;
  * the material-point driver in uniaxial stress at the gauge section's true strain rate (the grips make the
    gauge strain at about twice the nominal rate: 16 700 /s);
  * the digitized experiment at 8000 /s (Lesuer, tests/data/experiments/al6061T6_stress_strain_digitized.csv;
    tests/data/experiments/README.md says where the numbers come from).
    Its strain measure is not recorded (true or engineering): it is drawn as given, and also converted to
    E = (exp(2ε) − 1)/2 as if it were a true (logarithmic) strain.
Prints the comparison numbers (docs/correspondence.md quotes them). Exits 1 unless the gauge section's
averaged true stress is within 3 % of the driver beyond E_zz = 0.01 (the issue's target; no necking occurs in
this run). The experiment is compared, not asserted: it is a band (digitized, SHPB ring-up below 5 % strain).

    /usr/bin/python3 tests/verification/test_high_rate_tension.py --peridot build/peridot --source . \\
        --work build/tests/py_test_high_rate_tension [--plot docs/figures/high_rate_tension.png]

ctest runs it as py.test_high_rate_tension (about 7 s on one core); the gtest binary is found next to
--peridot (build/tests/peridot_tests) unless --tests names it.
"""
import argparse
import csv
import os
import subprocess
import sys

import numpy as np

GTEST = "CorrespondenceSolver.HighRateTensionFollowsTheMaterialPointDriver"


def read_run(path):
    rows, driver = [], []
    with open(path) as f:
        lines = f.readlines()
    for line in lines:
        if line.startswith("#D,"):
            driver.append([float(v) for v in line[3:].split(",")])
    data = [line for line in lines if not line.startswith("#")]
    rows = list(csv.DictReader(data))
    return rows, np.array(driver)


def column(rows, key):
    return np.array([float(r[key]) if r[key] != "" else np.nan for r in rows])


def experiment(path, rate=8000):
    pts = []
    for r in csv.DictReader(line for line in open(path) if not line.startswith("#")):
        if r["source_label"] == "Lesuer" and float(r["strain_rate_per_s"]) == rate:
            pts.append((float(r["strain"]), float(r["stress_MPa"]) * 1e6))
    return np.array(sorted(pts))


def main():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--peridot", required=True, help="the peridot program; peridot_tests is looked for beside it")
    p.add_argument("--source", default=os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", ".."))
    p.add_argument("--work", default="high_rate_tension")
    p.add_argument("--tests", help="the GoogleTest program (default: tests/peridot_tests beside --peridot)")
    p.add_argument("--data", help="digitized curves (default: tests/data/experiments/al6061T6_stress_strain_digitized.csv)")
    p.add_argument("--plot", help="the PNG (default: WORK/high_rate_tension.png)")
    a = p.parse_args()
    tests = a.tests or os.path.join(os.path.dirname(os.path.abspath(a.peridot)), "tests", "peridot_tests")
    data = a.data or os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "data", "experiments",
                                  "al6061T6_stress_strain_digitized.csv")
    os.makedirs(a.work, exist_ok=True)
    curves = os.path.join(os.path.abspath(a.work), "tension.csv")
    env = dict(os.environ, PERIDOT_TENSION_CSV=curves, OMP_NUM_THREADS=os.environ.get("OMP_NUM_THREADS", "1"))
    r = subprocess.run([tests, f"--gtest_filter={GTEST}"], env=env, capture_output=True, text=True)
    print("\n".join(line for line in r.stdout.splitlines() if line.startswith("measured")))
    if r.returncode != 0:
        print(f"FAIL: {GTEST} failed ({r.returncode})\n{r.stdout}{r.stderr}")
        return 1
    rows, driver = read_run(curves)
    e_raw, s_raw = column(rows, "section_Ezz"), column(rows, "section_szz")
    e, s, d = column(rows, "section_Ezz_avg"), column(rows, "section_szz_avg"), column(rows, "driver_at_section_Ezz_avg")
    ok = np.isfinite(e) & (e >= 0.01)
    rel = s[ok] / d[ok] - 1
    worst = float(np.abs(rel).max())
    print(f"gauge section (1 µs means) vs driver, E_zz from 0.01 to {e[ok].max():.3f}: worst {100 * worst:.2f} % "
          f"(at E_zz = {e[ok][np.abs(rel).argmax()]:.3f}), mean {100 * rel.mean():+.2f} %")

    exp = experiment(data) if os.path.exists(data) else np.zeros((0, 2))
    if len(exp):
        # beyond the ring-up (5 %) and within the run's strain range
        # beyond the ring-up (5 %) and within the run's strain range; the dip of the record between 5 and 10 %
        # (a ring-up oscillation) apart from the rest
        top = min(e[ok].max(), driver[:, 0].max())
        for label, strain in (("as given", exp[:, 0]), ("as true strain -> E", 0.5 * (np.exp(2 * exp[:, 0]) - 1))):
            for lo, hi in ((0.05, 0.10), (0.10, top)):
                sel = (strain >= lo) & (strain < hi)
                drv = np.interp(strain[sel], driver[:, 0], driver[:, 1])
                pd = np.interp(strain[sel], e[ok], s[ok])
                rd, rp = drv / exp[sel, 1] - 1, pd / exp[sel, 1] - 1
                print(f"digitized 8000 /s, strain {label}, E in [{lo:.2f}, {hi:.3f}) ({sel.sum()} points): driver "
                      f"{100 * rd.mean():+.1f} % mean ({100 * rd.min():+.1f} … {100 * rd.max():+.1f} %), gauge section "
                      f"{100 * rp.mean():+.1f} % mean ({100 * rp.min():+.1f} … {100 * rp.max():+.1f} %)")
    else:
        print(f"digitized curves not found at {data}: plotted without them")

    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, ax = plt.subplots(figsize=(6.4, 4.4))
    ax.plot(e_raw, s_raw / 1e6, color="C0", lw=0.6, alpha=0.35, label="peridynamic gauge section (every step)")
    ax.plot(e[np.isfinite(e)], s[np.isfinite(e)] / 1e6, color="C0", lw=2, label="peridynamic gauge section (1 µs mean)")
    ax.plot(driver[:, 0], driver[:, 1] / 1e6, "k--", lw=1.2, label="material-point driver (uniaxial stress)")
    if len(exp):
        ax.plot(exp[:, 0], exp[:, 1] / 1e6, "o", ms=3.5, mfc="none", color="C3",
                label="experiment 8000 /s (Lesuer, digitized; strain as given)")
        ax.plot(0.5 * (np.exp(2 * exp[:, 0]) - 1), exp[:, 1] / 1e6, ":", color="C3", lw=1,
                label="same, strain read as true strain, converted to E")
    ax.set_xlabel("Green–Lagrange strain E_zz")
    ax.set_ylabel("true stress (MPa)")
    ax.set_xlim(0, 0.3)
    ax.set_ylim(0, 550)
    ax.grid(alpha=0.3)
    ax.legend(fontsize=7, loc="lower right")
    ax.set_title("6061-T6, 8300 /s nominal (gauge ≈ 16 700 /s), J2 viscoplastic, correspondence", fontsize=8)
    fig.tight_layout()
    out = a.plot or os.path.join(a.work, "high_rate_tension.png")
    fig.savefig(out, dpi=120)
    print(f"wrote {out}")
    if worst >= 0.03:
        print(f"FAIL: gauge-section true stress {100 * worst:.2f} % from the driver (target 3 %)")
        return 1
    print("ok")
    return 0


if __name__ == "__main__":
    sys.exit(main())
