"""Helpers for the tests of distributed runs: a distributed run writes its Exodus output as pieces NAME.N.r
(one per rank); `peridot join` merges them into NAME, the file a serial run writes."""
import os
import re
import subprocess

PIECE = re.compile(r"^(?P<name>.+)\.(?P<count>\d+)\.(?P<rank>\d+)$")


def piece_sets(folder):
    """{NAME: N} for every complete set of Exodus pieces NAME.N.0 … NAME.N.N-1 in folder (not the checkpoints,
    checkpoint_<step>.nc.N.r)."""
    found = {}
    for f in os.listdir(folder):
        m = PIECE.match(f)
        if m and len(m["rank"]) == len(m["count"]) and int(m["rank"]) < int(m["count"]) \
                and not re.match(r"checkpoint_\d+\.nc$", m["name"]):
            found.setdefault((m["name"], int(m["count"])), set()).add(int(m["rank"]))
    return {name: count for (name, count), ranks in found.items() if ranks == set(range(count))}


def join_all(peridot, folder, env=None):
    """Runs `peridot join` on every piece set in folder; returns (ok, message)."""
    for name in sorted(piece_sets(folder)):
        r = subprocess.run([peridot, "join", os.path.join(folder, name)], capture_output=True, text=True, env=env, timeout=600)
        if r.returncode != 0:
            return False, f"peridot join {name}: exit {r.returncode}: {r.stderr.strip()}"
    return True, ""
