#!/usr/bin/python3
"""Checkpoint and restart (issue: reliability). For every model, damage criterion, solver and contact:
a run writes checkpoints (output.checkpoint every 7 steps, off the output schedules on purpose); a restart from
one in the middle, into a folder holding the finished run's results, must leave every output (Exodus file,
history, resolved deck) byte-identical to the uninterrupted run's. Distributed: checkpoints of a serial run
restart on 2 ranks, those of a 2-rank run on 3 ranks and of a 4-rank run on 4 (each rank reading only the pieces
near its points), with the same bytes as the serial run (the Exodus
frames carried over from the serial file, or from the 2-rank run's pieces, into the new run's pieces, merged
by `peridot join` for the comparison); a 2-rank run stopped by SIGTERM continues on 3 ranks. A run stopped
by SIGTERM writes a checkpoint at its last step and its .partial results; the restart continues them to the
same bytes. A checkpoint of another deck, of a changed deck, truncated, corrupt, of another code version or
beyond the end is refused with exit 2 and nothing written."""
import argparse
import filecmp
import os
import re
import shutil
import signal
import subprocess
import sys
import time

import netCDF4
import yaml

from exodus_pieces import join_all, piece_sets

EVERY = 7  # steps between checkpoints: off the output schedules on purpose

DECKS = [  # (deck, [(ranks that write, ranks that restart)], steps between checkpoints)
    ("examples/quickstart/deck.yaml", [(1, 2), (2, 3)], EVERY),                   # pmb 2D, pre-crack, probes
    ("tests/regression/decks/exodus_small.yaml", [], EVERY),                      # lps 2D with damage, jitter
    ("tests/regression/decks/inelastic_small.yaml", [(2, 3)], EVERY),             # lps_plastic | lps_viscoelastic
    ("tests/regression/decks/correspondence_small.yaml", [], EVERY),              # correspondence
    ("tests/regression/decks/mpi_symmetry_wall.yaml", [(2, 3)], EVERY),           # correspondence J2, symmetry released
    ("tests/regression/decks/jc_damage_small.yaml", [(1, 2), (4, 4)], 37),        # Johnson–Cook damage, bonds breaking
    ("tests/regression/decks/relaxation_notch.yaml", [(1, 2)], 1),  # dynamic relaxation, bonds breaking
    ("tests/regression/decks/implicit_notch.yaml", [], 1),  # Newton–Krylov (bitwise on one rank only: test_mpi.py)
    ("tests/regression/decks/thermoviscoelastic_small.yaml", [(2, 3)], 3),  # thermoviscoelastic, stepped loads
    ("tests/regression/decks/energy_failure_small.yaml", [(1, 2)], EVERY),        # energy criterion
    ("tests/regression/decks/surface_correction_small.yaml", [], EVERY),          # surface correction
    ("tests/regression/decks/mpi_contact.yaml", [(1, 2), (2, 3)], EVERY),         # contact, friction, free rigid ball
]



def main():
    p = argparse.ArgumentParser()
    p.add_argument("--peridot", required=True)
    p.add_argument("--source", required=True)
    p.add_argument("--work", required=True)
    p.add_argument("--mpirun", default=shutil.which("mpirun") or "mpirun")
    a = p.parse_args()
    shutil.rmtree(a.work, ignore_errors=True)
    os.makedirs(a.work)
    env = dict(os.environ, OMP_NUM_THREADS="1", OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1",
               OMPI_MCA_rmaps_base_oversubscribe="1")
    passed = failed = 0

    def check(ok, what):
        nonlocal passed, failed
        print(("ok   " if ok else "FAIL ") + what, flush=True)
        passed, failed = passed + bool(ok), failed + (not ok)
        return ok

    def peridot(args, ranks=1, timeout=600):
        cmd = [a.peridot] + args if ranks == 1 else [a.mpirun, "--oversubscribe", "-np", str(ranks), a.peridot] + args
        return subprocess.run(cmd, capture_output=True, text=True, env=env, timeout=timeout)

    def results(folder, pieces=False):
        """The result files (and with `pieces` the Exodus pieces of a distributed run)."""
        sets = piece_sets(folder)
        is_piece = lambda f: any(f.startswith(name + f".{n}.") for name, n in sets.items())
        return sorted(f for f in os.listdir(folder)
                      if f != "run.log" and not f.startswith("checkpoint_") and (pieces or not is_piece(f)))

    def same_results(mine, reference):
        """Every result file of reference byte-identical in mine (the resolved deck names its own folder); a
        distributed run's Exodus pieces merged first."""
        ok, why = join_all(a.peridot, mine, env)
        if not ok:
            return why
        names = results(reference)
        if results(mine) != names:
            return f"files {results(mine)} != {names}"
        for f in names:
            x, y = os.path.join(mine, f), os.path.join(reference, f)
            if f == "resolved_deck.yaml":
                if open(x).read().replace(mine, reference) != open(y).read():
                    return f + " differs"
            elif not filecmp.cmp(x, y, shallow=False):
                return f + " differs"
        return ""

    def restart_into(reference, checkpoint, deck, out, ranks):
        """A folder holding reference's results (a finished run), restarted from checkpoint on `ranks` ranks."""
        shutil.rmtree(out, ignore_errors=True)
        os.makedirs(out)
        for f in results(reference, pieces=True):
            if f != "resolved_deck.yaml":
                shutil.copy(os.path.join(reference, f), out)
        return peridot(["run", "-q", "-o", out, deck, "--restart", checkpoint], ranks)

    def with_checkpoints(deck, name, every):
        text = yaml.safe_load(open(deck))
        text.setdefault("output", {})["checkpoint"] = {"every": every, "keep": 1000}
        copy = os.path.join(a.work, name + ".yaml")
        yaml.safe_dump(text, open(copy, "w"), sort_keys=False, allow_unicode=True)
        return copy

    def checkpoints(folder):
        """The steps of the checkpoints in folder: checkpoint_<step>.nc, or a distributed run's pieces of it."""
        names = [re.match(r"checkpoint_(\d+)\.nc(\.\d+\.\d+)?$", f) for f in os.listdir(folder)]
        return sorted({int(m.group(1)) for m in names if m})

    full_quick = os.path.join(a.work, "quickstart", "full")
    for source, distributed, every in DECKS:
        name = os.path.basename(os.path.dirname(source)) if source.endswith("/deck.yaml") else os.path.splitext(os.path.basename(source))[0]
        deck = with_checkpoints(os.path.join(a.source, source), name, every)
        full = os.path.join(a.work, name, "full")
        r = peridot(["run", "-q", "-o", full, deck])
        if not check(r.returncode == 0, f"{name}: the uninterrupted run" + ("" if r.returncode == 0 else "\n" + r.stderr)):
            continue
        steps = checkpoints(full)
        middle = steps[len(steps) // 2 - 1] if len(steps) > 1 else steps[0]
        cp = os.path.join(full, f"checkpoint_{middle}.nc")
        out = os.path.join(a.work, name, "restarted")
        r = restart_into(full, cp, deck, out, 1)
        why = r.stderr if r.returncode else same_results(out, full)
        check(not why, f"{name}: restarted at step {middle} of {steps[-1]}, every output byte-identical {why}")
        if name == "quickstart":  # on another number of threads
            out = os.path.join(a.work, name, "threads")
            shutil.rmtree(out, ignore_errors=True)
            shutil.copytree(full, out, ignore=shutil.ignore_patterns("checkpoint_*", "run.log", "resolved_deck.yaml"))
            r = peridot(["run", "-q", "-t", "2", "-o", out, deck, "--restart", cp])
            why = r.stderr if r.returncode else same_results(out, full)
            check(not why, f"{name}: restarted on 2 threads, byte-identical {why}")
        for writers, readers in distributed:
            if writers == 1:
                written = cp
            else:
                wrote = os.path.join(a.work, name, f"np{writers}")
                r = peridot(["run", "-q", "-o", wrote, deck], writers)
                if not check(r.returncode == 0, f"{name}: run on {writers} ranks {r.stderr}"):
                    continue
                written = os.path.join(wrote, f"checkpoint_{middle}.nc")
            out = os.path.join(a.work, name, f"np{writers}to{readers}")
            # Into the folder of the run that wrote the checkpoint: a 2-rank run's pieces continue on 3 ranks.
            r = restart_into(full if writers == 1 else wrote, written, deck, out, readers)
            why = r.stderr if r.returncode else same_results(out, full)
            check(not why, f"{name}: checkpoint of {writers} rank(s) restarted on {readers}, byte-identical to serial {why}")
            if writers == 4 and not why:  # a bar cut in 4 slabs: the end ranks read only the pieces near their points
                m = re.search(r"(\d+) file\(s\), at most (\d+) read by one rank", open(os.path.join(out, "run.log")).read())
                check(m and int(m.group(2)) < int(m.group(1)),
                      f"{name}: restarted on {readers} ranks, each read at most {m and m.group(2)} of the {writers} pieces")

    # A run stopped by SIGTERM: checkpoint at its last step, results as .partial; the restart finishes them.
    quick = os.path.join(a.source, "examples/quickstart/deck.yaml")
    text = yaml.safe_load(open(quick))
    text["solver"]["end_time"] = "600 us"  # long enough to be stopped
    text["output"]["checkpoint"] = {"every": 100000, "keep": 2}
    long_deck = os.path.join(a.work, "long.yaml")
    yaml.safe_dump(text, open(long_deck, "w"), sort_keys=False, allow_unicode=True)
    full = os.path.join(a.work, "signal", "full")
    check(peridot(["run", "-q", "-o", full, long_deck]).returncode == 0, "signal: the uninterrupted run")
    stopped = os.path.join(a.work, "signal", "stopped")
    for attempt, delay in enumerate([1.0, 0.5, 0.25, 2.0]):
        shutil.rmtree(stopped, ignore_errors=True)
        proc = subprocess.Popen([a.peridot, "run", "-q", "-o", stopped, long_deck], env=env, stderr=subprocess.PIPE, text=True)
        time.sleep(delay)
        proc.send_signal(signal.SIGTERM)
        err = proc.communicate(timeout=600)[1]
        if proc.returncode == 128 + signal.SIGTERM:
            break
    check(proc.returncode == 128 + signal.SIGTERM and "--restart" in err,
          f"signal: SIGTERM stops the run with exit {proc.returncode} and names the checkpoint: {err.strip()}")
    steps = checkpoints(stopped)
    if check(len(steps) == 1, f"signal: one checkpoint, at the last step ({steps})"):
        r = peridot(["run", "-q", "-o", stopped, long_deck, "--restart", os.path.join(stopped, f"checkpoint_{steps[0]}.nc")])
        why = r.stderr if r.returncode else same_results(stopped, full)
        check(not why, f"signal: restarted from step {steps[0]}, the .partial results continued to the same bytes {why}")
        check(not any(f.endswith((".partial", ".before-restart")) for f in os.listdir(stopped)),
              "signal: no .partial or .before-restart file left")

    # Distributed: 2 ranks stopped by SIGTERM (mpirun passes it on to them) leave their Exodus pieces as
    # NAME.2.r.partial and a checkpoint; the restart on 3 ranks continues them into 3 pieces.
    stopped = os.path.join(a.work, "signal", "stopped_np2")
    for delay in [2.0, 1.0, 4.0, 8.0]:
        shutil.rmtree(stopped, ignore_errors=True)
        proc = subprocess.Popen([a.mpirun, "--oversubscribe", "-np", "2", a.peridot, "run", "-q", "-o", stopped, long_deck],
                                env=env, stderr=subprocess.PIPE, text=True)
        time.sleep(delay)
        proc.send_signal(signal.SIGTERM)
        err = proc.communicate(timeout=600)[1]
        if os.path.isdir(stopped) and checkpoints(stopped):
            break
    partial = sorted(f for f in os.listdir(stopped) if f.endswith(".partial")) if os.path.isdir(stopped) else []
    steps = checkpoints(stopped) if os.path.isdir(stopped) else []
    if check(len(steps) == 1 and "quickstart.e.2.0.partial" in partial and "quickstart.e.2.1.partial" in partial,
             f"signal, 2 ranks: stopped with exit {proc.returncode}, one checkpoint ({steps}), the pieces as .partial "
             f"({partial}) {err.strip()[-300:]}"):
        r = peridot(["run", "-q", "-o", stopped, long_deck, "--restart", os.path.join(stopped, f"checkpoint_{steps[0]}.nc")], 3)
        why = r.stderr if r.returncode else same_results(stopped, full)
        check(not why and piece_sets(stopped) == {"quickstart.e": 3},
              f"signal, 2 ranks: restarted on 3 ranks from step {steps[0]}, the 2 pieces continued into 3, joined the "
              f"serial run's bytes {why}")
        check(not any(f.endswith((".partial", ".before-restart")) for f in os.listdir(stopped)),
              "signal, 2 ranks: no .partial or .before-restart file left")

    # By wall-clock time, keeping the newest two.
    timed = dict(text, output=dict(text["output"], checkpoint={"wall_time": "0.5 s", "keep": 2}))
    timed_deck = os.path.join(a.work, "timed.yaml")
    yaml.safe_dump(timed, open(timed_deck, "w"), sort_keys=False, allow_unicode=True)
    out = os.path.join(a.work, "timed")
    r = peridot(["run", "-q", "-o", out, timed_deck])
    log = open(os.path.join(out, "run.log")).read() if r.returncode == 0 else r.stderr
    written = log.count("\ncheckpoint ")
    check(r.returncode == 0 and written >= 3 and len(checkpoints(out)) == 2,
          f"wall_time: {written} checkpoints written in {out}, the newest 2 kept: {checkpoints(out)}")

    # Refusals: exit 2, a clear message, nothing written.
    cp = os.path.join(full, sorted(f for f in os.listdir(full) if f.startswith("checkpoint_"))[0])

    def refused(what, deck, checkpoint, expect):
        out = os.path.join(a.work, "refused", what.replace(" ", "_"))
        r = peridot(["run", "-q", "-o", out, deck, "--restart", checkpoint])
        check(r.returncode == 2 and expect in r.stderr and not os.path.exists(out),
              f"refused, {what}: exit {r.returncode}, nothing written: {r.stderr.strip()}")

    other = dict(text, materials={k: dict(v) for k, v in text["materials"].items()})
    first = next(iter(other["materials"]))
    other["materials"][first]["density"] = "7000 kg/m^3"
    changed_deck = os.path.join(a.work, "changed.yaml")
    yaml.safe_dump(other, open(changed_deck, "w"), sort_keys=False, allow_unicode=True)
    refused("a changed deck", changed_deck, cp, "another deck")
    refused("another deck", os.path.join(a.source, "tests/regression/decks/exodus_small.yaml"), cp, "another deck")
    # (An earlier end time with the same Δt: the contact deck gives num_steps.)
    contact = yaml.safe_load(open(os.path.join(a.work, "mpi_contact.yaml")))
    contact["solver"]["num_steps"] = EVERY - 1
    ended_deck = os.path.join(a.work, "ended.yaml")
    yaml.safe_dump(contact, open(ended_deck, "w"), sort_keys=False, allow_unicode=True)
    refused("a checkpoint after the end", ended_deck, os.path.join(a.work, "mpi_contact", "full", f"checkpoint_{EVERY}.nc"),
            "after this deck's end")
    shorter = dict(text, solver=dict(text["solver"], end_time="100 us"))
    shorter_deck = os.path.join(a.work, "shorter.yaml")
    yaml.safe_dump(shorter, open(shorter_deck, "w"), sort_keys=False, allow_unicode=True)
    refused("another time step", shorter_deck, cp, "give solver.num_steps")
    data = open(cp, "rb").read()
    truncated = os.path.join(a.work, "truncated.nc")
    open(truncated, "wb").write(data[: len(data) // 2])
    refused("a truncated file", long_deck, truncated, "cannot read checkpoint")
    corrupt = os.path.join(a.work, "corrupt.nc")
    flipped = bytearray(data)
    flipped[-100] ^= 0x01
    open(corrupt, "wb").write(bytes(flipped))
    refused("a corrupt file", long_deck, corrupt, "checksum")
    version = os.path.join(a.work, "version.nc")
    shutil.copy(cp, version)
    with netCDF4.Dataset(version, "a") as nc:
        nc.setncattr("code_version", "0.0.1 (elsewhere)")
    refused("another code version", long_deck, version, "restart it with the version that wrote it")
    refused("a file that is not one", long_deck, long_deck, "cannot read checkpoint")
    # A distributed run's checkpoint is one piece per rank (each with its own points only); one missing is refused.
    np2 = os.path.join(a.work, "quickstart", "np2")
    step = checkpoints(np2)[0]
    pieces = [os.path.join(np2, f"checkpoint_{step}.nc.2.{r}") for r in range(2)]
    check(all(os.path.exists(p) for p in pieces) and not os.path.exists(os.path.join(np2, f"checkpoint_{step}.nc"))
          and all(os.path.getsize(p) < os.path.getsize(os.path.join(full_quick, f"checkpoint_{step}.nc")) for p in pieces),
          f"2 ranks write checkpoint_{step}.nc as 2 pieces, each smaller than the serial run's file")
    lacking = os.path.join(a.work, "lacking")
    shutil.rmtree(lacking, ignore_errors=True)
    os.makedirs(lacking)
    shutil.copy(pieces[0], lacking)
    refused("a piece missing", os.path.join(a.work, "quickstart.yaml"), os.path.join(lacking, f"checkpoint_{step}.nc"),
            f"checkpoint_{step}.nc.2.1 is missing")

    print(f"{passed} passed, {failed} failed")
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
