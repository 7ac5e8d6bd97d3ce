#!/usr/bin/env python3
"""Work against precision of the multirate steppers on the oscillator model (issue #17;
docs/time_integration.md, "Where MRIStep pays: the oscillator model"): the error at t = 2 against
the particle evaluations, one line per stepper, from the CSV of bench_multirate_oscillators.

    build/bin/bench_multirate_oscillators --benchmark_format=csv > wp.csv
    /usr/bin/python3 vis/multirate_work_precision.py wp.csv OUT.png

Prints a markdown table (stepper, setting, particle evaluations, error, wall ms)."""
import csv
import io
import sys

import matplotlib
matplotlib.use('Agg')
import matplotlib.pyplot as plt  # noqa: E402
from atomic_save import save_figure  # noqa: E402

STYLE = {'leapfrog': ('tab:blue', 'o'), 'erk-dp5': ('tab:orange', 's'), 'leapfrog-blocks': ('tab:green', '^'),
         'mri-erk33a': ('tab:red', 'D'), 'mri-erk45a': ('tab:purple', 'v')}


def rows_of(path):
    """The benchmark rows of Google Benchmark's CSV (its context lines come first)."""
    text = open(path).read()
    start = text.index('name,')
    return list(csv.DictReader(io.StringIO(text[start:])))


def main():
    if len(sys.argv) != 3:
        raise SystemExit(__doc__)
    rows = [r for r in rows_of(sys.argv[1]) if r.get('error_occurred', 'false') != 'true']
    series = {}
    print('| stepper | setting | particle evaluations | error | wall (ms) |')
    print('|---|---:|---:|---:|---:|')
    for r in rows:
        label = r['label'].strip('"')
        setting = r['name'].split('setting:')[1]
        evals, err = float(r['particle_evals']), float(r['error'])
        series.setdefault(label, []).append((evals, err))
        print(f'| {label} | {setting} | {evals:,.0f} | {err:.3g} | {float(r["real_time"]):.3g} |')
    fig, ax = plt.subplots(figsize=(6.4, 4.8))
    for label, points in series.items():
        colour, marker = STYLE.get(label, ('black', 'x'))
        points.sort()
        ax.loglog([p[0] for p in points], [p[1] for p in points], marker=marker, color=colour, label=label)
    ax.set_xlabel('particle evaluations to t = 2')
    ax.set_ylabel('error at t = 2: max |x - x*| + |v - v*| / w')
    ax.set_title('60 slow (w = 1..2) + 4 fast (w = 100) oscillators')
    ax.grid(True, which='both', alpha=0.3)
    ax.legend()
    fig.tight_layout()
    save_figure(fig, sys.argv[2], dpi=120)


if __name__ == '__main__':
    main()
