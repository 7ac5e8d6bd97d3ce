#!/usr/bin/python3
r"""Charts of a gravitating-sphere run (examples/gravitating_sphere):
  energies.png          kinetic, thermal, potential and total energy against t
  lagrangian_radii.png  the 10/50/90 % Lagrangian radii against the exact free fall (uniform sphere)
  slice.png             the gas particles with |z| < 0.05 R of the last frame, coloured by log10
                        density, and every sink (a red star, its mass in the legend)
  gravitating_sphere.py --dir out/gravitating_sphere/uniform --sphere uniform
"""
import argparse
import csv
import glob
import math
import os
import sys

import matplotlib
import numpy as np
matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
from atomic_save import save_figure  # noqa: E402


def read(path):
    with open(path, newline="") as f:
        rows = list(csv.DictReader(f))
    return {k: [float(r[k]) for r in rows] for k in rows[0]}


def energies(d, out, sphere):
    fig, ax = plt.subplots(figsize=(6.4, 4.4))
    for key, label in [("kinetic_energy", "kinetic"), ("thermal_energy", "thermal"),
                       ("potential_energy", "potential"), ("total_energy", "total")]:
        ax.plot(d["t"], d[key], label=label)
    ax.set_xlabel("t  [(R^3/GM)^(1/2)]")
    ax.set_ylabel("energy  [GM^2/R]")
    ax.set_title(f"{sphere} sphere: energies")
    ax.legend()
    ax.grid(alpha=0.3)
    save_figure(fig, os.path.join(out, "energies.png"))


def radii(d, out):
    fig, ax = plt.subplots(figsize=(6.4, 4.4))
    for f, c in [("10", "C0"), ("50", "C1"), ("90", "C2")]:
        ax.plot(d["t"], d["lagrangian_radius_" + f], c, label=f"{f} % (SPH)")
        exact = [(t, r) for t, r in zip(d["t"], d["free_fall_radius_" + f]) if math.isfinite(r)]
        if exact:
            ax.plot([p[0] for p in exact], [p[1] for p in exact], c + "--", label=f"{f} % (free fall)")
    ax.set_xlabel("t  [(R^3/GM)^(1/2)]")
    ax.set_ylabel("Lagrangian radius  [R]")
    ax.set_title("uniform sphere: Lagrangian radii against the exact free fall")
    ax.legend(fontsize=8)
    ax.grid(alpha=0.3)
    save_figure(fig, os.path.join(out, "lagrangian_radii.png"))


def density_slice(out):
    frames = sorted(glob.glob(os.path.join(out, "sphere_*.vtp")))
    if not frames:
        return
    import vtk  # python3-vtk9
    from vtk.util.numpy_support import vtk_to_numpy
    r = vtk.vtkXMLPolyDataReader()
    r.SetFileName(frames[-1])
    r.Update()
    poly = r.GetOutput()
    x = vtk_to_numpy(poly.GetPoints().GetData())
    rho = vtk_to_numpy(poly.GetPointData().GetArray("density"))
    species = poly.GetPointData().GetArray("species")  # 0 gas, 1 sink (runs with --sinks on)
    sink = vtk_to_numpy(species) == 1 if species is not None else np.zeros(len(x), dtype=bool)
    keep = (abs(x[:, 2]) < 0.05) & ~sink
    fig, ax = plt.subplots(figsize=(5.6, 5))
    sc = ax.scatter(x[keep, 0], x[keep, 1], c=[math.log10(v) for v in rho[keep]], s=2, cmap="viridis")
    if sink.any():  # every sink, whatever its z: a point mass, not part of the density field
        mass = vtk_to_numpy(poly.GetPointData().GetArray("mass"))[sink]
        ax.scatter(x[sink, 0], x[sink, 1], marker="*", s=160, c="red", edgecolors="k",
                   label=f"sink{'s' if sink.sum() > 1 else ''}: {', '.join(f'{m:.3g}' for m in mass)} M")
        ax.legend(loc="upper right", fontsize=8)
    fig.colorbar(sc, ax=ax, label="log10 density")
    ax.set_aspect("equal")
    ax.set_title(f"slice |z| < 0.05, {os.path.basename(frames[-1])}")
    save_figure(fig, os.path.join(out, "slice.png"))


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--dir", required=True)
    ap.add_argument("--sphere", default="uniform")
    a = ap.parse_args()
    path = os.path.join(a.dir, "diagnostics.csv")
    if not os.path.exists(path):
        print(f"gravitating_sphere.py: --dir: no {path}", file=sys.stderr)
        sys.exit(2)
    d = read(path)
    energies(d, a.dir, a.sphere)
    if a.sphere == "uniform":
        radii(d, a.dir)
    density_slice(a.dir)


if __name__ == "__main__":
    main()
