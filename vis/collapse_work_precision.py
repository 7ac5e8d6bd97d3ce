#!/usr/bin/env python3
"""Work against precision for the cloud collapse's time steppers (issue #17; docs/time_integration.md,
"Work-precision of the collapse"): for each run, the time error of its curves up to the end of the
reference run (the largest relative difference from the reference over the common diagnostics rows,
of the kinetic energy and of mean h|div B|/|B|; the maximum density is left out: which particle
is densest switches, so its curve is not smooth in the step) against its particle evaluations and
its wall time,
from <dir>/<variant>/diagnostics.csv and <dir>/summary_<variant>.csv.

    /usr/bin/python3 vis/collapse_work_precision.py OUT.png REF_DIR DIR=LABEL [DIR=LABEL ...] [--reference-label TEXT]

LABEL's first word names the stepper family (one colour and marker each). Prints a markdown table."""
import argparse
import csv
import os

import matplotlib
matplotlib.use('Agg')
import matplotlib.pyplot as plt

METRICS = [('kinetic_energy', 'kinetic energy'), ('mean_h_divB_over_B', 'mean h|div B|/|B|')]
MARKERS = ['o', 's', '^', 'D', 'v', 'P', 'X']


def rows_of(run_dir, variant):
    return list(csv.DictReader(open(os.path.join(run_dir, variant, 'diagnostics.csv'))))


def summary_of(run_dir, variant):
    rows = list(csv.DictReader(open(os.path.join(run_dir, f'summary_{variant}.csv'))))
    return rows[-1]


def curve_error(rows, ref, column):
    """Largest |run - ref| / |ref| over the rows both have (same output times)."""
    worst = 0.0
    for a, b in zip(rows, ref):
        if abs(float(a['t']) - float(b['t'])) > 1e-9 * max(1.0, abs(float(b['t']))):
            raise SystemExit(f'rows at different times: {a["t"]} / {b["t"]}')
        r = float(b[column])
        if r != 0:
            worst = max(worst, abs(float(a[column]) - r) / abs(r))
    return worst


def main():
    p = argparse.ArgumentParser(description=__doc__.split('\n')[0])
    p.add_argument('out')
    p.add_argument('reference')
    p.add_argument('runs', nargs='+', help='DIR=LABEL')
    p.add_argument('--variant', default='cleaning')
    p.add_argument('--reference-label', default=None, help='the reference run in the title (default: its folder)')
    a = p.parse_args()
    ref = rows_of(a.reference, a.variant)
    points = []
    for spec in a.runs:
        d, label = spec.split('=', 1)
        rows = rows_of(d, a.variant)
        if len(rows) < len(ref):
            raise SystemExit(f'{d}: {len(rows)} rows, the reference has {len(ref)}')
        s = summary_of(d, a.variant)
        errors = [curve_error(rows, ref, c) for c, _ in METRICS]
        points.append((label, float(s['particle_evals']), float(s['wall_s']), errors))
    families = list(dict.fromkeys(l.split()[0] for l, *_ in points))
    fig, ax = plt.subplots(2, 2, figsize=(12, 9))
    for m, (_, name) in enumerate(METRICS):
        for w, (work, unit) in enumerate([(1, 'particle evaluations'), (2, 'wall time (s, one thread)')]):
            axis = ax[m][w]
            for f, fam in enumerate(families):
                pts = sorted((pt for pt in points if pt[0].split()[0] == fam), key=lambda pt: pt[work])
                axis.loglog([pt[work] for pt in pts], [max(pt[3][m], 1e-16) for pt in pts], marker=MARKERS[f % 7],
                            label=fam)
                for pt in pts:
                    axis.annotate(pt[0].split(' ', 1)[1] if ' ' in pt[0] else '', (pt[work], max(pt[3][m], 1e-16)),
                                  fontsize=7, xytext=(3, 3), textcoords='offset points')
            axis.set_xlabel(unit)
            axis.set_ylabel(f'time error of the {name} curve')
            axis.grid(True, which='both', alpha=0.3)
            axis.legend(fontsize=8)
    t_end = float(ref[-1]['t_over_tff'])
    fig.suptitle(f'cloud collapse, {int(float(ref[0]["gas_particles"]))} particles, to {t_end:.3f} t_ff: '
                 f'time error against {a.reference_label or os.path.basename(a.reference.rstrip("/"))}')
    fig.tight_layout()
    fig.savefig(a.out, dpi=110)
    print("| run | particle evaluations | wall s | kinetic energy error | mean h|∇·B|/|B| error |")
    print('|---|---:|---:|---:|---:|')
    for label, evals, wall, errors in sorted(points, key=lambda pt: pt[1]):
        print(f'| {label} | {evals:,.0f} | {wall:.1f} | {errors[0]:.2e} | {errors[1]:.2e} |')


if __name__ == '__main__':
    main()
