#!/usr/bin/python3
"""The Python module (python/peridot_module.cpp), imported from the build tree and from a CMake install:

  * the quickstart run from Python, stepped in uneven pieces (7 steps, to a time, to the end), writes the same
    history bytes and the same Exodus values as `peridot run`;
  * a deck from a dict, from YAML text and from its file resolve to the same problem; parameters set by key path
    reach the problem;
  * fields are read-only numpy views of the solver's arrays (no copy: they follow the run), the history comes back
    as arrays equal to the CSV file's, write_files=False writes nothing;
  * a boundary condition changed between pieces drives the points from the next step on;
  * a deck error is peridot.InputError carrying file, line, column and message; a blow-up is NumericalError.

Exits 1 if any check fails. Runs on Debian's /usr/bin/python3 with numpy and netCDF4.
"""
import argparse
import csv
import os
import shutil
import subprocess
import sys

import netCDF4
import numpy as np


class Checker:
    def __init__(self):
        self.failures = 0
        self.passes = 0

    def check(self, ok, message):
        if ok:
            self.passes += 1
        else:
            self.failures += 1
            print(f"FAIL {message}")

    def raises(self, kind, call, message, text=None):
        try:
            call()
        except kind as e:
            self.check(text is None or text in str(e), f"{message}: '{text}' not in '{e}'")
            return e
        except Exception as e:  # noqa: BLE001 - any other kind is the failure reported
            self.check(False, f"{message}: raised {type(e).__name__}: {e}")
            return None
        self.check(False, f"{message}: nothing raised")
        return None


def exodus_values(path):
    with netCDF4.Dataset(path) as nc:
        nc.set_auto_mask(False)
        return {name: np.asarray(var[:]) for name, var in nc.variables.items()}


def check_quickstart_bytes(c, peridot, args, work):
    """The must-show: the quickstart from Python gives the CLI's history bytes."""
    deck = os.path.join(args.source, "examples", "quickstart", "deck.yaml")
    cli, py = os.path.join(work, "quickstart_cli"), os.path.join(work, "quickstart_py")
    subprocess.run([args.peridot, "run", "-q", deck, "-o", cli], check=True, stdout=subprocess.DEVNULL)
    run = peridot.Problem(deck).start(output_dir=py)
    run.advance(7)
    c.check(run.step == 7, f"advance(7) from step 0 ended at step {run.step}")
    run.advance(to_time=2e-5)
    c.check(run.time >= 2e-5 * (1 - 1e-12) and run.time - run.time_step < 2e-5,
            f"advance(to_time=2e-5) ended at t = {run.time}, not the first step at or after it")
    run.advance()
    c.check(run.step == run.total_steps, f"advance() ended at step {run.step} of {run.total_steps}")
    run.finish()
    with open(os.path.join(cli, "history.csv"), "rb") as a, open(os.path.join(py, "history.csv"), "rb") as b:
        same = a.read() == b.read()
    c.check(same, "quickstart: Python's history.csv differs from the CLI's")
    ea, eb = exodus_values(os.path.join(cli, "quickstart.e")), exodus_values(os.path.join(py, "quickstart.e"))
    differing = [k for k in ea if k not in eb or not np.array_equal(ea[k], eb[k])]
    c.check(not differing, f"quickstart: Exodus variables differ: {differing}")
    # The history in memory is the file's, value for value.
    with open(os.path.join(py, "history.csv")) as f:
        rows = list(csv.reader(f))
    history = run.history()
    c.check(list(history) == rows[0], f"history columns {list(history)[:4]}… differ from the CSV header")
    table = np.array(rows[1:], dtype=float)
    c.check(all(np.array_equal(history[name], table[:, k]) for k, name in enumerate(rows[0])),
            "history arrays differ from the CSV's values")
    print(f"quickstart: {run.total_steps} steps in pieces 7 / to 2e-5 s / to the end: history.csv "
          f"{'identical' if same else 'DIFFERENT'} to the CLI's, {len(ea)} Exodus variables compared")


def check_problem_sources(c, peridot, args, work):
    import yaml

    deck = os.path.join(args.source, "tests", "regression", "decks", "postprocessors.yaml")
    folder = os.path.dirname(deck)
    with open(deck) as f:
        text = f.read()
    from_file = peridot.Problem(deck)
    from_text = peridot.Problem(yaml=text, base_dir=folder)
    from_dict = peridot.Problem(deck=yaml.safe_load(text), base_dir=folder)
    def body(problem):  # the resolved deck less its first line, which names where the deck came from
        return problem.resolved_yaml().split("\n", 1)[1]

    c.check(body(from_text) == body(from_file), "Problem(yaml=) resolves differently from the file")
    c.check(body(from_dict) == body(from_file), "Problem(deck=dict) resolves differently from the file")
    changed = peridot.Problem(deck, parameters={"materials.steel.youngs_modulus": 150e9, "solver.num_steps": 12,
                                                "boundary_conditions.0.velocity.y": "-3*t"})
    resolved = yaml.safe_load(changed.resolved_yaml())
    c.check(resolved["materials"]["steel"]["youngs_modulus"] == 150e9, "parameter youngs_modulus not set")
    c.check(resolved["solver"]["num_steps"] == 12, "parameter num_steps not set")
    c.check(changed.start(write_files=False).total_steps == 12, "a run of the changed problem has the old step count")
    # Errors: the parameter's path, the deck's file:line:col, a Python type that is no YAML value.
    c.raises(peridot.InputError, lambda: peridot.Problem(deck, parameters={"materials.steel.youngs_modulis": 1e9}),
             "a misspelt parameter", "unknown key 'youngs_modulis'")
    c.raises(TypeError, lambda: peridot.Problem(deck, parameters={"solver.num_steps": object()}),
             "a parameter that is no YAML value", "solver.num_steps")
    c.raises(ValueError, lambda: peridot.Problem(deck, yaml=text), "a file and yaml= together")
    bad = os.path.join(work, "bad.yaml")
    with open(bad, "w") as f:
        f.write(text.replace("    density: 7800\n", "    density: -7800\n"))
    line = text.split("\n").index("    density: 7800") + 1
    error = c.raises(peridot.InputError, lambda: peridot.Problem(bad), "a negative density")
    if error is not None:
        c.check(isinstance(error, ValueError), "InputError is not a ValueError")
        c.check(any(d[0] == bad and d[1] == line and d[2] == 14 and "density" in d[3] for d in error.diagnostics),
                f"InputError.diagnostics {error.diagnostics} lack ({bad}, {line}, 14, …density…)")
        c.check(f"{bad}:{line}:14" in str(error), f"the message '{error}' lacks {bad}:{line}:14")
    print("problem sources: file, yaml=, deck= resolve alike; parameters set; errors carry file:line:col")


def check_fields_and_loads(c, peridot, args, work):
    deck = os.path.join(args.source, "tests", "regression", "decks", "postprocessors.yaml")
    out = os.path.join(work, "no_files")
    run = peridot.Problem(deck).start(output_dir=out, write_files=False)
    c.check(not os.path.exists(out), "write_files=False created the output folder")
    u, v, x = run.field("displacement"), run.field("velocity"), run.field("position")
    c.check(u.shape == (run.num_points, 3) and run.field("damage").shape == (run.num_points,),
            f"field shapes {u.shape}, {run.field('damage').shape}")
    c.check(not u.flags.writeable, "a field view is writeable")
    c.raises(ValueError, lambda: u.__setitem__((0, 0), 1.0), "writing into a field view")
    free = x[:, 0] < 0.0105  # right_end's points are driven at 5 m/s from t = 0
    c.check(np.max(np.abs(v[free, 0] - 5 * (x[free, 0] - 0.006) / 0.006)) <= 1e-12 * 5,
            "the initial velocity field is not the deck's 5 (x - 0.006)/0.006")
    before = u.copy()
    run.advance(10)
    c.check(not np.array_equal(u, before), "the displacement view did not follow the run (a copy?)")
    c.check(np.array_equal(u, run.field("displacement")), "two views of the displacement differ")
    right = run.node_set("right_end")
    c.check(np.allclose(v[right, 0], 5) and np.allclose(v[right, 1], 2), "right_end is not driven at (5, 2) m/s")
    # Held from step 10 on: the driven points stop where they are.
    run.set_boundary_condition("right_end", "x", "0")
    run.set_boundary_condition("right_end", "y", "0")
    held = u[right].copy()
    run.advance(to_step=20)
    c.check(np.array_equal(v[right, :2], np.zeros((len(right), 2))), "right_end still moves after its velocity was set to 0")
    c.check(np.array_equal(u[right, :2], held[:, :2]), "right_end's displacement changed while held")
    c.raises(KeyError, lambda: run.set_boundary_condition("left_end", "x", "0"), "a node set with no condition",
             "the deck has: (right_end, x), (right_end, y)")
    c.raises(peridot.InputError, lambda: run.set_boundary_condition("right_end", "x", "5*"), "a malformed expression",
             "boundary condition on right_end, x")
    c.raises(KeyError, lambda: run.field("equivalent_plastic_strain"), "a field this problem lacks", "it has: position")
    c.raises(ValueError, lambda: run.advance(to_step=run.total_steps + 1), "a step after the end", "after the run's end")
    c.check(run.history() == {}, "a deck without history output gives history columns")
    run.advance()
    run.finish()
    c.check(not os.path.exists(out), "write_files=False wrote the output folder at the end")
    print(f"fields: views follow the run, read-only; a velocity condition set to 0 at step 10 held "
          f"{len(right)} points still to step 20; nothing written without files")


def check_numerical_error(c, peridot, args, work):
    deck = os.path.join(args.source, "tests", "regression", "decks", "exodus_small.yaml")
    problem = peridot.Problem(deck, parameters={"solver.num_steps": 400, "solver.time_step": 2e-6,
                                                "materials.steel.damage.critical_stretch": 10,
                                                "output.directory": os.path.join(work, "blowup")})
    run = problem.start()
    error = c.raises(peridot.NumericalError, run.advance, "a time step far above the stable one", "at step")
    if error is not None:
        c.check(isinstance(error, RuntimeError), "NumericalError is not a RuntimeError")
    c.check(run.finished, "a run that blew up is not finished")
    print(f"numerical error: {str(error).splitlines()[0][:100] if error else None}")


def check_install(c, args, work):
    build = os.path.dirname(args.peridot)
    prefix = os.path.join(work, "prefix")
    shutil.rmtree(prefix, ignore_errors=True)
    subprocess.run(["cmake", "--install", build, "--component", "python", "--prefix", prefix], check=True,
                   stdout=subprocess.DEVNULL)
    found = [os.path.join(d, f) for d, _, files in os.walk(prefix) for f in files if f.startswith("peridot")]
    c.check(len(found) == 1 and "dist-packages" in found[0], f"installed files {found}")
    if found:
        env = dict(os.environ, PYTHONPATH=os.path.dirname(found[0]))
        probe = subprocess.run([sys.executable, "-c", "import peridot; print(peridot.__file__)"], env=env,
                               capture_output=True, text=True)
        c.check(probe.returncode == 0 and probe.stdout.strip() == found[0],
                f"import from the install: {probe.stdout.strip()} {probe.stderr.strip()}")
    print(f"install: {found[0] if found else None}")


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--peridot", required=True)
    parser.add_argument("--source", required=True)
    parser.add_argument("--work", required=True)
    args = parser.parse_args()
    work = os.path.abspath(args.work)
    shutil.rmtree(work, ignore_errors=True)
    os.makedirs(work)
    sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(args.peridot)), "python"))
    import peridot

    c = Checker()
    check_quickstart_bytes(c, peridot, args, work)
    check_problem_sources(c, peridot, args, work)
    check_fields_and_loads(c, peridot, args, work)
    check_numerical_error(c, peridot, args, work)
    check_install(c, args, work)
    print(f"{c.passes} checks passed, {c.failures} failed")
    return 1 if c.failures else 0


if __name__ == "__main__":
    sys.exit(main())
