#!/usr/bin/python3
"""Fig. 1 of seed 000 (§IV-A): max h|div B|/|B| (left) and max h|div B|/B0 (right, B0 = 1/sqrt(4 pi);
the seed plots the unnormalised maximum) vs t for the free-boundary disc, the previous
(non-conservative) cleaning on top, the constrained cleaning below, each with sigma = 0
(hyperbolic) and sigma > 0 (hyperbolic/parabolic). Non-conservative runs stop when their
cleaning energy has grown 1e4-fold.

  cleaning_disc.py --dir out/cleaning_disc --out out/cleaning_disc/fig1_max_divB.png
"""
import argparse
import csv
import os
import sys

import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt
from atomic_save import save_figure  # noqa: E402


def read(path, column):
    with open(path, newline="") as f:
        rows = list(csv.DictReader(f))
    return [float(r["t"]) for r in rows], [float(r[column]) for r in rows]


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--dir", required=True, help="output directory of the cleaning_disc run")
    ap.add_argument("--out", required=True, help="PNG to write")
    a = ap.parse_args()
    panels = [("nonconservative", "previous (non-conservative) cleaning"),
              ("constrained", "constrained cleaning (seed 000)")]
    columns = [("max_h_divB_over_B", "max h|∇·B|/|B|"), ("max_h_divB_over_B0", "max h|∇·B| / B0")]
    fig, axes = plt.subplots(2, 2, figsize=(11, 7.2), sharex=True)
    for row, (form, title) in zip(axes, panels):
        for ax, (column, ylabel) in zip(row, columns):
            for suffix, label, style in (("sigma0", "hyperbolic (σ = 0)", "-"),
                                         ("damped", "hyperbolic/parabolic (σ > 0)", "--")):
                path = os.path.join(a.dir, f"{form}_{suffix}.csv")
                if not os.path.exists(path):
                    print(f"cleaning_disc.py: --dir: missing {path}", file=sys.stderr)
                    sys.exit(2)
                t, e = read(path, column)
                ax.semilogy(t, e, style, label=label)
            ax.set_title(title)
            ax.set_ylabel(ylabel)
            ax.grid(True, which="both", alpha=0.3)
            ax.legend()
    for ax in axes[-1]:
        ax.set_xlabel("t")
        ax.set_xlim(0, None)
    fig.tight_layout()
    save_figure(fig, a.out, dpi=150)


if __name__ == "__main__":
    main()
