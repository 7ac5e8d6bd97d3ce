#!/usr/bin/env python3
"""Charts for examples/second_derivative_1d (seed 001, SPH second derivatives near boundaries in 1D).

usage: second_derivative_1d.py OUT_DIR [--markdown]
  Reads the CSV files written by build/bin/second_derivative_1d into OUT_DIR and writes
  fig2.png, fig4.png, fig5.png (the paper's Figures 2, 4, 5), kappa.png, convergence.png (Tables 1-5, ours
  as lines, the paper's printed values as markers) and cost.png (error vs wall time per method).
  --markdown: print Tables 1-5 side by side with the paper's values (for docs/) instead.
"""
import csv
import math
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
from atomic_save import save_figure  # noqa: E402

SIZES = [11, 21, 41, 81, 161, 321, 641, 1281]
# seed 001, Tables 1-5, e_N as printed (rows N = 11 ... 1281)
PAPER = {
    1: {"CSPM": [1.417163e+01, 1.429096e+01, 1.432149e+01, 1.432916e+01, 1.433108e+01, 1.433156e+01, 1.433168e+01, 1.433171e+01],
        "BIM": [2.541300e-01, 6.336412e-01, 1.535954e+00, 3.585439e+00, 7.712388e+00, 1.597336e+01, 3.249707e+01, 6.554494e+01],
        "ICSPM": [7.718045e-01, 1.965008e-01, 4.934995e-02, 1.235158e-02, 3.088777e-03, 7.722492e-04, 1.930658e-04, 4.826679e-05]},
    2: {"BIM": [3.089736e+00, 3.212382e-01, 4.607038e-01, 3.741568e-01, 2.328916e-01, 1.223207e-01, 5.701353e-02, 2.433353e-02]},
    3: {"CSPM": [8.904183e-02, 2.483635e-02, 6.473150e-03, 1.646873e-03, 4.149916e-04, 1.041376e-04, 2.608189e-05, 6.526331e-06],
        "BIM": [4.294576e-02, 6.346824e-03, 8.987147e-03, 6.850803e-03, 3.860040e-03, 1.885634e-03, 8.424516e-04, 3.528668e-04],
        "ICSPM": [5.251809e-03, 1.267271e-03, 3.155887e-04, 7.870952e-05, 1.967555e-05, 4.918146e-06, 1.229500e-06, 3.073762e-07]},
    4: {"CSPM": [1.496826e+01, 1.525255e+01, 1.514748e+01, 1.505215e+01, 1.596598e+01, 1.525074e+01, 1.498349e+01, 1.583231e+01],
        "BIM": [2.859126e+00, 2.746229e+00, 3.171560e+00, 3.737718e+00, 2.499004e+00, 1.901789e+00, 1.354160e+00, 5.048178e-01],
        "ICSPM": [4.079375e+00, 5.379078e+00, 5.413025e+00, 4.778599e-01, 1.485031e-01, 4.168193e-01, 3.230522e-02, 1.162366e-02]},
    5: {"CSPM": [1.325633e+00, 5.197703e+00, 8.532167e-01, 2.499042e-01, 4.005557e-01, 7.136763e-02, 1.748399e-02, 1.407180e-02],
        "BIM": [4.978369e-02, 1.044371e-01, 1.360910e-01, 1.736974e-01, 9.364072e-02, 6.289111e-02, 3.866721e-02, 1.000940e-02],
        "ICSPM": [6.168400e-02, 2.330835e-01, 6.058769e-03, 9.570489e-04, 2.929810e-04, 9.106805e-05, 3.425470e-05, 6.795946e-06]},
}
COLORS = {"CSPM": "tab:red", "BIM": "tab:blue", "ICSPM": "tab:green"}
MARKERS = {"CSPM": "s", "BIM": "^", "ICSPM": "o"}


def read_csv(path):
    with open(path) as fh:
        return list(csv.DictReader(line for line in fh if not line.startswith("#")))


def header_comment(path):
    with open(path) as fh:
        first = fh.readline()
    return first[1:].strip() if first.startswith("#") else ""


def table(out, number, suffix=""):
    rows = read_csv(os.path.join(out, f"table{number}{suffix}.csv"))
    t = {}
    for r in rows:
        t.setdefault(r["method"], []).append((int(r["N"]), float(r["e_N"]), r["p_N"]))
    return t


def num(s):
    return float(s) if s not in ("", None) else math.nan


def plot_direct(ax, path, title):
    rows = read_csv(path)
    x = [float(r["x"]) for r in rows]
    ax.plot(x, [float(r["exact"]) for r in rows], "k-", lw=1.2, label="exact $f''$")
    for m in ("CSPM", "BIM", "ICSPM"):
        ax.plot(x, [num(r[m]) for r in rows], MARKERS[m], color=COLORS[m], ms=4, mfc="none", label=m)
    ax.set_xlabel("x")
    ax.set_title(f"{title} ({header_comment(path)})", fontsize=9)
    ax.grid(alpha=0.3)
    ax.legend(fontsize=8)


def figures(out):
    fig, ax = plt.subplots(figsize=(6.4, 4.2))
    plot_direct(ax, os.path.join(out, "fig2.csv"), "Fig. 2: uniform particles")
    ax.set_ylabel("second derivative")
    fig.tight_layout()
    save_figure(fig, os.path.join(out, "fig2.png"), dpi=110)
    plt.close(fig)

    fig, axes = plt.subplots(2, 1, figsize=(6.4, 7.4))
    plot_direct(axes[0], os.path.join(out, "fig4_c2.csv"), "Fig. 4 top: random particles, c = 2")
    plot_direct(axes[1], os.path.join(out, "fig4_c3.csv"), "Fig. 4 bottom: random particles, c = 3")
    for ax in axes:
        ax.set_ylabel("second derivative")
    fig.tight_layout()
    save_figure(fig, os.path.join(out, "fig4.png"), dpi=110)
    plt.close(fig)

    path = os.path.join(out, "fig5.csv")
    rows = read_csv(path)
    x = [float(r["x"]) for r in rows]
    fig, axes = plt.subplots(2, 1, figsize=(6.4, 6.4), sharex=True, gridspec_kw={"height_ratios": [2, 1]})
    axes[0].plot(x, [float(r["exact"]) for r in rows], "k-", lw=1.2, label="exact $f$")
    for m in ("CSPM", "BIM", "ICSPM"):
        axes[0].plot(x, [float(r[m]) for r in rows], MARKERS[m], color=COLORS[m], ms=4, mfc="none", label=m)
        inner = rows[1:-1]  # the two boundary particles carry the exact Dirichlet values
        axes[1].semilogy([float(r["x"]) for r in inner], [abs(float(r[m]) - float(r["exact"])) for r in inner],
                         MARKERS[m] + "-", color=COLORS[m], ms=3, lw=0.6, label=m)
    axes[0].set_title(f"Fig. 5: solution of (5.18), random particles ({header_comment(path)}, c = 2)", fontsize=9)
    axes[0].set_ylabel("f")
    axes[1].set_ylabel("|u_i - f(x_i)| (interior particles)")
    axes[1].set_xlabel("x")
    for ax in axes:
        ax.grid(alpha=0.3)
        ax.legend(fontsize=8)
    fig.tight_layout()
    save_figure(fig, os.path.join(out, "fig5.png"), dpi=110)
    plt.close(fig)


def convergence(out):
    titles = {1: "Table 1: direct, uniform, c=2", 2: "Table 2: direct, uniform, BIM h=k²Δx",
              3: "Table 3: BVP, uniform", 4: "Table 4: direct, random", 5: "Table 5: BVP, random",
              6: "2nd function e^x sin3x: direct (T1 set-up)"}
    fig, axes = plt.subplots(2, 3, figsize=(13, 7.5))
    for k, ax in zip(range(1, 7), axes.flat):
        t = table(out, 1, "_expsin") if k == 6 else table(out, k)
        for m, rows in t.items():
            ax.loglog([r[0] for r in rows], [r[1] for r in rows], "-", color=COLORS[m], label=f"{m} (ours)")
            if k in PAPER and m in PAPER[k]:
                ax.loglog(SIZES, PAPER[k][m], MARKERS[m], color=COLORS[m], mfc="none", label=f"{m} (paper)")
        n = [11, 1281]
        ax.loglog(n, [1e-1 * (11 / v) ** 2 for v in n], "k:", lw=0.8, label="slope 2")
        ax.loglog(n, [1e-1 * (11 / v) for v in n], "k--", lw=0.8, label="slope 1")
        ax.set_title(titles[k], fontsize=9)
        ax.set_xlabel("N")
        ax.set_ylabel("$e_N$")
        ax.grid(alpha=0.3, which="both")
        ax.legend(fontsize=6, ncol=2)
    fig.tight_layout()
    save_figure(fig, os.path.join(out, "convergence.png"), dpi=80)
    plt.close(fig)


def cost(out):
    rows = read_csv(os.path.join(out, "timing.csv"))
    by = {}
    for r in rows:
        by.setdefault(r["config"], []).append(r)
    styles = {"CSPM c=2": ("tab:red", "s"), "ICSPM c=2": ("tab:green", "o"),
              "BIM c=2": ("tab:cyan", "v"), "BIM c=k^2": ("tab:blue", "^")}
    fig, axes = plt.subplots(1, 3, figsize=(14, 4.4))
    for cfg, rs in by.items():
        c, mk = styles.get(cfg, ("k", "x"))
        n = [int(r["N"]) for r in rs]
        ta = [float(r["assemble_s"]) for r in rs]
        axes[0].loglog(n, ta, mk + "-", color=c, label=cfg)
        axes[1].loglog([float(r["assemble_s"]) + float(r["apply_s"]) for r in rs],
                       [float(r["e_direct"]) for r in rs], mk + "-", color=c, label=cfg)
        axes[2].loglog([float(r["assemble_s"]) + float(r["solve_s"]) for r in rs],
                       [float(r["e_bvp"]) for r in rs], mk + "-", color=c, label=cfg)
    axes[0].set(xlabel="N", ylabel="assemble time [s]", title="cost of assembling the operator")
    axes[1].set(xlabel="assemble + apply time [s]", ylabel="$e_N$ (direct, Table 1/2)", title="direct f'': error vs cost")
    axes[2].set(xlabel="assemble + sparse LU solve time [s]", ylabel="$e_N$ (BVP, Table 3)",
                title="BVP (5.18): error vs cost")
    for ax in axes:
        ax.grid(alpha=0.3, which="both")
        ax.legend(fontsize=8)
    fig.tight_layout()
    save_figure(fig, os.path.join(out, "cost.png"), dpi=80)
    plt.close(fig)


def continuous_kappa(s_values):
    """kappa(x) of seed 001 (4.14), sign corrected, for x at distance s*h from an end (h = 1)."""
    import numpy as np
    t = np.linspace(-2.0, 2.0, 400001)  # t = y - x
    aq = np.abs(t)
    w = np.where(aq < 2, 3 / 128 * (2 - aq) ** 5 * (2 * t * t + 2.5 * aq + 1), 0.0)
    dw = np.where(aq < 2, 7 * 3 / 128 * t * (2 - aq) ** 4 * (2 * aq + 1), 0.0)  # dW/dx at x - y = -t
    res = []
    for s in s_values:
        m = t >= -s
        tt, ww, dd = t[m], w[m], dw[m]
        gt, gs = np.trapz(tt * dd, tt), np.trapz(tt * tt / 2 * ww, tt)
        m1, m2 = np.trapz(tt * ww, tt), np.trapz(tt * tt / 2 * dd, tt)
        res.append(1 - m2 * m1 / (gt * gs))
    return res


def kappa_chart(out):
    rows = read_csv(os.path.join(out, "kappa.csv"))
    s = [float(r["s"]) for r in rows]
    fig, axes = plt.subplots(2, 1, figsize=(6.4, 6.4), sharex=True)
    grid = [0.02 * k for k in range(126)]
    axes[0].plot(grid, continuous_kappa(grid), "k-", lw=1.2, label="continuous (4.14), corrected sign")
    axes[0].plot(s, [float(r["kappa"]) for r in rows], ".", color="tab:green", ms=3,
                 label=r"discrete $\kappa_i$, 10 random sets, N = 641, c = 2")
    axes[0].axhline(0, color="gray", lw=0.6)
    axes[0].set_ylabel(r"$\kappa$")
    axes[0].legend(fontsize=8)
    axes[1].semilogy(s, [float(r["err_cspm"]) for r in rows], "s", color=COLORS["CSPM"], ms=2, label="CSPM")
    axes[1].semilogy(s, [float(r["err_icspm"]) for r in rows], ".", color=COLORS["ICSPM"], ms=3, label="ICSPM")
    axes[1].set_ylabel(r"$|\langle f''\rangle_i - f''(x_i)|$")
    axes[1].set_xlabel("distance to the nearest end / h")
    axes[1].legend(fontsize=8)
    for ax in axes:
        ax.grid(alpha=0.3)
    axes[0].set_title(r"ICSPM divides by $\kappa_i$, which vanishes about 0.3 h from the boundary", fontsize=9)
    fig.tight_layout()
    save_figure(fig, os.path.join(out, "kappa.png"), dpi=100)
    plt.close(fig)


def markdown(out):
    for k in range(1, 6):
        t = table(out, k)
        print(f"\n**Table {k}** (ours | paper)\n")
        head = "| N |" + "".join(f" {m} ours | {m} paper | p ours | p paper |" for m in t)
        print(head)
        print("|---:|" + "---:|---:|---:|---:|" * len(t))
        for i, n in enumerate(SIZES):
            line = f"| {n} |"
            for m, rows in t.items():
                if i >= len(rows):
                    line += " | | | |"
                    continue
                e, p = rows[i][1], rows[i][2]
                ep = PAPER[k][m][i]
                pp = "" if i == 0 else f"{math.log(PAPER[k][m][i - 1] / ep) / math.log(2):.4f}"
                line += f" {e:.6e} | {ep:.6e} | {p} | {pp} |"
            print(line)


def main(argv):
    if len(argv) < 2 or argv[1] in ("-h", "--help"):
        print(__doc__)
        return 0 if len(argv) >= 2 else 2
    out = argv[1]
    if not os.path.isdir(out):
        print(f"second_derivative_1d.py: invalid value '{out}' for OUT_DIR: not a directory", file=sys.stderr)
        return 2
    if "--markdown" in argv[2:]:
        markdown(out)
        return 0
    figures(out)
    convergence(out)
    kappa_chart(out)
    if os.path.exists(os.path.join(out, "timing.csv")):
        cost(out)
    print(f"wrote fig2.png fig4.png fig5.png convergence.png kappa.png cost.png in {out}")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
