#!/usr/bin/python3
"""The fragmenting cylinder with contact on: do fragments pass through each other, and how many fragments of what
mass does the tube break into, at two resolutions and two random seeds?

    contact.py --peridot PATH [--spacings 1.5,1] [--seeds 42,7] [--threads N] [--out DIR] [--without] [--check]

Each run is deck.yaml with the given lattice spacing (the horizon stays 4.17462 mm) and jitter seed, with
`contact: {}` (--without: also each run without contact, for the count of overlaps contact prevents). At every
Exodus frame it counts the pairs of points of different fragments closer than half a spacing (in the deformed
configuration) and their closest distance; at the last frame the fragments (connected through intact bonds) and
their masses. Writes DIR/fragments.png (the cumulative mass distribution of every run) and prints the table of
README.md. --check exits 1 if, with contact on, two points of different fragments come closer than half a spacing
in some frame."""
import argparse
import itertools
import os
import pathlib
import re
import subprocess
import sys

import numpy as np

HERE = pathlib.Path(__file__).resolve().parent
sys.path.insert(0, str(HERE.parents[1] / "tools"))
import peridot_results as pr  # noqa: E402

import matplotlib  # noqa: E402

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

DENSITY = 7800.0


def close_pairs(y, radius):
    """Index pairs (i < j) of points closer than radius: cells of that size, the 27 around each point."""
    cell = np.floor(y / radius).astype(np.int64)
    cell -= cell.min(axis=0) - 1
    span = cell.max(axis=0) + 2
    key = (cell[:, 0] * span[1] + cell[:, 1]) * span[2] + cell[:, 2]
    order = np.argsort(key, kind="stable")
    sorted_keys = key[order]
    firsts, seconds = [], []
    for dx, dy, dz in itertools.product((-1, 0, 1), repeat=3):
        want = ((cell[:, 0] + dx) * span[1] + cell[:, 1] + dy) * span[2] + cell[:, 2] + dz
        lo = np.searchsorted(sorted_keys, want, "left")
        hi = np.searchsorted(sorted_keys, want, "right")
        count = hi - lo
        if count.sum() == 0:
            continue
        i = np.repeat(np.arange(len(y)), count)
        offset = np.arange(count.sum()) - np.repeat(np.cumsum(count) - count, count)
        j = order[np.repeat(lo, count) + offset]
        keep = i < j
        firsts.append(i[keep])
        seconds.append(j[keep])
    i, j = np.concatenate(firsts), np.concatenate(seconds)
    near = np.linalg.norm(y[i] - y[j], axis=1) < radius
    return i[near], j[near]


def analyse(path, spacing):
    """Per frame: pairs of different fragments closer than spacing/2 and the smallest distance between two
    fragments (in spacings; NaN when none are within a spacing); at the last frame the fragments' masses (kg, largest first)."""
    frames = []
    with pr.Results(path) as res:
        volume = res.field("volume", 0) if "volume" in res.names else None
        for k in range(res.num_frames):
            y = res.positions(k)
            fragment = res.field("fragment", k)
            i, j = close_pairs(y, spacing)
            apart = fragment[i] != fragment[j]
            distance = np.linalg.norm(y[i[apart]] - y[j[apart]], axis=1) / spacing
            closest = distance.min() if apart.any() else np.nan
            frames.append((res.times[k], int((distance < 0.5).sum()), closest))
        if volume is None:
            volume = np.full(len(fragment), spacing ** 3)
        labels, inverse = np.unique(fragment, return_inverse=True)
        masses = np.sort(np.bincount(inverse, weights=DENSITY * volume))[::-1]
    return frames, masses


def run(peridot, spacing, seed, contact, out, threads):
    name = f"dx{spacing:g}_seed{seed}_{'contact' if contact else 'none'}"
    text = (HERE / "deck.yaml").read_text()
    text = re.sub(r"spacing: 1 mm", f"spacing: {spacing} mm", text)
    text = re.sub(r"seed: 42", f"seed: {seed}", text)
    text = re.sub(r"directory: out", f"directory: {out / name}", text)
    # 11 frames at any spacing: 0, 25, …, 250 µs.
    text = re.sub(r"exodus: \{every: \d+, file: cylinder.e\}", "exodus: {every: 10000000, file: cylinder.e}", text)
    if contact:
        text += "\ncontact: {}\n"
    deck = out / f"{name}.yaml"
    deck.write_text(text)
    # A first, short run tells the step: the Exodus frames every 25 µs are set from it.
    check = subprocess.run([peridot, "check", str(deck)], capture_output=True, text=True, check=True).stdout
    dt = float(re.search(r"^time step\s+([0-9.e+-]+) s", check, re.M).group(1))
    every = max(1, round(25e-6 / dt))
    deck.write_text(text.replace("exodus: {every: 10000000,", f"exodus: {{every: {every},"))
    env = dict(os.environ, OMP_NUM_THREADS=str(threads))
    subprocess.run([peridot, "run", "-q", str(deck)], check=True, env=env)
    return name, out / name / "cylinder.e"


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--peridot", required=True)
    ap.add_argument("--spacings", default="1.5,1")
    ap.add_argument("--seeds", default="42,7")
    ap.add_argument("--threads", type=int, default=1)
    ap.add_argument("--out", default=str(HERE / "out_contact"))
    ap.add_argument("--without", action="store_true", help="also run each case without contact")
    ap.add_argument("--check", action="store_true", help="exit 1 on a pair of fragments closer than Δx/2 (contact on)")
    a = ap.parse_args()
    out = pathlib.Path(a.out).resolve()
    out.mkdir(parents=True, exist_ok=True)
    rows, curves = [], []
    overlapping = 0
    for spacing in [float(s) for s in a.spacings.split(",")]:
        for seed in [int(s) for s in a.seeds.split(",")]:
            for contact in ([True, False] if a.without else [True]):
                name, path = run(a.peridot, spacing, seed, contact, out, a.threads)
                frames, masses = analyse(path, spacing * 1e-3)
                total = masses.sum()
                overlaps = max(f[1] for f in frames)
                if contact:
                    overlapping += overlaps
                closest = np.nanmin([f[2] for f in frames])
                rows.append([f"{spacing:g}", str(seed), "on" if contact else "off", str(overlaps), f"{closest:.2f}",
                             str(len(masses)), str(int((masses > 1e-3 * total).sum())),
                             f"{masses[0] / total:.3f}", f"{masses[:10].sum() / total:.3f}"])
                curves.append((f"Δx = {spacing:g} mm, seed {seed}, contact {'on' if contact else 'off'}", masses / total))
                print(name, "frames (t µs, overlapping pairs, closest in Δx):",
                      ", ".join(f"({t * 1e6:.0f}, {n}, {c:.2f})" for t, n, c in frames), flush=True)
    header = ["Δx (mm)", "seed", "contact", "most pairs of different fragments < Δx/2 in a frame",
              "closest two fragments (Δx)", "fragments", "fragments > 0.1 % of the mass", "largest (mass fraction)",
              "ten largest (mass fraction)"]
    print("| " + " | ".join(header) + " |")
    print("|" + "---|" * len(header))
    for row in rows:
        print("| " + " | ".join(row) + " |")
    fig, ax = plt.subplots(figsize=(7, 4.5))
    for label, fractions in curves:
        ax.loglog(fractions, np.arange(1, len(fractions) + 1), label=label)
    ax.set_xlabel("fragment mass / tube mass")
    ax.set_ylabel("fragments at least this heavy")
    ax.set_title("Fragmenting cylinder at 250 µs, contact on")
    ax.grid(alpha=0.3, which="both")
    ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(out / "fragments.png", dpi=120)
    print(f"wrote {out / 'fragments.png'}")
    if a.check:
        print(("ok" if overlapping == 0 else "FAIL") + f": {overlapping} pairs of different fragments closer than Δx/2 "
              "with contact on")
        sys.exit(0 if overlapping == 0 else 1)


if __name__ == "__main__":
    main()
