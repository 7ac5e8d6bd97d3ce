#!/usr/bin/python3
"""Orszag-Tang figures of seed 000 (§IV-B) from an orszag_tang output directory:

  fig2_t0.5.png, fig2_t1.png  density, magnetic pressure and div B (rows) for each variant
                              (columns) at t = 0.5 and t = 1 (Fig. 2 of the seed is t = 1)
  fig3_mean_divB.png          mean h|div B|/|B| vs t for every variant found (Fig. 3)

  orszag_tang.py --dir out/orszag_tang
"""
import argparse
import csv
import math
import os
import sys
import xml.etree.ElementTree as ET

import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt
import matplotlib.tri as mtri
from atomic_save import save_figure  # noqa: E402

VARIANTS = [("none", "no control"), ("resistivity", "resistivity"), ("euler", "Euler potentials"),
            ("cleaning", "divergence cleaning"), ("cleaning_resistivity", "cleaning + resistivity")]


def fail(msg):
    print(f"orszag_tang.py: {msg}", file=sys.stderr)
    sys.exit(2)


def frame_at(run_dir, t_want):
    """The .vtp file of the series whose time is nearest t_want (from the .pvd)."""
    pvd = os.path.join(run_dir, "orszag_tang.pvd")
    if not os.path.exists(pvd):
        return None, None
    best = None
    for ds in ET.parse(pvd).getroot().iter("DataSet"):
        t = float(ds.get("timestep"))
        if best is None or abs(t - t_want) < abs(best[0] - t_want):
            best = (t, os.path.join(run_dir, ds.get("file")))
    return best if best else (None, None)


def read_vtp(path, names):
    """A frame: .vtp, or a distributed run's .pvtp (its pieces merged by the parallel reader)."""
    from vtkmodules.vtkIOXML import vtkXMLPolyDataReader, vtkXMLPPolyDataReader
    from vtkmodules.util.numpy_support import vtk_to_numpy
    r = vtkXMLPPolyDataReader() if path.endswith(".pvtp") else vtkXMLPolyDataReader()
    r.SetFileName(path)
    r.Update()
    pd = r.GetOutput()
    pts = vtk_to_numpy(pd.GetPoints().GetData())
    arrays = {n: vtk_to_numpy(pd.GetPointData().GetArray(n)) for n in names}
    return pts[:, 0], pts[:, 1], arrays


def triangulation(x, y):
    tri = mtri.Triangulation(x, y)
    # Mask the long triangles that the (non-periodic) Delaunay triangulation makes across edges.
    xt, yt = x[tri.triangles], y[tri.triangles]
    edge = max(abs(xt[:, 0] - xt[:, 1]).max(), 0)
    lengths = [((xt[:, i] - xt[:, j]) ** 2 + (yt[:, i] - yt[:, j]) ** 2) ** 0.5 for i, j in ((0, 1), (1, 2), (2, 0))]
    longest = lengths[0]
    for l in lengths[1:]:
        longest = longest.clip(min=l)
    spacing = 1.0 / math.sqrt(len(x))
    tri.set_mask(longest > 4 * spacing)
    return tri


def fig2(directory, t_want, out):
    found = [(v, label) for v, label in VARIANTS[:4] if os.path.isdir(os.path.join(directory, v))]
    if not found:
        return False
    rows = [("density", "density", "viridis"), ("magnetic_pressure", "magnetic pressure", "inferno"),
            ("div_B", "∇·B", "RdBu_r")]
    fig, axes = plt.subplots(3, len(found), figsize=(3.2 * len(found), 9.6), squeeze=False)
    frames = {}
    for v, label in found:
        t, path = frame_at(os.path.join(directory, v), t_want)
        if path is not None and abs(t - t_want) <= 1e-6:  # else the run did not reach t_want
            frames[v] = (t, read_vtp(path, [r[0] for r in rows]))
    # One div B colour scale for every column (as in the seed's Fig. 2, where the cleaned field
    # looks blank next to the others): the 99th percentile of |div B| over all panels.
    all_div = sorted(abs(float(z)) for _, (_, _, arr) in frames.values() for z in arr["div_B"])
    div_lim = all_div[int(0.99 * (len(all_div) - 1))] if all_div else 1.0
    t_seen = None
    for col, (v, label) in enumerate(found):
        if v not in frames:
            continue
        t_seen, (x, y, arr) = frames[v]
        tri = triangulation(x, y)
        for row, (name, title, cmap) in enumerate(rows):
            ax = axes[row][col]
            z = arr[name]
            if name == "div_B":
                lim = div_lim or 1.0
                im = ax.tripcolor(tri, z, shading="gouraud", cmap=cmap, vmin=-lim, vmax=lim)
            else:
                im = ax.tripcolor(tri, z, shading="gouraud", cmap=cmap)
            ax.set_aspect("equal")
            ax.set_xticks([])
            ax.set_yticks([])
            fig.colorbar(im, ax=ax, fraction=0.046, pad=0.02)
            if row == 0:
                ax.set_title(label)
            if col == 0:
                ax.set_ylabel(title)
    if t_seen is None:
        plt.close(fig)
        return False
    fig.suptitle(f"Orszag–Tang vortex, t = {t_seen:g}")
    fig.tight_layout()
    save_figure(fig, out, dpi=130)
    plt.close(fig)
    return True


def fig3(directory, out):
    fig, ax = plt.subplots(figsize=(6.4, 4.6))
    any_run = False
    for v, label in VARIANTS:
        path = os.path.join(directory, v, "diagnostics.csv")
        if not os.path.exists(path):
            continue
        with open(path, newline="") as f:
            rows = list(csv.DictReader(f))
        t = [float(r["t"]) for r in rows if float(r["t"]) > 0]
        e = [float(r["mean_h_divB_over_B"]) for r in rows if float(r["t"]) > 0]
        ax.semilogy(t, e, label=label)
        any_run = True
    if not any_run:
        return False
    ax.set_xlabel("t")
    ax.set_ylabel("mean h|∇·B|/|B|")
    ax.set_title("Orszag–Tang: average divergence error (seed 000 Fig. 3)")
    ax.grid(True, which="both", alpha=0.3)
    ax.legend()
    fig.tight_layout()
    save_figure(fig, out, dpi=150)
    plt.close(fig)
    return True


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--dir", required=True, help="output directory of orszag_tang")
    a = ap.parse_args()
    if not os.path.isdir(a.dir):
        fail(f"--dir: not a directory: {a.dir}")
    if not fig3(a.dir, os.path.join(a.dir, "fig3_mean_divB.png")):
        fail(f"--dir: no <variant>/diagnostics.csv in {a.dir}")
    for t in (0.5, 1.0):
        fig2(a.dir, t, os.path.join(a.dir, f"fig2_t{t:g}.png"))


if __name__ == "__main__":
    main()
