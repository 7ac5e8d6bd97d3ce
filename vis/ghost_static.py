#!/usr/bin/env python3
"""Charts for examples/ghost_static (seed 004, Figs. 5-8): run as
   /usr/bin/python3 vis/ghost_static.py OUT_DIR
Reads fig5.csv, fig5_branch.csv, static_summary.csv, profile_<g>.csv, particles_<g>_{map,mirror}.csv
and writes fig5.png, fig6_cylinder.png, fig7_sphere.png, fig8_torus.png, slices_<g>.png."""
import csv
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
from atomic_save import save_figure  # noqa: E402


def read_csv(path):
    with open(path) as f:
        rows = list(csv.DictReader(f))
    cols = {}
    for k in rows[0].keys():
        cols[k] = np.array([float(r[k]) if r[k] != "" else np.nan for r in rows])
    return cols


def fig5(out):
    d = read_csv(os.path.join(out, "fig5.csv"))
    b = read_csv(os.path.join(out, "fig5_branch.csv"))
    fig, ax = plt.subplots(1, 2, figsize=(11, 4.5))
    s = d["s"]
    ax[0].plot(s, d["mirror"], "k--", label=r"mirror $\Psi_0$")
    ax[0].plot(s, d["cylinder"], label="cylinder (21)")
    ax[0].plot(s, d["sphere"], label="sphere (25)")
    ax[0].plot(s, d["torus_theta0"], label=r"torus $\theta=0$, $R/a=2.5$")
    ax[0].plot(s, d["torus_thetapi"], label=r"torus $\theta=\pi$, $R/a=2.5$")
    ax[0].set_xlabel("s (fluid side, R = a = 1)")
    ax[0].set_ylabel(r"$\psi(s)$")
    ax[0].set_title("Fig. 5: ghost coordinate vs inner coordinate")
    ax[0].legend(fontsize=8)
    ax[0].grid(alpha=0.3)
    ax[1].plot(b["s"], -b["s"], "k--", label=r"mirror $\Psi_0$")
    for key, lab in [("ra_2.01", "R/a = 2.01"), ("ra_2.00", "R/a = 2.00"), ("ra_1.99", "R/a = 1.99"),
                     ("ra_1.90", "R/a = 1.90")]:
        ax[1].plot(b["s"], b[key], label=r"torus $\theta=\pi$, " + lab)
    ax[1].set_xlim(-1, -0.6)
    ax[1].set_ylim(0.55, 1.05)
    ax[1].set_xlabel("s")
    ax[1].set_title(r"torus $\theta=\pi$ near $R/a=2$ (curves end where the ghost would cross the axis)",
                    fontsize=9)
    ax[1].legend(fontsize=8)
    ax[1].grid(alpha=0.3)
    fig.tight_layout()
    save_figure(fig, os.path.join(out, "fig5.png"), dpi=130)
    plt.close(fig)


def profile_fig(out, geo, number, H):
    prof = read_csv(os.path.join(out, f"profile_{geo}.csv"))
    fig, ax = plt.subplots(figsize=(8, 5))
    rng = np.random.default_rng(0)
    for kind, colour in [("mirror", "tab:red"), ("map", "tab:blue")]:
        p = read_csv(os.path.join(out, f"particles_{geo}_{kind}.csv"))
        idx = rng.choice(len(p["s"]), size=min(20000, len(p["s"])), replace=False)
        lab = r"$\Psi_0$ (mirror)" if kind == "mirror" else r"$\Psi$ (density-preserving)"
        ax.scatter(p["s"][idx], p["n"][idx], s=1, alpha=0.15, color=colour)
        ax.plot(prof["s"], prof["n_mirror" if kind == "mirror" else "n_map"], color=colour, lw=2,
                label=lab + " bin means")
    ax.axvline(0, color="k", lw=0.8)
    ax.axhline(1, color="k", lw=0.5, ls=":")
    ax.set_xlabel("s  (s < 0 inner, s > 0 ghosts)")
    ax.set_ylabel(r"node density $n / \langle n \rangle_{interior}$ (eq. 3)")
    ax.set_ylim(0, 1.6)
    ax.set_title(f"Fig. {number}: {geo}, node density of inner and ghost particles")
    ax.legend(loc="lower left", fontsize=9)
    ins = ax.inset_axes([0.55, 0.58, 0.42, 0.38])
    for kind, colour in [("mirror", "tab:red"), ("map", "tab:blue")]:
        ins.plot(prof["s"], prof["n_mirror" if kind == "mirror" else "n_map"], "o-", ms=3, color=colour)
    ins.axvline(0, color="k", lw=0.8)
    ins.axvline(H, color="gray", lw=0.8, ls="--")
    ins.axhline(1, color="k", lw=0.5, ls=":")
    ins.axhspan(0.99, 1.01, color="gray", alpha=0.2)
    ins.set_xlim(-1.5 * H, 2 * H)
    ins.set_ylim(0.7, 1.1)
    ins.set_title("zoom: |s| < 2H (dashed: s = H, band: 1%)", fontsize=8)
    ins.tick_params(labelsize=7)
    fig.tight_layout()
    save_figure(fig, os.path.join(out, f"fig{number}_{geo}.png"), dpi=130)
    plt.close(fig)


def slices(out, geo, H):
    """Particles in a thin slice through the geometry, coloured by node density (VTK stand-in)."""
    fig, ax = plt.subplots(1, 2, figsize=(11, 5))
    for k, kind in enumerate(["mirror", "map"]):
        p = read_csv(os.path.join(out, f"particles_{geo}_{kind}.csv"))
        if geo == "torus":  # poloidal cross-section at y ~ 0, x > 0
            sel = (np.abs(p["y"]) < 0.5 * H) & (p["x"] > 0)
            u, v = p["x"][sel], p["z"][sel]
        else:  # z ~ 0 cross-section
            sel = np.abs(p["z"]) < 0.5 * H
            u, v = p["x"][sel], p["y"][sel]
        sc = ax[k].scatter(u, v, c=p["n"][sel], s=4, cmap="coolwarm", vmin=0.6, vmax=1.4)
        ax[k].set_aspect("equal")
        ax[k].set_title(f"{geo}: inner + ghosts by " + (r"$\Psi_0$" if kind == "mirror" else r"$\Psi$"))
        fig.colorbar(sc, ax=ax[k], shrink=0.8, label=r"$n/\langle n\rangle$")
    fig.tight_layout()
    save_figure(fig, os.path.join(out, f"slices_{geo}.png"), dpi=110)
    plt.close(fig)


def main():
    if len(sys.argv) != 2:
        print("usage: ghost_static.py OUT_DIR", file=sys.stderr)
        return 2
    out = sys.argv[1]
    if os.path.exists(os.path.join(out, "fig5.csv")):
        fig5(out)
    summary = os.path.join(out, "static_summary.csv")
    if os.path.exists(summary):
        with open(summary) as f:
            rows = {r["geometry"]: r for r in csv.DictReader(f)}
        for geo, number in [("cylinder", 6), ("sphere", 7), ("torus", 8)]:
            if geo in rows:
                H = float(rows[geo]["H"])
                profile_fig(out, geo, number, H)
                slices(out, geo, H)
    print("ghost_static.py: charts written to", out)
    return 0


if __name__ == "__main__":
    sys.exit(main())
