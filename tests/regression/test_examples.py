#!/usr/bin/python3
"""Examples double as smoke tests: every examples/*/deck.yaml passes `peridot check`, and the quickstart
runs to the end with a crack that runs (the damage probe ahead of the pre-crack tip reaches 0.5 and the
plate keeps its momentum balance: the two grips pull symmetrically, so the net y momentum stays ~0)."""
import argparse
import csv
import glob
import os
import subprocess
import sys


def main():
    p = argparse.ArgumentParser()
    p.add_argument("--peridot", required=True)
    p.add_argument("--source", required=True)
    p.add_argument("--work", required=True)
    a = p.parse_args()
    os.makedirs(a.work, exist_ok=True)
    passed = failed = 0

    def check(ok, what):
        nonlocal passed, failed
        print(("ok   " if ok else "FAIL ") + what)
        passed, failed = passed + bool(ok), failed + (not ok)

    decks = sorted(glob.glob(os.path.join(os.path.abspath(a.source), "examples", "*", "deck*.yaml")))
    check(len(decks) >= 1, f"{len(decks)} example decks found")
    for deck in decks:
        r = subprocess.run([a.peridot, "check", deck], capture_output=True, text=True)
        check(r.returncode == 0, f"peridot check {os.path.relpath(deck, a.source)}" + ("" if r.returncode == 0 else "\n" + r.stderr))

    quickstart = os.path.join(os.path.abspath(a.source), "examples", "quickstart", "deck.yaml")
    out = os.path.join(a.work, "quickstart")
    r = subprocess.run([a.peridot, "run", "-q", "-o", out, quickstart], capture_output=True, text=True, timeout=600)
    check(r.returncode == 0, "quickstart runs" + ("" if r.returncode == 0 else "\n" + r.stderr))
    if r.returncode == 0:
        rows = list(csv.DictReader(open(os.path.join(out, "history.csv"))))
        last = rows[-1]
        check(float(last["crack_tip_damage"]) > 0.5, f"the crack runs: damage {last['crack_tip_damage']} 5 mm ahead of the pre-crack tip")
        check(float(last["max_damage"]) == 1.0, "some points lost every bond")
        momentum = max(abs(float(row["momentum_y"])) for row in rows)
        check(momentum < 1e-9, f"net y momentum stays ~0 (max {momentum:.3g} kg m/s)")
        for name in ("quickstart.e", "resolved_deck.yaml", "run.log"):
            check(os.path.getsize(os.path.join(out, name)) > 0, f"{name} written")
    print(f"{passed} passed, {failed} failed")
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
