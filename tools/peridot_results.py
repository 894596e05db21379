"""Read Peridot Exodus II results and plot nodal fields as scatter plots.

Peridot writes one Exodus II (netCDF) file per run: reference coordinates
``coordx``/``coordy``[/``coordz``], the frame times ``time_whole`` and nodal
variables ``vals_nod_var1..N`` whose names are listed in ``name_nod_var``
(displacement_*, velocity_*, force_density_*, damage, dilatation,
weighted_volume, volume).  Only /usr/bin/python3 with numpy, netCDF4 and
matplotlib is needed.

Use from a script next to an example::

    import sys, pathlib
    sys.path.insert(0, str(pathlib.Path(__file__).resolve().parents[2] / "tools"))
    import peridot_results as pr

    res = pr.Results("out/results.e")
    x = res.coords                      # (N, dim) reference positions, m
    d = res.field("damage")             # last frame; frame=k for frame k
    pr.plot_field(res, "damage", "damage.png")               # 2D x-y / 3D x-y
    pr.plot_field(res, "damage", "tube.png", view="unrolled")  # tube: θ-axial

or from the shell: ``python3 tools/peridot_results.py out/results.e damage damage.png
[--view xy|xz|yz|unrolled|3d] [--deformed [SCALE]] [--frame K]``.
"""

from __future__ import annotations

import argparse
import os

import numpy as np
import netCDF4

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

__all__ = ["Results", "read_coordinates", "read_times", "read_field", "unroll", "plot_field"]


def _names(chars) -> list[str]:
    # A name ends at its first NUL: Exodus leaves the rest of its row unwritten (netCDF no-fill mode), so
    # the row may hold stray bytes that netCDF4.chartostring cannot decode.
    return [row.tobytes().split(b"\0")[0].decode().strip() for row in np.asarray(chars[:])]


class Results:
    """An open Peridot Exodus file (read-only, loaded lazily; use as a context manager or call close())."""

    def __init__(self, path: str | os.PathLike):
        self.path = os.fspath(path)
        self._ds = netCDF4.Dataset(self.path, "r")
        self._ds.set_auto_mask(False)
        axes = [a for a in ("coordx", "coordy", "coordz") if a in self._ds.variables]
        #: reference coordinates, shape (N, dim), metres
        self.coords = np.column_stack([np.asarray(self._ds[a][:], dtype=float) for a in axes])
        #: spatial dimension (2 or 3)
        self.dim = self.coords.shape[1]
        #: nodal variable names in file order
        self.names = _names(self._ds["name_nod_var"]) if "name_nod_var" in self._ds.variables else []
        #: time of each frame, s
        self.times = np.asarray(self._ds["time_whole"][:], dtype=float)

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        self.close()

    def close(self) -> None:
        self._ds.close()

    @property
    def num_frames(self) -> int:
        return len(self.times)

    def field(self, name: str, frame: int = -1) -> np.ndarray:
        """Nodal variable ``name`` at ``frame`` (negative counts from the end), shape (N,)."""
        if name not in self.names:
            raise KeyError(f"{self.path}: no nodal variable {name!r}; have {self.names}")
        var = self._ds[f"vals_nod_var{self.names.index(name) + 1}"]
        return np.asarray(var[frame, :], dtype=float)

    def vector(self, prefix: str, frame: int = -1) -> np.ndarray:
        """Vector field ``prefix`` (e.g. "displacement", "velocity") at ``frame``, shape (N, dim)."""
        return np.column_stack([self.field(f"{prefix}_{c}", frame) for c in "xyz"[: self.dim]])

    def positions(self, frame: int = -1, scale: float = 1.0) -> np.ndarray:
        """Current positions x + scale·u at ``frame``, shape (N, dim)."""
        return self.coords + scale * self.vector("displacement", frame)


def read_coordinates(path) -> np.ndarray:
    """Reference coordinates (N, dim) of a Peridot Exodus file."""
    with Results(path) as r:
        return r.coords


def read_times(path) -> np.ndarray:
    """Frame times of a Peridot Exodus file."""
    with Results(path) as r:
        return r.times


def read_field(path, name: str, frame: int = -1) -> np.ndarray:
    """Nodal variable ``name`` at ``frame`` of a Peridot Exodus file."""
    with Results(path) as r:
        return r.field(name, frame)


def unroll(points: np.ndarray, center=(0.0, 0.0, 0.0), axis=(0.0, 0.0, 1.0)):
    """Cylindrical coordinates about an axis: returns (theta in degrees (-180, 180], axial s, radius r)."""
    a = np.asarray(axis, float)
    a = a / np.linalg.norm(a)
    e1 = np.cross(a, [1.0, 0.0, 0.0] if abs(a[0]) < 0.9 else [0.0, 1.0, 0.0])
    e1 /= np.linalg.norm(e1)
    e2 = np.cross(a, e1)
    if np.allclose(a, [0, 0, 1]):  # keep the usual θ = atan2(y, x) for a z axis
        e1, e2 = np.array([1.0, 0, 0]), np.array([0, 1.0, 0])
    rel = points - np.asarray(center, float)
    s = rel @ a
    p, q = rel @ e1, rel @ e2
    return np.degrees(np.arctan2(q, p)), s, np.hypot(p, q)


def plot_field(results, name: str = "damage", out: str | None = "damage.png", frame: int = -1,
               deformed: bool | float = False, view: str = "auto", center=(0.0, 0.0, 0.0),
               axis=(0.0, 0.0, 1.0), vmin=None, vmax=None, cmap: str = "viridis",
               point_size: float | None = None, title: str | None = None, ax=None,
               length_unit: str = "mm", bins=None):
    """Scatter plot of scalar nodal field ``name`` at ``frame``, written to ``out`` (PNG).

    results    a Results or a path to an Exodus file
    deformed   False: reference configuration; True or a number: current positions
               x + scale·u (True = scale 1)
    view       2D: "xy" (auto). 3D: "xy", "xz", "yz" projections (auto = "xy", drawn in
               order of the field value, so damaged points stay visible through the
               thickness), "unrolled" (θ about ``axis`` through ``center`` versus
               axial position: the natural view of a tube) or "3d" (a perspective scatter)
    bins       None: a scatter plot of the points; an int or (nu, nv): for 2D views, the
               mean of the field over each cell of a nu x nv grid (through-thickness or
               through-wall average, drawn as an image; empty cells blank)
    ax         draw into this matplotlib Axes instead of a new figure (out may be None)
    Returns the matplotlib Axes.
    """
    own = not isinstance(results, Results)
    res = Results(results) if own else results
    try:
        values = res.field(name, frame)
        scale = 0.0 if deformed is False else (1.0 if deformed is True else float(deformed))
        pts = res.positions(frame, scale) if scale else res.coords
        f = {"m": 1.0, "mm": 1e3, "um": 1e6}[length_unit]
        if view == "auto":
            view = "xy"
        if res.dim == 2 and view not in ("xy",):
            raise ValueError("2D results support view='xy' only")
        if point_size is None:
            point_size = max(0.3, min(8.0, 2.0e4 / len(values)))
        newfig = ax is None
        if view == "3d":
            fig = plt.figure(figsize=(7, 6)) if newfig else ax.figure
            ax = fig.add_subplot(projection="3d") if newfig else ax
            order = np.argsort(values)
            sc = ax.scatter(*(f * pts[order].T), c=values[order], s=point_size, cmap=cmap,
                            vmin=vmin, vmax=vmax, linewidths=0, depthshade=False)
            ax.set_xlabel(f"x ({length_unit})"), ax.set_ylabel(f"y ({length_unit})")
            ax.set_zlabel(f"z ({length_unit})")
            span = np.ptp(f * pts, axis=0)
            ax.set_box_aspect(span / span.max())
        else:
            if view == "unrolled":
                theta, s, _ = unroll(pts, center, axis)
                u, v, xl, yl = theta, f * s, "θ (degrees)", f"axial position ({length_unit})"
            else:
                i, j = "xyz".index(view[0]), "xyz".index(view[1])
                u, v = f * pts[:, i], f * pts[:, j]
                xl, yl = f"{view[0]} ({length_unit})", f"{view[1]} ({length_unit})"
            if newfig:
                w, h = np.ptp(u), np.ptp(v)
                if view == "unrolled":
                    w, h = 1.6, 1.0
                aspect = h / w if w > 0 else 1.0
                fig, ax = plt.subplots(figsize=(8, max(2.5, min(10, 8 * aspect + 1))))
            if bins is None:
                order = np.argsort(values, kind="stable")
                sc = ax.scatter(u[order], v[order], c=values[order], s=point_size, cmap=cmap,
                                vmin=vmin, vmax=vmax, linewidths=0, rasterized=True)
            else:
                total, ue, ve = np.histogram2d(u, v, bins=bins, weights=values)
                count, _, _ = np.histogram2d(u, v, bins=(ue, ve))
                with np.errstate(invalid="ignore", divide="ignore"):
                    mean = np.where(count > 0, total / count, np.nan)
                sc = ax.pcolormesh(ue, ve, mean.T, cmap=cmap, vmin=vmin, vmax=vmax, rasterized=True)
            ax.set_xlabel(xl), ax.set_ylabel(yl)
            if view != "unrolled":
                ax.set_aspect("equal")
        t = res.times[frame] if res.num_frames else float("nan")
        ax.set_title(title if title is not None else
                     f"{name}, {'deformed' if scale else 'reference'} configuration, t = {t * 1e6:.1f} µs")
        ax.figure.colorbar(sc, ax=ax, label=name, shrink=0.8)
        if out is not None:
            ax.figure.savefig(out, dpi=130, bbox_inches="tight")
            if newfig:
                plt.close(ax.figure)
        return ax
    finally:
        if own:
            res.close()


def _main(argv=None):
    p = argparse.ArgumentParser(description="Plot a nodal field of a Peridot Exodus file to PNG.")
    p.add_argument("exodus")
    p.add_argument("field", nargs="?", default="damage")
    p.add_argument("png", nargs="?", default="damage.png")
    p.add_argument("--frame", type=int, default=-1)
    p.add_argument("--view", default="auto", choices=["auto", "xy", "xz", "yz", "unrolled", "3d"])
    p.add_argument("--deformed", nargs="?", const=1.0, type=float, default=0.0,
                   help="plot on x + SCALE·u (default SCALE 1)")
    a = p.parse_args(argv)
    with Results(a.exodus) as r:
        print(f"{a.exodus}: {len(r.coords)} points, dim {r.dim}, {r.num_frames} frames "
              f"(t = {r.times[0]:.3g} … {r.times[-1]:.3g} s), fields {', '.join(r.names)}")
        plot_field(r, a.field, a.png, frame=a.frame, deformed=a.deformed or False, view=a.view)
    print(f"wrote {a.png}")


if __name__ == "__main__":
    _main()
