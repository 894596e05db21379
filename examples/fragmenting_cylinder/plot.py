#!/usr/bin/python3
"""Plot the fragmenting cylinder: damage at the last frame, written to damage.png.

Left: the tube unrolled (angle θ around the axis versus height z) in the reference
configuration, so cracks show as bright lines and fragments as the dark patches between them.
Right: a perspective view of the deformed tube at the same time, coloured by damage.

Run from this folder after the simulation:  /usr/bin/python3 plot.py [out/cylinder.e]
"""

import pathlib
import sys

HERE = pathlib.Path(__file__).resolve().parent
sys.path.insert(0, str(HERE.parents[1] / "tools"))
import peridot_results as pr  # noqa: E402
import matplotlib.pyplot as plt  # noqa: E402


def main(path):
    with pr.Results(path) as res:
        t = res.times[-1]
        fig = plt.figure(figsize=(15, 6.5))
        ax1 = fig.add_subplot(1, 2, 1)
        pr.plot_field(res, "damage", out=None, ax=ax1, view="unrolled", vmin=0, vmax=1,
                      bins=(141, 100),
                      title="damage (mean through the wall), unrolled reference tube")
        ax2 = fig.add_subplot(1, 2, 2, projection="3d")
        pr.plot_field(res, "damage", out=None, ax=ax2, view="3d", deformed=True, vmin=0, vmax=1,
                      point_size=0.3, title="damage on the deformed tube")
        ax2.view_init(elev=20, azim=-60)
        ax2.set_box_aspect((1, 1, 1))
        fig.suptitle(f"Expanding steel tube (LPS, critical stretch 0.02), t = {t * 1e6:.0f} µs")
        out = HERE / "damage.png"
        fig.savefig(out, dpi=80, bbox_inches="tight")
        print(f"wrote {out}")


if __name__ == "__main__":
    main(sys.argv[1] if len(sys.argv) > 1 else str(HERE / "out" / "cylinder.e"))
