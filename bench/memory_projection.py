#!/usr/bin/python3
"""Memory per rank, halo and output volume of an LPS block at 10⁸ and 10⁹ points on 1 000 and 65 000 ranks,
from the per-point and per-bond sizes that bench/mpi_memory.py measured (docs/performance.md, "Memory per
rank"; the constants below are those measurements, stated where they come from).

    /usr/bin/python3 bench/memory_projection.py

Each rank owns a cube of n = N / R lattice points (side L = n^(1/3)); its ghosts are the lattice points within
the horizon (3.015 spacings) outside the cube, counted on the lattice (an interior rank, all six faces). Per rank:
  memory = M0 + P·(n + ghosts) + B·bonds,  bonds = 122 n (a full LPS family at δ = 3.015 Δx; surfaces have fewer)
and, for decks that write Exodus frames, W·n more on every rank (its piece's writer: a copy of the volumes and
one field's buffer; nothing is gathered, each rank writes its own file NAME.N.r). A frame is F bytes per point:
F·n per rank, all ranks writing at once at the file system's aggregate bandwidth; for comparison, the same
frame through one writer (one file written by one process) at the stated single-client bandwidth.
"""
import math
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from mpi_scaling import ghosts_of_box  # noqa: E402  (the lattice count of a box's ghosts)

M0 = 60 * 2**20      # B per rank: process, libraries, MPI (measured: peak minus the points-and-bonds estimate, 1 M block)
P = 192              # B per point (state, positions, offsets: Simulation::memory_bytes for lps, checked against VmHWM)
B = 5                # B per directed bond (neighbour index, broken flag)
BONDS = 122          # bonds of an interior point, δ = 3.015 Δx
W = 16               # B per owned point for a rank's Exodus piece writer (volume copy, one field buffer)
F = 13 * 8           # B per point per frame: 3D lps with damage writes 13 nodal doubles (u, v, f, damage, θ, m, V, fragment)
ONE_WRITER = 1e9     # B/s: rank 0 writing one file (assumed: one client of a parallel file system)
AGGREGATE = 100e9    # B/s: one file per rank, all writing at once (assumed: a large Lustre/GPFS system)
EXCHANGE = 32        # B per ghost per step (LPS: u and θ)


def main():
    print("| points | ranks | points/rank | ghosts/rank | halo fraction | memory/rank (MiB) | with frames (MiB) | "
          "messages/step/rank | halo bytes/step/rank | frame (GB) | frame per rank (MB) | frame, file per rank (s) | "
          "frame through one writer (s) |")
    print("|---|---|---|---|---|---|---|---|---|---|---|---|---|")
    for total in (1e8, 1e9):
        for ranks in (1000, 65000):
            n = total / ranks
            side = max(1, round(n ** (1 / 3)))
            ghosts = ghosts_of_box((side, side, side))
            memory = M0 + P * (n + ghosts) + B * BONDS * n
            with_frames = memory + W * n
            frame = F * total
            print(f"| {total:.0e} | {ranks} | {n:.0f} | {ghosts} | {ghosts / n:.2f} | {memory / 2**20:.0f} | "
                  f"{with_frames / 2**20:.0f} | 26 × 2 fields | {EXCHANGE * ghosts} | {frame / 1e9:.1f} | "
                  f"{F * n / 1e6:.2f} | {frame / AGGREGATE:.1f} | {frame / ONE_WRITER:.0f} |")


if __name__ == "__main__":
    main()
