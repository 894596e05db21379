#!/usr/bin/python3
"""Reads an Exodus II file written by Peridot back with netCDF4 and checks what a post-processor relies on:
coordinates, SPHERE element blocks with a "radius" attribute, node sets, the nodal variable names and
values, and the times.

Two modes:
  * default: runs `<peridot> run <source>/tests/regression/decks/exodus_small.yaml` in --work and checks every
    .e file the run leaves there (skipped, with a message, while that deck does not exist yet);
  * --file F: checks F only. With --fixture, F must be the file of the gtest ExodusWriter.RoundTrip3D
    (PERIDOT_EXODUS_FIXTURE=F build/tests/peridot_tests --gtest_filter=ExodusWriter.RoundTrip3D), whose
    values follow known formulas; they are then compared exactly.

Handles both Exodus layouts: one netCDF variable per nodal variable (vals_nod_var1, …, "large model") or
one combined vals_nod_var(time_step, num_nod_var, num_nodes), and coordx/coordy/coordz or a combined coord.
Exits 1 if any check fails. Runs on Debian's /usr/bin/python3 with numpy and netCDF4 only.
"""
import argparse
import glob
import math
import os
import subprocess
import sys

import netCDF4
import numpy as np


def expected_names(dim):
    names = [f"{field}_{axis}" for field in ("displacement", "velocity", "force_density") for axis in "xyz"[:dim]]
    return names + ["damage", "dilatation", "weighted_volume", "volume"]


# Fields a run adds when its models need them, in this order: inelastic models, then damage.
OPTIONAL_NAMES = ["equivalent_plastic_strain", "dissipation", "fragment"]


def names_ok(names, dim):
    """The fixed names, then a subset of the optional ones in their order."""
    fixed = expected_names(dim)
    extra = names[len(fixed):]
    return names[: len(fixed)] == fixed and extra == [n for n in OPTIONAL_NAMES if n in extra]


def strings(var):
    # A string ends at its first NUL: the rest of its row is left unwritten (netCDF no-fill mode).
    return [row.tobytes().split(b"\0")[0].decode().strip() for row in np.asarray(var[:])]


class Checker:
    def __init__(self, path):
        self.path = path
        self.failures = 0
        self.passes = 0

    def check(self, ok, message):
        if ok:
            self.passes += 1
        else:
            self.failures += 1
            print(f"FAIL {self.path}: {message}")
        return ok


class ExodusFile:
    """The parts of an Exodus file these checks need, as numpy arrays, whatever the layout."""

    def __init__(self, path):
        self.ds = netCDF4.Dataset(path, "r")
        self.ds.set_auto_mask(False)
        ds = self.ds
        self.dim = ds.dimensions["num_dim"].size
        self.num_nodes = ds.dimensions["num_nodes"].size
        self.num_steps = ds.dimensions["time_step"].size
        if "coordx" in ds.variables:
            self.coords = np.array([ds.variables["coord" + a][:] for a in "xyz"[: self.dim]])
        else:
            self.coords = np.array(ds.variables["coord"][:])
        self.times = np.array(ds.variables["time_whole"][:])
        self.var_names = strings(ds.variables["name_nod_var"]) if "name_nod_var" in ds.variables else []

    def nodal(self, name, step):
        """Values of nodal variable `name` at 0-based `step`."""
        k = self.var_names.index(name)
        if f"vals_nod_var{k + 1}" in self.ds.variables:
            return np.array(self.ds.variables[f"vals_nod_var{k + 1}"][step, :])
        return np.array(self.ds.variables["vals_nod_var"][step, k, :])

    def blocks(self):
        """(name, element type, connectivity (1-based), attribute names, attributes) per block."""
        ds = self.ds
        count = ds.dimensions["num_el_blk"].size if "num_el_blk" in ds.dimensions else 0
        names = strings(ds.variables["eb_names"]) if "eb_names" in ds.variables else [""] * count
        out = []
        for b in range(1, count + 1):
            conn = ds.variables[f"connect{b}"]
            attr = np.array(ds.variables[f"attrib{b}"][:]) if f"attrib{b}" in ds.variables else None
            attr_names = strings(ds.variables[f"attrib_name{b}"]) if f"attrib_name{b}" in ds.variables else []
            out.append((names[b - 1], conn.getncattr("elem_type"), np.array(conn[:]), attr_names, attr))
        return out

    def node_sets(self):
        ds = self.ds
        count = ds.dimensions["num_node_sets"].size if "num_node_sets" in ds.dimensions else 0
        names = strings(ds.variables["ns_names"]) if "ns_names" in ds.variables else [""] * count
        # An empty node set has no node_ns variable.
        return [(names[s - 1], np.array(ds.variables[f"node_ns{s}"][:]) if f"node_ns{s}" in ds.variables
                 else np.array([], dtype=int)) for s in range(1, count + 1)]


def check_generic(c, ex, thickness):
    """What holds for any Peridot output of a sane run."""
    c.check(ex.dim in (2, 3), f"num_dim {ex.dim}")
    c.check(ex.coords.shape == (ex.dim, ex.num_nodes), f"coordinates shape {ex.coords.shape}")
    c.check(names_ok(ex.var_names, ex.dim), f"nodal variable names {ex.var_names}")
    c.check(ex.num_steps >= 1, "no time step")
    c.check(len(ex.times) == ex.num_steps, "time_whole length")
    c.check(bool(np.all(np.diff(ex.times) > 0)), f"times not increasing: {ex.times}")
    if not names_ok(ex.var_names, ex.dim):
        return
    volume0 = ex.nodal("volume", 0)
    c.check(bool(np.all(volume0 > 0)), "volume not positive")
    for step in range(ex.num_steps):
        for name in ex.var_names:
            values = ex.nodal(name, step)
            c.check(values.shape == (ex.num_nodes,), f"{name} step {step} shape {values.shape}")
            c.check(bool(np.all(np.isfinite(values))), f"{name} step {step} not finite")
        c.check(np.array_equal(ex.nodal("volume", step), volume0), f"volume changes at step {step}")
        damage = ex.nodal("damage", step)
        c.check(bool(np.all((damage >= 0) & (damage <= 1))), f"damage outside [0, 1] at step {step}")

    # Every point is one SPHERE element with its radius; elements cover the nodes exactly once.
    seen = []
    for name, elem_type, conn, attr_names, attr in ex.blocks():
        c.check(elem_type.upper() == "SPHERE", f"block {name} type {elem_type}")
        c.check(conn.ndim == 2 and conn.shape[1] == 1, f"block {name} connectivity shape {conn.shape}")
        c.check(attr_names == ["radius"], f"block {name} attribute names {attr_names}")
        nodes = conn[:, 0] - 1
        seen.extend(nodes.tolist())
        if attr is not None and attr_names == ["radius"]:
            v = volume0[nodes]
            radius = np.cbrt(3 * v / (4 * math.pi)) if ex.dim == 3 else np.sqrt(v / (math.pi * thickness))
            c.check(np.allclose(attr[:, 0], radius, rtol=1e-14, atol=0), f"block {name} radius")
    c.check(sorted(seen) == list(range(ex.num_nodes)), "elements do not cover every node exactly once")
    for name, members in ex.node_sets():
        c.check(name != "", "unnamed node set")
        c.check(bool(np.all((members >= 1) & (members <= ex.num_nodes))), f"node set {name} out of range")


def check_fixture(c, ex):
    """Exact values of the file written by the gtest ExodusWriter.RoundTrip3D (formulas copied from
    tests/unit/exodus_writer_test.cpp, same operation order, so equality is exact)."""
    c.check(ex.ds.title == "peridot exodus writer test", f"title {ex.ds.title!r}")
    c.check(ex.dim == 3 and ex.num_nodes == 8, f"dim {ex.dim} nodes {ex.num_nodes}")
    c.check(np.array_equal(ex.times, [0.0, 0.5, 1.25]), f"times {ex.times}")
    h = 0.1
    i = np.arange(ex.num_nodes)
    lattice = np.array([(i % 2) * h, ((i // 2) % 2) * h, (i // 4) * h])
    c.check(np.array_equal(ex.coords, lattice), "coordinates")
    ii = i.astype(np.float64)
    for f in range(ex.num_steps):
        for d, axis in enumerate("xyz"):
            c.check(np.array_equal(ex.nodal("displacement_" + axis, f), 0.001 * ii + d + 10.0 * f), f"u{axis} {f}")
            c.check(np.array_equal(ex.nodal("velocity_" + axis, f), -0.5 * ii + 0.25 * d + f), f"v{axis} {f}")
            c.check(np.array_equal(ex.nodal("force_density_" + axis, f), 1.0e6 * (ii + 1) * (d + 1) + f),
                    f"force_density_{axis} {f}")
        c.check(np.array_equal(ex.nodal("damage", f), (i % 4) / 4.0 * (f / 2.0)), f"damage {f}")
        c.check(np.array_equal(ex.nodal("dilatation", f), 0.001 * ii - f), f"dilatation {f}")
        c.check(np.array_equal(ex.nodal("weighted_volume", f), 1.0e-9 * (ii + 1) + 1.0e-12 * f),
                f"weighted_volume {f}")
        c.check(np.array_equal(ex.nodal("volume", f), np.full(8, h * h * h)), f"volume {f}")
    blocks = ex.blocks()
    c.check([b[0] for b in blocks] == ["right", "left"], f"block names {[b[0] for b in blocks]}")
    c.check([b[2][:, 0].tolist() for b in blocks] == [[2, 4, 6, 8], [1, 3, 5, 7]], "element order")
    c.check(np.array_equal(np.array(ex.ds.variables["node_num_map"][:]), 8 - i), "node_num_map")
    sets = ex.node_sets()
    c.check([s[0] for s in sets] == ["bottom", "corner"], f"node set names {[s[0] for s in sets]}")
    c.check([s[1].tolist() for s in sets] == [[1, 2, 3, 4], [8]], "node set members")


def check_against_history(c, path, density):
    """The values written are those of the run: kinetic energy and max damage of each Exodus frame equal
    the history row of the same time (both written by the run at the same step)."""
    history = os.path.join(os.path.dirname(path), "history.csv")
    if not os.path.exists(history):
        return
    rows = np.genfromtxt(history, delimiter=",", names=True)
    ex = ExodusFile(path)
    volume = ex.nodal("volume", 0)
    matched = 0
    for step, t in enumerate(ex.times):
        row = rows[np.isclose(rows["time"], t, rtol=0, atol=1e-15)]
        if len(row) != 1:
            continue
        speed2 = sum(ex.nodal(f"velocity_{a}", step) ** 2 for a in "xyz"[: ex.dim])
        kinetic = 0.5 * density * np.sum(volume * speed2)
        c.check(np.isclose(kinetic, row["kinetic_energy"][0], rtol=1e-12, atol=0),
                f"frame {step}: kinetic energy {kinetic} from Exodus, {row['kinetic_energy'][0]} in history")
        damage = ex.nodal("damage", step).max()
        c.check(damage == row["max_damage"][0], f"frame {step}: max damage {damage} vs {row['max_damage'][0]}")
        if "fragment" in ex.var_names:
            # Each fragment is labelled by the smallest input id among its points; node ids are input id + 1.
            label = ex.nodal("fragment", step)
            ids = ex.ds.variables["node_num_map"][:] - 1 if "node_num_map" in ex.ds.variables else np.arange(ex.num_nodes)
            distinct = np.unique(label)
            c.check(len(distinct) == row["fragments"][0], f"frame {step}: {len(distinct)} labels, {row['fragments'][0]} fragments")
            smallest = {value: ids[label == value].min() for value in distinct}
            c.check(all(smallest[v] == v for v in distinct), f"frame {step}: a fragment label is not its smallest id")
        matched += 1
    c.check(matched >= 2, f"{matched} Exodus frames matched a history row")
    c.check(ex.nodal("damage", ex.num_steps - 1).max() > 0, "bonds broke (the deck is meant to break some)")
    ex.ds.close()


def check_file(path, fixture, thickness):
    c = Checker(path)
    try:
        ex = ExodusFile(path)
    except (OSError, KeyError) as e:
        c.check(False, f"cannot read: {e}")
        return c
    check_generic(c, ex, thickness)
    if fixture:
        check_fixture(c, ex)
    ex.ds.close()
    return c


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--peridot", help="the peridot executable")
    parser.add_argument("--source", help="repository root")
    parser.add_argument("--work", help="scratch directory")
    parser.add_argument("--file", help="check this .e file instead of running a deck")
    parser.add_argument("--fixture", action="store_true", help="the file is the gtest fixture: check values")
    parser.add_argument("--thickness", type=float, default=1.0, help="2D thickness used for the radius")
    args = parser.parse_args()

    if args.file:
        files = [args.file]
    else:
        if not (args.peridot and args.source and args.work):
            parser.error("--peridot, --source and --work are needed without --file")
        deck = os.path.join(os.path.abspath(args.source), "tests", "regression", "decks", "exodus_small.yaml")
        os.makedirs(args.work, exist_ok=True)
        for old in glob.glob(os.path.join(args.work, "**", "*.e"), recursive=True):
            os.remove(old)
        run = subprocess.run([args.peridot, "run", "-q", "--output-dir", os.path.join(args.work, "out"), deck],
                             cwd=args.work, capture_output=True, text=True,
                             timeout=600)
        if run.returncode != 0:
            print(f"FAIL: peridot run {deck} exited {run.returncode}\n{run.stdout}\n{run.stderr}")
            return 1
        files = sorted(glob.glob(os.path.join(args.work, "**", "*.e"), recursive=True))
        if not files:
            print(f"FAIL: peridot run {deck} left no .e file under {args.work}")
            return 1

    failures = 0
    for path in files:
        c = check_file(path, args.fixture, args.thickness if args.file else 1e-3)  # exodus_small: h = 1 mm
        if not args.file:
            check_against_history(c, path, density=7800.0)  # the density of exodus_small.yaml
        print(f"{path}: {c.passes} checks passed, {c.failures} failed")
        failures += c.failures
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
