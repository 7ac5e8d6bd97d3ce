#!/usr/bin/python3
r"""Line charts from sphark CSV time series (matplotlib, Agg backend, 150 dpi).

Several CSVs, one y column:
  charts.py --csv run_a.csv:"cleaning on" --csv run_b.csv:"cleaning off" \
            --x t --y mean_abs_div_v --logy --out div.png
Several y columns of one CSV:
  charts.py --csv run.csv --x t --y kinetic --y-extra thermal:"thermal energy" \
            --y-extra total:total --out energy.png
Every --csv may carry a legend label after the last ':' (default: the file name).
"""
import argparse
import csv
import math
import os
import sys
from atomic_save import save_figure  # noqa: E402


def fail(msg):
    print(f"charts.py: {msg}", file=sys.stderr)
    sys.exit(2)


def split_label(spec, default_label):
    """'path:label' -> (path, label); a bare path keeps default_label."""
    path, sep, label = spec.rpartition(":")
    if sep and path and label and not os.path.exists(spec):
        return path, label
    return spec, default_label


def read_csv(path):
    try:
        with open(path, newline="") as f:
            rows = list(csv.reader(f))
    except OSError as e:
        fail(f"--csv: cannot read '{path}': {e.strerror}")
    if not rows:
        fail(f"--csv: '{path}' is empty")
    header, body = rows[0], rows[1:]
    columns = {name: [] for name in header}
    for n, row in enumerate(body, start=2):
        if len(row) != len(header):
            fail(f"--csv: '{path}' line {n}: {len(row)} fields, header has {len(header)}")
        for name, cell in zip(header, row):
            try:
                columns[name].append(float(cell))
            except ValueError:
                fail(f"--csv: '{path}' line {n}: column '{name}': not a number '{cell}'")
    return columns


def column(columns, name, path, option):
    if name not in columns:
        fail(f"{option}: no column '{name}' in '{path}' (has: {', '.join(columns)})")
    return columns[name]


def main(argv=None):
    ap = argparse.ArgumentParser(
        description="Line charts from one or more CSV files (header row, numeric columns).",
        formatter_class=argparse.RawDescriptionHelpFormatter, epilog=__doc__)
    ap.add_argument("--csv", action="append", required=True, metavar="FILE[:LABEL]",
                    help="CSV file, optionally with a legend label (repeatable)")
    ap.add_argument("--x", required=True, help="column for the x axis, e.g. t")
    ap.add_argument("--y", required=True, help="column for the y axis")
    ap.add_argument("--y-extra", action="append", default=[], metavar="COL[:LABEL]",
                    help="more y columns from the (single) CSV, each its own line")
    ap.add_argument("--out", required=True, help="output PNG")
    ap.add_argument("--logy", action="store_true", help="logarithmic y axis")
    ap.add_argument("--logx", action="store_true", help="logarithmic x axis")
    ap.add_argument("--xlabel", help="x axis label (default: the x column)")
    ap.add_argument("--ylabel", help="y axis label (default: the y column)")
    ap.add_argument("--title", help="chart title")
    ap.add_argument("--styles", help="comma-separated matplotlib line styles, one per line in order "
                    "(e.g. '-,-,--,--'; default all solid)")
    ap.add_argument("--size", nargs=2, type=float, default=[6.4, 4.4], metavar=("W", "H"),
                    help="figure size in inches (default 6.4 4.4)")
    args = ap.parse_args(argv)

    if args.y_extra and len(args.csv) != 1:
        fail("--y-extra: only with a single --csv")

    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, ax = plt.subplots(figsize=tuple(args.size))
    series = []  # (x, y, label)
    for spec in args.csv:
        path, label = split_label(spec, os.path.basename(spec))
        cols = read_csv(path)
        x = column(cols, args.x, path, "--x")
        if args.y_extra:
            series.append((x, column(cols, args.y, path, "--y"), args.y if label == os.path.basename(spec) else label))
            for extra in args.y_extra:
                name, sep, elabel = extra.partition(":")
                series.append((x, column(cols, name, path, "--y-extra"), elabel if sep else name))
        else:
            series.append((x, column(cols, args.y, path, "--y"), label))

    styles = args.styles.split(",") if args.styles else []
    if len(styles) > len(series):
        fail(f"--styles: {len(styles)} styles for {len(series)} lines")
    styles += ["-"] * (len(series) - len(styles))
    for (x, y, label), style in zip(series, styles):
        if args.logy:  # non-positive values cannot be drawn on a log axis
            pts = [(a, b) for a, b in zip(x, y) if b > 0 and math.isfinite(b)]
            if len(pts) < len(y):
                print(f"charts.py: warning: {label}: {len(y) - len(pts)} non-positive values "
                      "left out of the log axis", file=sys.stderr)
            x, y = [p[0] for p in pts], [p[1] for p in pts]
        ax.plot(x, y, style, label=label, linewidth=1.4)
    if args.logy:
        ax.set_yscale("log")
    if args.logx:
        ax.set_xscale("log")
    ax.set_xlabel(args.xlabel or args.x)
    ax.set_ylabel(args.ylabel or args.y)
    if args.title:
        ax.set_title(args.title)
    ax.grid(True, which="both" if args.logy else "major", alpha=0.35)
    if len(series) > 1 or args.csv[0] != split_label(args.csv[0], None)[0]:
        ax.legend()
    fig.tight_layout()
    try:
        save_figure(fig, args.out, dpi=150)
    except OSError as e:
        fail(f"--out: cannot write '{args.out}': {e.strerror}")
    print(args.out)


if __name__ == "__main__":
    main()
