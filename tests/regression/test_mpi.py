#!/usr/bin/python3
"""Distributed runs (issue: MPI domain decomposition). Every model, damage, loads, walls and outputs give the
same bits on 1, 2, 3 and 4 ranks as a serial run: each deck runs once without mpirun and then under
`mpirun --oversubscribe -np N` (more ranks than this machine's cores), and every byte of the Exodus file (the
ranks' pieces NAME.N.r merged by `peridot join`), the history and the resolved deck (but for its output
directory) must match; where ParaView's Python (pvpython) is installed, ParaView reads the pieces as one data set
with the serial run's values. Also: a deck error is reported once (not once per rank)
with exit status 2 and nothing written, also when only some ranks can see it (a correspondence body bonded
to another model's body, found from the local bonds); a numerical failure exits 3 on every rank with one
message and the frames written so far readable; an output rank 0 cannot write stops every rank with one
message; `peridot check` describes the decomposition. The implicit solver (PETSc) gives the same bits on threads
and on one rank, and the same equilibria to its tolerances on 2 and 3 ranks."""
import argparse
import csv
import filecmp
import os
import re
import shutil
import subprocess
import sys

from exodus_pieces import join_all, piece_sets

DECKS = [  # (deck, what it covers)
    ("examples/quickstart/deck.yaml", "pmb 2D fracture: pre-crack, no-fail grips, velocity conditions, reaction, probe"),
    ("tests/regression/decks/exodus_small.yaml", "lps 2D plane strain with damage, body force, jitter"),
    ("tests/regression/decks/mpi_mixed.yaml", "pmb|lps interface in 3D, damage, displacement condition, rigid wall"),
    ("tests/regression/decks/inelastic_small.yaml", "lps_plastic beside lps_viscoelastic, damage across the interface"),
    ("tests/regression/decks/mpi_correspondence_wall.yaml", "correspondence J2 with hourglass control on an anvil"),
    ("tests/regression/decks/mpi_symmetry_wall.yaml", "correspondence J2 on an anvil with contact: symmetry, released"),
    ("tests/regression/decks/jc_damage_small.yaml",
     "correspondence Johnson–Cook damage: bonds degrading and breaking across ranks, failed points, fragments"),
    ("tests/regression/decks/relaxation_notch.yaml", "dynamic relaxation in load steps, bonds breaking between equilibria"),
    ("tests/regression/decks/thermoviscoelastic_small.yaml",
     "thermoviscoelastic with WLF and thermal strain in a temperature gradient, relaxation with stepped loads"),
    ("tests/regression/decks/surface_correction_small.yaml",
     "surface correction of pmb beside lps (factors from ghosts' energies), jitter, bond failure"),
    ("tests/regression/decks/energy_failure_small.yaml", "lps 2D, bonds breaking by their work (damage criterion: energy)"),
    ("tests/regression/decks/mpi_contact.yaml",
     "short-range contact with fragments and friction, a free rigid ball and a fixed rigid box"),
    ("tests/regression/decks/mpi_generated.yaml",
     "points made per rank: overlapping bodies, jitter, a volume-constraint layer, an id-file node set"),
    ("tests/regression/decks/mpi_mesh_body.yaml", "a point-file body beside a lattice body: each rank keeps a share of the file"),
    ("tests/regression/decks/mpi_mesh_sets.yaml",
     "an Abaqus mesh body beside a lattice body, its node set pulling, bonds breaking: the mesh read in shares"),
    ("tests/regression/decks/mpi_few_points.yaml", "two points on up to 4 ranks: ranks that own nothing"),
]
RANKS = [1, 2, 3, 4]


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

    def peridot(args, ranks=None, timeout=600):
        cmd = [a.peridot] + args if ranks is None else [a.mpirun, "--oversubscribe", "-np", str(ranks), a.peridot] + args
        r = subprocess.run(cmd, capture_output=True, text=True, env=env, timeout=timeout)
        if r.returncode == 0 and args[0] == "run" and ranks and ranks > 1:  # its Exodus pieces, merged
            out = args[args.index("-o") + 1]
            ok, why = join_all(a.peridot, out, env)
            if not ok:
                r.returncode, r.stderr = 1, why
        return r

    for deck, what in DECKS:
        path = os.path.join(a.source, deck)
        name = os.path.basename(os.path.dirname(deck)) if deck.endswith("/deck.yaml") else os.path.splitext(os.path.basename(deck))[0]
        serial = os.path.join(a.work, name, "serial")
        r = peridot(["run", "-q", "-o", serial, path])
        check(r.returncode == 0, f"{name}: serial run ({what})" + ("" if r.returncode == 0 else "\n" + r.stderr))
        if r.returncode != 0:
            continue
        outputs = sorted(f for f in os.listdir(serial) if f != "run.log")
        for n in RANKS:
            out = os.path.join(a.work, name, f"np{n}")
            r = peridot(["run", "-q", "-o", out, path], ranks=n)
            if r.returncode != 0:
                check(False, f"{name}: {n} ranks run\n{r.stdout}\n{r.stderr}")
                continue
            def identical(f):
                mine, theirs = os.path.join(out, f), os.path.join(serial, f)
                if not os.path.exists(mine):
                    return False
                if f == "resolved_deck.yaml":  # names its own output directory
                    return open(mine).read().replace(out, serial) == open(theirs).read()
                return filecmp.cmp(mine, theirs, shallow=False)
            pieces = piece_sets(out)
            if n > 1 and any(f.endswith(".e") for f in outputs):
                check(all(pieces.get(f) == n for f in outputs if f.endswith(".e")),
                      f"{name}: {n} ranks wrote {n} Exodus pieces each ({pieces})")
            same = [f for f in outputs if identical(f)]
            check(same == outputs, f"{name}: {n} ranks, every byte of {', '.join(outputs)} as serial"
                  + ("" if same == outputs else f" (differ: {sorted(set(outputs) - set(same))})"))
            # The closing summary of a plastic run names the same extremes and points on any rank count.
            summary = lambda d: [l for l in open(os.path.join(d, "run.log")) if l.startswith("plasticity:")]
            if summary(serial):
                check(summary(out) == summary(serial), f"{name}: {n} ranks, the log's plasticity summary as serial")

    # The implicit solver (PETSc): the same bits on 2 threads and under mpirun -np 1 as serial; on 2 and 3 ranks
    # the Krylov reductions and the preconditioner (ILU blocks, GAMG's aggregates) follow the partition, so the
    # equilibria agree to the solver's tolerances: the same bonds break, reactions and energies within 1e-8 (measured: 1e-12).
    # Each Jacobian: matrix-free (the deck), colored finite differences, and lps's exact tangent (its assembly
    # gathers the blocks that families on other ranks add to a rank's rows).
    notch = open(os.path.join(a.source, "tests", "regression", "decks", "implicit_notch.yaml")).read()
    variants = {
        "implicit_notch": notch,
        "implicit_notch_finite_difference": notch.replace("  type: implicit\n", "  type: implicit\n  jacobian: finite_difference\n"),
        "implicit_notch_exact": notch.replace("  type: implicit\n", "  type: implicit\n  jacobian: exact\n").replace(
            "model: lps_plastic\n    yield_stress: 60 MPa\n    hardening_modulus: 1 GPa\n", "model: lps\n"),
    }
    for name, text in variants.items():
        check(text.count("jacobian") == (name != "implicit_notch") and ("yield_stress" in text) != name.endswith("exact"),
              f"{name}: the variant deck was made")
        implicit = os.path.join(a.work, name + ".yaml")
        open(implicit, "w").write(text)
        serial = os.path.join(a.work, name, "serial")
        r = peridot(["run", "-q", "-o", serial, implicit])
        check(r.returncode == 0, f"{name}: serial run" + ("" if r.returncode == 0 else "\n" + r.stderr))
        rows = lambda d: list(csv.DictReader(open(os.path.join(d, "history.csv"))))
        for label, args, ranks in (("2 threads", ["-t", "2"], None), ("1 rank", [], 1), ("2 ranks", [], 2), ("3 ranks", [], 3)):
            out = os.path.join(a.work, name, label.replace(" ", "_"))
            r = peridot(["run", "-q"] + args + ["-o", out, implicit], ranks=ranks)
            if r.returncode != 0:
                check(False, f"{name}: {label}\n{r.stdout}\n{r.stderr}")
                continue
            if ranks is None or ranks == 1:
                check(all(filecmp.cmp(os.path.join(serial, f), os.path.join(out, f), shallow=False)
                          for f in ("small.e", "history.csv")), f"{name}: {label}, every byte of small.e and history.csv as serial")
                continue
            worst = 0.0
            same_breaks = True
            for mine, theirs in zip(rows(out), rows(serial)):
                same_breaks &= mine["broken_fraction"] == theirs["broken_fraction"]
                for column in ("reaction_top_y", "strain_energy", "external_work"):
                    scale = max(abs(float(theirs[column])), 1e-300)
                    worst = max(worst, abs(float(mine[column]) - float(theirs[column])) / scale if float(theirs[column]) else 0.0)
            check(same_breaks and worst < 1e-8 and len(rows(out)) == len(rows(serial)),
                  f"{name}: {label}, the same broken bonds at every load step, reaction and energies within "
                  f"{worst:.1e} of serial (1e-8 allowed)")

    # Threads inside ranks: 2 ranks of 2 threads each.
    mixed = os.path.join(a.source, "tests", "regression", "decks", "mpi_mixed.yaml")
    serial, out = os.path.join(a.work, "mpi_mixed", "serial"), os.path.join(a.work, "mpi_mixed", "np2t2")
    r = peridot(["run", "-q", "-t", "2", "-o", out, mixed], ranks=2)
    check(r.returncode == 0 and all(filecmp.cmp(os.path.join(serial, f), os.path.join(out, f), shallow=False)
                                    for f in ("small.e", "history.csv")),
          "mpi_mixed: 2 ranks of 2 threads, every byte of small.e and history.csv as serial")

    # The other partitioners give other splits and the same bits.
    for method in ("rib", "hsfc"):
        deck = os.path.join(a.work, f"mixed_{method}.yaml")  # the Exodus title names the deck: a serial run of it
        open(deck, "w").write(open(mixed).read().replace("\nsolver:", f"\ndecomposition: {{method: {method}}}\nsolver:"))
        serial, out = os.path.join(a.work, f"mixed_{method}", "serial"), os.path.join(a.work, f"mixed_{method}", "np3")
        r = peridot(["run", "-q", "-o", serial, deck])
        if r.returncode == 0:
            r = peridot(["run", "-q", "-o", out, deck], ranks=3)
        same = r.returncode == 0 and all(filecmp.cmp(os.path.join(serial, f), os.path.join(out, f), shallow=False)
                                         for f in ("small.e", "history.csv"))
        check(same, f"mpi_mixed: decomposition {method} on 3 ranks, every byte of small.e and history.csv as serial")

    # A deck error: reported once, exit 2, nothing written.
    bad = os.path.join(a.source, "tests", "data", "decks", "bad_poisson.yaml")
    out = os.path.join(a.work, "bad")
    r = peridot(["run", "-q", "-o", out, bad], ranks=3)
    errors = [line for line in r.stderr.splitlines() if ": error: " in line]
    check(r.returncode == 2 and len(errors) == 1 and not os.path.exists(out),
          f"bad deck on 3 ranks: exit {r.returncode}, {len(errors)} error line(s), nothing written")
    # Only the ranks that own a correspondence point bonded to the lps plate can see this one.
    bad = os.path.join(a.source, "tests", "data", "decks", "bad_correspondence_interface.yaml")
    out = os.path.join(a.work, "bad_interface")
    r = peridot(["run", "-q", "-o", out, bad], ranks=3)
    errors = [line for line in r.stderr.splitlines() if ": error: " in line]
    check(r.returncode == 2 and len(errors) == 1 and ":22:3: error: bodies.rod" in r.stderr and not os.path.exists(out),
          f"set-up error seen by some ranks only: exit {r.returncode}, {len(errors)} error line(s) "
          f"({errors[0] if errors else r.stderr.strip()[:200]})")

    # A misplaced symmetry wall: the check reads only the points near the plane, gathered in the global order,
    # so every rank count names the same point as a serial run.
    text = open(os.path.join(a.source, "tests", "regression", "decks", "mpi_symmetry_wall.yaml")).read()
    for shift, kind in (("0.0007", "behind the plane"), ("0.0003", "not half its spacing")):
        bad = os.path.join(a.work, f"bad_symmetry{shift}.yaml")
        open(bad, "w").write(text.replace("point: [0, 0, 0], normal: [0, 0, 1]", f"point: [0, 0, {shift}], normal: [0, 0, 1]"))
        lines = []
        for ranks in (None, 3):
            out = os.path.join(a.work, f"bad_symmetry{shift}_{ranks}")
            r = peridot(["run", "-q", "-o", out, bad], ranks=ranks)
            lines.append((r.returncode, [line for line in r.stderr.splitlines() if ": error: " in line], os.path.exists(out)))
        check(lines[0] == lines[1] and lines[0][0] == 2 and len(lines[0][1]) == 1 and kind in lines[0][1][0] and not lines[0][2],
              f"symmetry wall {kind}: 3 ranks report what serial does ({lines[1][1][:1]})")

    # A numerical failure: every rank stops with the failing rank's message, exit 3, outputs readable.
    text = open(os.path.join(a.source, "tests", "regression", "decks", "exodus_small.yaml")).read()
    text = text.replace("  num_steps: 120", "  num_steps: 400\n  time_step: 2e-6").replace("    damage: {critical_stretch: 0.002}\n", "")
    blowup = os.path.join(a.work, "blowup.yaml")
    open(blowup, "w").write(text)
    out = os.path.join(a.work, "blowup")
    r = peridot(["run", "-q", "-o", out, blowup], ranks=2)
    messages = re.findall(r"error: runaway \w+ at step \d+, time [0-9.e+-]+ s, point \d+", r.stderr)
    check(r.returncode == 3 and len(messages) == 1 and piece_sets(out).get("small.e") == 2
          and all(os.path.getsize(os.path.join(out, f"small.e.2.{k}")) > 0 for k in range(2))
          and "error: runaway" in open(os.path.join(out, "run.log")).read(),
          f"blow-up on 2 ranks: exit {r.returncode}, {len(messages)} message(s), frames and log kept")

    # A correspondence point whose deformation gradient inverts (a cube hit at 20 km/s) fails inside the
    # force of a step, between two exchanges: every rank still stops, with one message.
    text = open(os.path.join(a.source, "tests", "regression", "decks", "correspondence_small.yaml")).read()
    text = re.sub(r"\{velocity: \{.*\}\}", '{velocity: {x: "-2e4*sin(3000*x)"}}', text)
    inverted = os.path.join(a.work, "inverted.yaml")
    open(inverted, "w").write(text)
    out = os.path.join(a.work, "inverted")
    r = peridot(["run", "-q", "-o", out, inverted], ranks=3, timeout=120)
    messages = re.findall(r"error: at step \d+, time [0-9.e+-]+ s: correspondence model: point \d+", r.stderr)
    check(r.returncode == 3 and len(messages) == 1 and os.path.exists(os.path.join(out, "history.csv")),
          f"correspondence failure inside a step on 3 ranks: exit {r.returncode}, {len(messages)} message(s)")

    # An output that cannot be written (rank 0 writes): every rank stops, one message, no hang.
    r = peridot(["run", "-q", "-o", os.path.join(blowup, "out"), blowup], ranks=2, timeout=120)
    check(r.returncode == 1 and sum(line.startswith("error: ") for line in r.stderr.splitlines()) == 1 and "cannot create" in r.stderr,
          f"unwritable output directory on 2 ranks: exit {r.returncode}, one message")

    # ParaView reads the pieces as one data set, point by point the serial run's (where pvpython is installed).
    pvpython = shutil.which("pvpython")
    for name, n in (("exodus_small", 3), ("mpi_generated", 4)):
        folder = os.path.join(a.work, name)
        if not pvpython:
            print(f"skip {name}: ParaView reading {n} pieces (no pvpython; Debian's paraview package has it)")
            continue
        r = subprocess.run([pvpython, "--force-offscreen-rendering", os.path.join(a.source, "tests", "regression", "paraview_pieces.py"),
                            os.path.join(folder, "serial", "small.e"), os.path.join(folder, f"np{n}", f"small.e.{n}.0")],
                           capture_output=True, text=True, env=env, timeout=600)
        check(r.returncode == 0 and "paraview: same data set" in r.stdout,
              f"{name}: ParaView ({pvpython}) reads the {n} pieces as one data set, every value the serial run's"
              + ("" if r.returncode == 0 else "\n" + r.stdout[-2000:] + r.stderr[-2000:]))

    r = peridot(["check", os.path.join(a.source, "tests", "regression", "decks", "mpi_mixed.yaml")], ranks=2)
    check(r.returncode == 0 and r.stdout.count(": valid") == 1 and re.search(r"ranks +2 \(owned points", r.stdout)
          and "points made      by each rank for its own part of space" in r.stdout,
          "peridot check on 2 ranks prints one description with the decomposition, the points made per rank\n" + r.stdout)
    print(f"{passed} passed, {failed} failed")
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
