#!/usr/bin/env python3
"""The cloud collapse's curves for several runs side by side (docs/time_integration.md, "The
collapse's default, measured on the curves at two resolutions"): mean h|div B|/|B|, |momentum|
and the sink mass against t/t_ff, from each run's <dir>/<variant>/diagnostics.csv.

    /usr/bin/python3 vis/collapse_courant.py OUT.png DIR=LABEL [DIR=LABEL ...] [--variant cleaning]

Runs with the same sphere-particle count share a colour (the first row's gas_particles), and
take line styles in the order given."""
import argparse
import csv
import math
import os

import matplotlib
matplotlib.use('Agg')
import matplotlib.pyplot as plt

COLOURS = ['tab:blue', 'tab:red', 'tab:green', 'tab:purple', 'tab:orange']
STYLES = [':', '--', '-', '-.', (0, (5, 1, 1, 1))]
PANELS = [('mean_h_divB_over_B', 'mean h|div B|/|B|', True), ('momentum_magnitude', '|total momentum| (code units)', True),
          ('sink_mass', 'sink mass (M_sun)', False)]


def read(path):
    rows = list(csv.DictReader(open(path)))
    if not rows:
        raise SystemExit(f'{path}: no rows')
    return rows


def main():
    p = argparse.ArgumentParser(description=__doc__.split('\n')[0])
    p.add_argument('out')
    p.add_argument('runs', nargs='+', help='DIR=LABEL')
    p.add_argument('--variant', default='cleaning')
    p.add_argument('--t-min', type=float, default=0.9)
    a = p.parse_args()
    fig, ax = plt.subplots(1, 3, figsize=(15, 4.5))
    colour_of, styles_used = {}, {}
    for run in a.runs:
        directory, _, label = run.partition('=')
        rows = read(os.path.join(directory, a.variant, 'diagnostics.csv'))
        n = rows[0]['gas_particles']
        colour = colour_of.setdefault(n, COLOURS[len(colour_of) % len(COLOURS)])
        style = STYLES[styles_used.get(n, 0) % len(STYLES)]
        styles_used[n] = styles_used.get(n, 0) + 1
        rows = [r for r in rows if float(r['t_over_tff']) >= a.t_min]  # the window shown (and scaled)
        t = [float(r['t_over_tff']) for r in rows]
        for k, (column, _, _) in enumerate(PANELS):
            y = [float(r[column]) for r in rows]
            ax[k].plot(t, [0 if math.isnan(v) else v for v in y], color=colour, ls=style, lw=1.2, label=label or directory)
    for k, (_, title, log) in enumerate(PANELS):
        ax[k].set_xlabel('t / t_ff')
        ax[k].set_title(title)
        if log:
            ax[k].set_yscale('log')
    ax[2].legend(fontsize=8, loc='upper left')
    fig.suptitle(f'Cloud collapse, {a.variant}: the runs side by side')
    fig.tight_layout()
    fig.savefig(a.out, dpi=110)


if __name__ == '__main__':
    main()
