#!/usr/bin/python3
"""Runs every example deck (shortened to --steps steps, a frame and a history row every 10) and every
regression deck with 1 and 2 threads and on 2 MPI ranks, and keeps their Exodus files and histories, so
that two builds can be compared byte for byte (a refactoring that must not move a bit):

    tools/output_snapshot.py run --peridot build_old/peridot --out /tmp/before
    tools/output_snapshot.py run --peridot build/peridot --out /tmp/after
    tools/output_snapshot.py compare /tmp/before /tmp/after

`compare` lists every file it compared and exits 1 when one differs or is missing."""
import argparse
import filecmp
import glob
import os
import re
import subprocess
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
SOURCE = os.path.dirname(HERE)


def decks():
    found = sorted(glob.glob(os.path.join(SOURCE, "examples", "*", "deck*.yaml")))
    found += sorted(glob.glob(os.path.join(SOURCE, "tests", "regression", "decks", "*.yaml")))
    return found


def shortened(text, steps):
    if re.search(r"(?m)^\s+type: relaxation", text):  # quasi-static: a loose tolerance keeps it short
        text = re.sub(r"(?m)^(\s+)tolerance: .*$", r"\g<1>tolerance: 1e-4", text)
        return re.sub(r"every: *\d+", "every: 1", text)
    text = re.sub(r"(?m)^(\s+)end_time: .*$", rf"\g<1>num_steps: {steps}", text)
    text = re.sub(r"(?m)^(\s+)num_steps: .*$", rf"\g<1>num_steps: {steps}", text)
    return re.sub(r"every: *\d+", "every: 10", text)


def run(a):
    env = dict(os.environ, OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1", OMP_NUM_THREADS="1")
    os.makedirs(a.out, exist_ok=True)
    failed = 0
    for deck in decks():
        name = os.path.basename(os.path.dirname(deck)) + "_" + os.path.splitext(os.path.basename(deck))[0]
        # Beside the original, so that point files and relative paths resolve as they do there.
        path = os.path.join(os.path.dirname(deck), f".snapshot_{os.path.basename(deck)}")
        open(path, "w").write(shortened(open(deck).read(), a.steps))
        try:
            for mode in ("t1", "t2", "np2"):
                out = os.path.join(os.path.abspath(a.out), name, mode)
                cmd = [a.peridot, "run", "-q", "-o", out, path]
                if mode == "t2":
                    cmd += ["-t", "2"]
                if mode == "np2":
                    cmd = ["mpirun", "--oversubscribe", "-np", "2"] + cmd
                r = subprocess.run(cmd, capture_output=True, text=True, env=env, timeout=1800)
                if mode == "np2" and r.returncode == 0:  # the ranks' Exodus pieces NAME.2.r, merged into NAME
                    for piece in sorted(glob.glob(os.path.join(out, "*.2.0"))):
                        joined = subprocess.run([a.peridot, "join", piece[:-len(".2.0")]], capture_output=True, text=True)
                        if joined.returncode != 0:
                            r = joined
                print(("ok   " if r.returncode == 0 else "FAIL ") + f"{name} {mode}", flush=True)
                if r.returncode != 0:
                    failed += 1
                    print(r.stdout + r.stderr)
        finally:
            os.remove(path)
    return 1 if failed else 0


def compare(a):
    def outputs(root):
        return sorted(os.path.relpath(p, root) for p in glob.glob(os.path.join(root, "**", "*"), recursive=True)
                      if p.endswith((".e", ".csv")))
    before, after = outputs(a.before), outputs(a.after)
    different = 0
    for f in sorted(set(before) | set(after)):
        if f not in before or f not in after:
            print(f"MISSING {f}")
            different += 1
            continue
        same = filecmp.cmp(os.path.join(a.before, f), os.path.join(a.after, f), shallow=False)
        print(("same " if same else "DIFF ") + f)
        different += not same
    print(f"{len(before)} files compared, {different} differ or are missing")
    return 1 if different or not before else 0


def main():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    sub = p.add_subparsers(dest="command", required=True)
    r = sub.add_parser("run")
    r.add_argument("--peridot", required=True)
    r.add_argument("--out", required=True)
    r.add_argument("--steps", type=int, default=60)
    c = sub.add_parser("compare")
    c.add_argument("before")
    c.add_argument("after")
    a = p.parse_args()
    return run(a) if a.command == "run" else compare(a)


if __name__ == "__main__":
    sys.exit(main())
