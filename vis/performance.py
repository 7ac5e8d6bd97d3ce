#!/usr/bin/python3
r"""Cost per particle vs N from Google Benchmark JSON (bench/*, --benchmark_format=json).

  performance.py --json wcsph.json --json spmhd.json --json neighbours.json \
      --out docs/figures/performance/cost_per_particle.png [--table]

Plots the counter ns_per_particle of every single-thread row (threads = 1) against the counter
particles, one line per benchmark family (the name before the first '/', plus the dimension
of 3D families), log-log. --table also prints a Markdown table of all rows (N, threads,
ns per particle, pairs per particle, pair interactions per second).
"""
import argparse
import json
import os
import sys


def fail(msg):
    print(f"performance.py: {msg}", file=sys.stderr)
    sys.exit(2)


LABELS = {
    "BM_WcsphRhs": "WCSPH RHS (2D, velocity cleaning)",
    "BM_SpmhdRhs2D": "SPMHD RHS (2D, cleaning + resistivity)",
    "BM_SpmhdRhs3D": "SPMHD RHS (3D, cleaning + resistivity)",
    "BM_Build<2>": "neighbour build (2D)",
    "BM_Build<3>": "neighbour build (3D)",
}


def family(row):
    name = row["name"].split("/")[0]
    if (name == "BM_WcsphRhs" and "/clean:0/" in row["name"]) or "/shuffled:1" in row["name"]:
        return None  # single points (no-cleaning WCSPH, shuffled SPMHD): table only
    return name


def load(paths):
    rows = []
    for p in paths:
        if not os.path.exists(p):
            fail(f"--json: no such file '{p}'")
        try:
            with open(p) as f:
                data = json.load(f)
        except json.JSONDecodeError as e:
            fail(f"--json: '{p}' is not benchmark JSON ({e})")
        for b in data.get("benchmarks", []):
            if b.get("run_type", "iteration") != "iteration" or "ns_per_particle" not in b:
                continue
            rows.append(b)
    if not rows:
        fail("--json: no benchmark rows with an ns_per_particle counter")
    return rows


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--json", action="append", required=True, help="benchmark JSON file (repeatable)")
    ap.add_argument("--out", required=True, help="PNG to write")
    ap.add_argument("--table", action="store_true", help="print a Markdown table of every row")
    a = ap.parse_args()
    rows = load(a.json)

    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, ax = plt.subplots(figsize=(7.2, 5.4))
    series = {}
    for r in rows:
        fam = family(r)
        if fam is None or int(r.get("threads", 1)) != 1:
            continue
        series.setdefault(fam, []).append((r["particles"], r["ns_per_particle"]))
    markers = "osD^v<>"
    for k, (fam, pts) in enumerate(sorted(series.items())):
        pts.sort()
        ax.plot([p[0] for p in pts], [p[1] for p in pts], marker=markers[k % len(markers)],
                label=LABELS.get(fam, fam))
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_xlabel("particles N")
    ax.set_ylabel("CPU ns per particle per call (1 thread)")
    ax.set_title("sphark: cost per particle vs N")
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=8, loc="upper center", bbox_to_anchor=(0.5, -0.16), ncol=2)
    os.makedirs(os.path.dirname(os.path.abspath(a.out)), exist_ok=True)
    fig.tight_layout()
    fig.savefig(a.out, dpi=150)
    print(a.out)

    if a.table:
        print("| benchmark | N | threads | ns / particle | pairs / particle | pairs / s |")
        print("|---|---:|---:|---:|---:|---:|")
        for r in rows:
            note = " (no cleaning)" if "/clean:0/" in r["name"] else " (shuffled order)" if "/shuffled:1" in r["name"] else ""
            print(f"| {r['name'].split('/')[0]}{note} "
                  f"| {int(r['particles'])} | {int(r.get('threads', 1))} | {r['ns_per_particle']:.0f} "
                  f"| {r.get('pairs_per_particle', float('nan')):.1f} | {r.get('pairs_per_s', float('nan')):.3g} |")


if __name__ == "__main__":
    main()
