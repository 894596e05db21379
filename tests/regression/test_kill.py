#!/usr/bin/python3
"""A run killed with SIGKILL at any moment leaves every file it had written readable, up to its last
complete frame, and the finished results of an earlier run untouched.

Runs tests/regression/decks/exodus_small.yaml once to the end, then KILLS times again with a step count too
large to finish, each killed with SIGKILL after a random delay (fixed seed, so the same delays every time).
After each kill: the finished small.e and history.csv are byte for byte as before; small.e.partial (when the
run got that far) opens with netCDF4, its times increase, and every nodal variable of every frame it counts is
finite (no fill values: a frame is counted only once its values are written); every line of
history.csv.partial has all its columns. Exits 1 if any check fails.
"""
import argparse
import os
import random
import re
import shutil
import signal
import subprocess
import sys
import time

import netCDF4
import numpy as np

KILLS = 20
SEED = 20261203


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("--peridot", required=True)
    parser.add_argument("--source", required=True)
    parser.add_argument("--work", required=True)
    a = parser.parse_args()
    shutil.rmtree(a.work, ignore_errors=True)
    os.makedirs(a.work)
    out = os.path.join(a.work, "out")
    small = os.path.join(a.source, "tests", "regression", "decks", "exodus_small.yaml")
    failures = []

    def check(ok, what):
        print(("ok   " if ok else "FAIL ") + what)
        if not ok:
            failures.append(what)

    env = dict(os.environ, OMP_NUM_THREADS="1")
    done = subprocess.run([a.peridot, "run", "-q", "-o", out, small], env=env, capture_output=True, text=True)
    check(done.returncode == 0, f"the finished run exits 0 ({done.stderr.strip()[-200:]})")
    finished = {name: open(os.path.join(out, name), "rb").read() for name in ("small.e", "history.csv")}

    deck = os.path.join(a.work, "long.yaml")
    with open(deck, "w") as f:
        f.write(re.sub(r"num_steps: 120", "num_steps: 100000000", open(small).read()))

    # Delays from before the first file exists to well into the run (a frame every 10 steps).
    rng = random.Random(SEED)
    delays = sorted(rng.uniform(0.0, 1.5) for _ in range(KILLS))
    frames_seen = 0
    for k, delay in enumerate(delays):
        run = subprocess.Popen([a.peridot, "run", "-q", "-o", out, deck], env=env,
                               stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
        time.sleep(delay)
        run.send_signal(signal.SIGKILL)
        run.wait()
        what = f"kill {k + 1} after {delay:.3f} s"
        for name, data in finished.items():
            check(open(os.path.join(out, name), "rb").read() == data, f"{what}: finished {name} untouched")
        exodus = os.path.join(out, "small.e.partial")
        if os.path.exists(exodus) and os.path.getsize(exodus) > 0:
            try:
                with netCDF4.Dataset(exodus) as d:
                    times = np.asarray(d["time_whole"][:])
                    finite = all(np.isfinite(np.ma.filled(d[v][:], np.nan)).all()
                                 for v in d.variables if v.startswith("vals_nod_var"))
                    increasing = bool(np.all(np.diff(times) > 0))
                check(finite and increasing, f"{what}: small.e.partial readable, {len(times)} frames, "
                                             f"times increasing, every value finite")
                frames_seen += len(times) > 0
            except (OSError, RuntimeError) as e:
                check(False, f"{what}: small.e.partial unreadable: {e}")
        history = os.path.join(out, "history.csv.partial")
        if os.path.exists(history):
            lines = open(history).read().splitlines()
            columns = len(lines[0].split(",")) if lines else 0
            whole = all(len(line.split(",")) == columns and all(np.isfinite(float(x)) for x in line.split(","))
                        for line in lines[1:])
            check(columns > 0 and whole, f"{what}: history.csv.partial has {len(lines) - 1} whole rows")
    check(frames_seen >= KILLS // 2, f"{frames_seen} of {KILLS} kills came after frames were written")
    if failures:
        print(f"{len(failures)} checks failed")
        sys.exit(1)
    print("all checks passed")


if __name__ == "__main__":
    main()
