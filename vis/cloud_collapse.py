#!/usr/bin/python3
r"""Figures of the magnetised cloud collapse (examples/cloud_collapse; seed 000, Figs. 4-6):
  fig4_column_density.png  column density along y of the last frame, whole cloud and a zoom on
                           the sink (or the density maximum), one row per variant, log10 g/cm^2
  fig5_divb_error.png      mean h|div B|/|B| against t/t_ff
  fig6_momentum.png        |total linear momentum| against t/t_ff, with the bound on what the
                           terms other than the tensile correction can have changed
  collapse_history.png     maximum density, sink mass and the step limiters against t/t_ff
  cloud_collapse.py --out out/cloud_collapse
"""
import argparse
import csv
import math
import os
import sys

import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
from atomic_save import save_figure  # noqa: E402

VARIANTS = [("none", "no cleaning"), ("cleaning", "cleaning"),
            ("cleaning_resistivity", "cleaning + resistivity")]


def read_table(path):
    with open(path, newline="") as f:
        rows = list(csv.DictReader(f))
    if not rows:
        return None
    return {k: [float(r[k]) for r in rows] for k in rows[0]}


def read_map(path):
    with open(path) as f:
        head = f.readline().strip().split(",")
        rows = [[float(v) for v in line.split(",")] for line in f if line.strip()]
    axis, nx, ny = (int(v) for v in head[:3])
    x0, x1, y0, y1 = (float(v) for v in head[3:7])
    return {"axis": axis, "extent": (x0, x1, y0, y1), "sigma": rows, "nx": nx, "ny": ny}


def runs(out):
    found = []
    for key, label in VARIANTS:
        d = os.path.join(out, key)
        table = os.path.join(d, "diagnostics.csv")
        if os.path.exists(table):
            t = read_table(table)
            if t:
                found.append((key, label, d, t))
    return found


def log_map(m, floor):
    return [[math.log10(max(v, floor)) for v in row] for row in m["sigma"]]


def column_density_figure(found, out):
    fig, axes = plt.subplots(len(found), 2, figsize=(9, 4.2 * len(found)), squeeze=False)
    image = None
    for row, (key, label, d, table) in enumerate(found):
        full = os.path.join(d, "column_density_y.csv")
        zoom = os.path.join(d, "column_density_y_zoom.csv")
        if not (os.path.exists(full) and os.path.exists(zoom)):
            # a run that failed writes no maps: say so where its row would be
            for ax in axes[row]:
                ax.axis("off")
            axes[row][0].text(0.0, 0.5, f"{label}: no column density map -- the run ended at "
                              f"t = {table['t_over_tff'][-1]:.4f} t_ff\n(a failed or stopped run writes none; "
                              "its last frame and checkpoint are in its folder)", fontsize=10,
                              transform=axes[row][0].transAxes, va="center")
            continue
        whole, near = read_map(full), read_map(zoom)
        radius = (whole["extent"][1] - whole["extent"][0]) / 2.5   # the full map is 2.5 R wide
        for col, (m, title) in enumerate([(whole, "whole cloud"), (near, "zoom, 0.3 R wide")]):
            ax = axes[row][col]
            x0, x1, y0, y1 = (v / radius for v in m["extent"])
            peak = max(max(r) for r in m["sigma"])
            image = ax.imshow(log_map(m, 1e-6 * peak), origin="lower", extent=(x0, x1, y0, y1),
                              cmap="inferno", vmin=-2.5 if col == 0 else None)
            fig.colorbar(image, ax=ax, label="log10 column density  [g/cm^2]", shrink=0.85)
            if table.get("n_sinks") and table["n_sinks"][-1] > 0:
                sx, sz = table["sink_x"][-1] / radius, table["sink_z"][-1] / radius
                ax.plot([sx], [sz], "c+", ms=12, mew=2, label="sink")
                ax.legend(loc="upper right", fontsize=8)
            ax.set_xlabel("x / R")
            ax.set_ylabel("z / R")
            ax.set_title(f"{label}\n{title}, t = {table['t_over_tff'][-1]:.3f} t_ff", fontsize=9)  # (two lines: clear of the colour bar)
    fig.tight_layout()
    save_figure(fig, os.path.join(out, "fig4_column_density.png"))


def divb_figure(found, out):
    fig, ax = plt.subplots(figsize=(6.4, 4.4))
    for key, label, d, t in found:
        ax.semilogy(t["t_over_tff"], t["mean_h_divB_over_B"], label=label)
    ax.set_xlabel("t / t_ff")
    ax.set_ylabel("mean h |div B| / |B|")
    ax.set_title("divergence error (seed 000, Fig. 5)")
    ax.legend()
    ax.grid(alpha=0.3, which="both")
    save_figure(fig, os.path.join(out, "fig5_divb_error.png"))


def cumulative(t, rate):
    out, s = [0.0], 0.0
    for k in range(1, len(t)):
        s += 0.5 * (rate[k] + rate[k - 1]) * (t[k] - t[k - 1])
        out.append(s)
    return out


def momentum_figure(found, out):
    fig, ax = plt.subplots(figsize=(6.4, 4.4))
    for n, (key, label, d, t) in enumerate(found):
        c = f"C{n}"
        ax.semilogy(t["t_over_tff"], [max(v, 1e-30) for v in t["momentum_magnitude"]], c, label=label)
        bound = cumulative(t["t"], t["other_momentum_rate"])
        ax.semilogy(t["t_over_tff"], [max(v, 1e-30) for v in bound], c + ":",
                    label=f"{label}: bound of the other terms")
    ax.set_xlabel("t / t_ff")
    ax.set_ylabel("|total momentum|  [code units, M = 1]")
    ax.set_title("momentum conservation (seed 000, Fig. 6)")
    ax.legend(fontsize=8)
    ax.grid(alpha=0.3, which="both")
    save_figure(fig, os.path.join(out, "fig6_momentum.png"))


def history_figure(found, out):
    fig, axes = plt.subplots(1, 3, figsize=(14, 4.2))
    for n, (key, label, d, t) in enumerate(found):
        c = f"C{n}"
        axes[0].semilogy(t["t_over_tff"], t["max_density"], c, label=label)
        axes[1].plot(t["t_over_tff"], t["sink_mass"], c, label=label)
        axes[2].semilogy(t["t_over_tff"], t["dt_courant"], c, label=f"{label}: Courant")
        axes[2].semilogy(t["t_over_tff"], t["dt_force"], c + "--", label=f"{label}: force")
    axes[0].set_ylabel("maximum density  [g/cm^3]")
    axes[1].set_ylabel("sink mass  [M_cloud]")
    axes[2].set_ylabel("smallest stable step  [code time]")
    for ax in axes:
        ax.set_xlabel("t / t_ff")
        ax.grid(alpha=0.3, which="both")
        ax.legend(fontsize=7)
    fig.tight_layout()
    save_figure(fig, os.path.join(out, "collapse_history.png"))


def main():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--out", required=True, help="the example's output folder (holds one folder per variant)")
    a = p.parse_args()
    found = runs(a.out)
    if not found:
        sys.exit(f"cloud_collapse.py: no <variant>/diagnostics.csv under {a.out}")
    column_density_figure(found, a.out)
    divb_figure(found, a.out)
    momentum_figure(found, a.out)
    history_figure(found, a.out)


if __name__ == "__main__":
    main()
