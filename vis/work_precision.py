#!/usr/bin/python3
r"""Work-precision charts and summary tables of examples/stepper_study (issue 7).

  work_precision.py --dir out/stepper_study/drop

Reads <dir>/work_precision.csv, <dir>/stability.csv and <dir>/reference.csv (any may be
missing) and writes, in <dir>:
  work_precision_time.png      time-integration error (vs the reference run) against CPU time
                               and against RHS evaluations, log-log, one line a method and mode
  work_precision_position.png  RMS position difference vs the reference run, same axes
  work_precision_total.png     error against the scene's exact solution (space + time) vs CPU
  stability.png                largest stable fixed CFL number per method; mean CFL number of
                               the adaptive runs without the cap
  summary.md                   the tables of docs/time_integration.md
"""
import argparse
import csv
import math
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
from atomic_save import save_figure, write_text  # noqa: E402

FLOOR = 1e-15  # errors below this (round-off) are drawn at the floor
LEVELS = [1e-2, 1e-3, 1e-4, 1e-6, 1e-8]
LEAPFROGS = ("leapfrog", "leapfrog-rev")

# What each error column measures, per scene: (time_error, position_error, error vs exact).
LABELS = {
    "drop": ("max relative semi-axis difference vs reference run",
             "max RMS position difference / R vs reference run",
             "max relative semi-axis error vs exact solution"),
    "disc": ("max relative cleaning-energy difference vs reference run",
             "max RMS field difference (B / B0, psi / (c_h B0)) vs reference run",
             "max relative change of the cleaning energy (exact invariant)"),
    "disc_damped": ("max relative cleaning-energy difference vs reference run",
                    "max RMS field difference (B / B0, psi / (c_h B0)) vs reference run",
                    None),
    "orszag_tang": ("max L1 density difference / rho0 vs reference run",
                    "max RMS position difference / box vs reference run",
                    None),
    "lattice": ("max RMS velocity difference / v0 vs reference run",
                "max RMS position difference / R vs reference run",
                None),
}
SHORT_LABELS = {"drop": ("semi-axis time error", "RMS position time error / R", "semi-axis error vs exact"),
                "disc": ("cleaning-energy time error", "RMS field time error", "cleaning-energy change"),
                "disc_damped": ("cleaning-energy time error", "RMS field time error", None),
                "orszag_tang": ("L1 density time error", "RMS position time error", None),
                "lattice": ("RMS velocity time error / v0", "RMS position time error / R", None)}


def fail(msg):
    print(f"work_precision.py: {msg}", file=sys.stderr)
    sys.exit(2)


def read(path):
    if not os.path.exists(path):
        return []
    with open(path, newline="") as f:
        rows = list(csv.DictReader(f))
    for r in rows:
        for k, v in list(r.items()):
            try:
                r[k] = float(v)
            except (TypeError, ValueError):
                pass
    return rows


def short(method):
    m = method.replace("ARKODE_", "")
    return {"ark-imex": "ARK-IMEX 436L2SA", "leapfrog": "leapfrog KDK",
            "leapfrog-rev": "leapfrog-rev (2 RHS/step)"}.get(m, m)


def stages(method):
    """RHS evaluations per step by the table's name (FSAL tables reuse one: BS3 3, DP5 6)."""
    if method == "leapfrog":
        return 1
    if method == "leapfrog-rev":
        return 2
    if method == "ark-imex":
        return 6
    nums = [int(t) for t in method.split("_") if t.isdigit()]
    s = nums[0] if nums else 1
    return s - 1 if short(method) in ("BOGACKI_SHAMPINE_4_2_3", "DORMAND_PRINCE_7_4_5") else s


def curve_key(r):
    return (r["method"], r["mode"])


def curve_label(key):
    m, mode = key
    if m in LEAPFROGS:
        return f"{short(m)} (fixed CFL)"
    return f"{short(m)} ({mode})"


def curves(rows):
    out = {}
    for r in rows:
        if r["status"] != "ok" or not isinstance(r["rhs_evals"], float):
            continue
        out.setdefault(curve_key(r), []).append(r)
    for k in out:
        out[k].sort(key=lambda r: r["rhs_evals"])
    return out


def styles(keys):
    methods = sorted({k[0] for k in keys}, key=lambda m: (m in LEAPFROGS, m))
    cmap = plt.get_cmap("tab10")
    colour = {m: cmap(i % 10) for i, m in enumerate(methods)}
    colour["leapfrog"] = "black"
    colour["leapfrog-rev"] = "dimgrey"
    dash = {"capped": "-", "uncapped": "--", "fixed": ":"}
    mark = {"capped": "o", "uncapped": "s", "fixed": "^"}
    return {k: dict(color=colour[k[0]], linestyle=dash.get(k[1], "-"), marker=mark.get(k[1], "o"),
                    markersize=4, linewidth=1.2) for k in keys}


def plot_curves(ax, cs, st, x, y, xlabel, ylabel):
    for k, pts in sorted(cs.items()):
        pts = [p for p in pts if not math.isnan(p[y])]
        if not pts:
            continue
        xs = [p[x] for p in pts]
        ys = [max(p[y], FLOOR) for p in pts]
        ax.loglog(xs, ys, label=curve_label(k), **st[k])
    ax.set_xlabel(xlabel)
    ax.set_ylabel(ylabel)
    ax.grid(True, which="both", alpha=0.3)


def work_precision_chart(cs, path, y, ylabel, title, both=True):
    st = styles(cs.keys())
    n = 2 if both else 1
    fig, axes = plt.subplots(1, n, figsize=(7.5 * n, 6.5), squeeze=False)
    plot_curves(axes[0][0], cs, st, "cpu_s", y, "process CPU time [s] (shared machine: noisy)", ylabel)
    if both:
        plot_curves(axes[0][1], cs, st, "rhs_evals", y, "RHS evaluations", ylabel)
    handles, labels = axes[0][0].get_legend_handles_labels()
    fig.legend(handles, labels, loc="lower center", ncol=4, fontsize=7)
    fig.suptitle(title)
    fig.tight_layout(rect=(0, 0.13, 1, 0.95))
    save_figure(fig, path, dpi=150)
    plt.close(fig)
    print(path)


def stability_chart(stab, rows, path):
    fig, (a, b) = plt.subplots(1, 2, figsize=(15, 6.5))
    if stab:
        stab = sorted(stab, key=lambda r: r["cfl_stable"])
        names = [short(r["method"]) for r in stab]
        a.barh(names, [r["cfl_stable"] for r in stab], color="tab:blue", label="largest stable CFL")
        a.barh(names, [r["cfl_stable"] / stages(r["method"]) for r in stab], color="tab:orange", height=0.4,
               label="per RHS evaluation (stable CFL / RHS per step)")
        a.axvline(0.25, color="grey", linestyle="--", linewidth=1, label="cap of the capped adaptive runs (0.25)")
        a.set_xlabel("CFL number  dt / (h / (c + |v|))")
        a.legend(fontsize=8)
        a.grid(True, axis="x", alpha=0.3)
        a.tick_params(axis="y", labelsize=7)
        a.set_title(f"fixed-step stability limit (horizon {stab[0]['horizon']:g}, |dE| <= {stab[0]['energy_tolerance']:g} E0)")
    unc = [r for r in rows if r["mode"] == "uncapped"]
    by = {}
    for r in unc:
        by.setdefault(r["method"], []).append(r)
    for m, pts in sorted(by.items()):
        pts.sort(key=lambda r: r["rtol"])
        ok = [p for p in pts if p["status"] == "ok"]
        line, = b.semilogx([p["rtol"] for p in ok], [p["mean_cfl"] for p in ok], marker="o", label=short(m))
        lim = [r["cfl_stable"] for r in stab if r["method"] == m]
        if lim:
            b.axhline(lim[0], color=line.get_color(), linestyle=":", linewidth=1)
        bad = [p for p in pts if p["status"] != "ok"]
        if bad:
            b.semilogx([p["rtol"] for p in bad], [p["mean_cfl"] for p in bad], "x", color=line.get_color(), markersize=9)
    b.set_xlabel("rtol (adaptive, no CFL cap; x = run failed/blew up/over budget)")
    b.set_yscale("log")
    b.set_ylabel("mean CFL number of the accepted steps (dotted: fixed-step stability limit)")
    b.set_title("where the error control puts the step without the cap")
    b.grid(True, which="both", alpha=0.3)
    b.legend(fontsize=7)
    fig.tight_layout()
    save_figure(fig, path, dpi=150)
    plt.close(fig)
    print(path)


def describe_point(r):
    if r["mode"] == "fixed":
        return f"{short(r['method'])} fixed CFL {r['cfl']:g}"
    return f"{short(r['method'])} {r['mode']} rtol {r['rtol']:.0e}"


def cheapest(pts, metric, level, work):
    ok = [p for p in pts if p[metric] <= level]
    return min(ok, key=lambda p: p[work]) if ok else None


def fmt(v, spec=".3g"):
    return "—" if v is None or (isinstance(v, float) and math.isnan(v)) else format(v, spec)


def summary(rows, stab, ref, path, scene):
    ok = [r for r in rows if r["status"] == "ok"]
    lf = [r for r in ok if r["method"] in LEAPFROGS]
    tl, pl, el = SHORT_LABELS.get(scene, SHORT_LABELS["drop"])
    cs = curves(rows)
    out = []
    if ref:
        out.append(f"Reference run: {describe_point(ref[0])}, {int(ref[0]['rhs_evals'])} RHS evaluations; "
                   f"check run {describe_point(ref[1]) if len(ref) > 1 else '—'}: {tl} "
                   f"{fmt(ref[1]['time_error'] if len(ref) > 1 else None)}, {pl} "
                   f"{fmt(ref[1]['position_error'] if len(ref) > 1 else None)} (the floor of the time errors).\n")
        if el:
            out.append(f"Error of the reference run against the exact solution ({el}): {fmt(ref[0]['error'])}.\n")
    metrics = [("time_error", f"{tl} (vs the reference run)"), ("position_error", f"{pl} (vs the reference run)")]
    if el:
        metrics.append(("error", f"{el} (vs the exact solution: space + time)"))
    for metric, name in metrics:
        out.append(f"\n### Cheapest run per accuracy: {name}\n")
        out.append("| accuracy | cheapest run (RHS evals) | RHS evals | CPU s | cheapest leapfrog | leapfrog RHS | "
                   "cost / leapfrog (RHS) | cost / leapfrog (CPU) |")
        out.append("|---|---|---|---|---|---|---|---|")
        for lev in LEVELS:
            c = cheapest([r for r in ok if not math.isnan(r[metric])], metric, lev, "rhs_evals")
            l = cheapest(lf, metric, lev, "rhs_evals")
            lc = cheapest(lf, metric, lev, "cpu_s")
            no_lf = "no leapfrog run (the scene cannot run it)" if not lf else "not reached"
            out.append(f"| {lev:.0e} | {describe_point(c) if c else 'not reached'} | {fmt(c and c['rhs_evals'], '.0f')} | "
                       f"{fmt(c and c['cpu_s'], '.2f')} | {describe_point(l) if l else no_lf} | "
                       f"{fmt(l and l['rhs_evals'], '.0f')} | "
                       f"{fmt(c['rhs_evals'] / l['rhs_evals'] if c and l else None, '.2f')} | "
                       f"{fmt(c['cpu_s'] / lc['cpu_s'] if c and lc and lc['cpu_s'] > 0 else None, '.2f')} |")
        out.append(f"\nCost (RHS evaluations) of every method and mode to reach each {name.split(' (')[0]}, "
                   "relative to the cheapest leapfrog run reaching it in brackets:\n")
        out.append("| method (mode) | " + " | ".join(f"{lev:.0e}" for lev in LEVELS) + " |")
        out.append("|---|" + "---|" * len(LEVELS))
        for k, pts in sorted(cs.items()):
            cells = []
            for lev in LEVELS:
                c = cheapest(pts, metric, lev, "rhs_evals")
                l = cheapest(lf, metric, lev, "rhs_evals")
                cells.append("—" if not c else f"{c['rhs_evals']:.0f}" + (f" ({c['rhs_evals'] / l['rhs_evals']:.2f}×)" if l else ""))
            out.append(f"| {curve_label(k)} | " + " | ".join(cells) + " |")
    if stab:
        out.append("\n### Stability limits (fixed step, CFL number = dt / (h / (c + |v|)max at t = 0))\n")
        out.append("| method | largest stable CFL | smallest unstable CFL | RHS per step | stable CFL per RHS | first unstable trial hit |")
        out.append("|---|---|---|---|---|---|")
        for r in sorted(stab, key=lambda r: -r["cfl_stable"]):
            reason = str(r.get("unstable_reason", "")).split(";")[0][:70]
            out.append(f"| {short(r['method'])} | {r['cfl_stable']:.3g} | {r['cfl_unstable']:.3g} | {stages(r['method'])} | "
                       f"{r['cfl_stable'] / stages(r['method']):.3g} | {reason} |")
    unc = [r for r in rows if r["mode"] == "uncapped"]
    if unc:
        rtols = sorted({r["rtol"] for r in unc}, reverse=True)
        out.append("\n### Adaptive runs without the CFL cap: mean CFL number of the accepted steps (rejected steps)\n")
        out.append("| method | " + " | ".join(f"{t:.0e}" for t in rtols) + " |")
        out.append("|---|" + "---|" * len(rtols))
        for m in sorted({r["method"] for r in unc}):
            cells = []
            for t in rtols:
                rr = [r for r in unc if r["method"] == m and r["rtol"] == t]
                if not rr:
                    cells.append("")
                    continue
                r = rr[0]
                tag = "" if r["status"] == "ok" else f" **{r['status']}**"
                cells.append(f"{r['mean_cfl']:.3g} ({int(r['rejected'])}){tag}")
            out.append(f"| {short(m)} | " + " | ".join(cells) + " |")
    for mode in ("uncapped", "capped"):
        rr = [r for r in rows if r["mode"] == mode]
        if not rr:
            continue
        rtols = sorted({r["rtol"] for r in rr}, reverse=True)
        out.append(f"\n### Adaptive runs, {mode}: {tl} / {el or 'no exact solution'}\n")
        out.append("| method | " + " | ".join(f"{t:.0e}" for t in rtols) + " |")
        out.append("|---|" + "---|" * len(rtols))
        for m in sorted({r["method"] for r in rr}):
            cells = []
            for t in rtols:
                x = [r for r in rr if r["method"] == m and r["rtol"] == t]
                cells.append(f"{x[0]['time_error']:.1e} / {fmt(x[0]['error'], '.1e')}" if x else "")
            out.append(f"| {short(m)} | " + " | ".join(cells) + " |")
    write_text(path, "\n".join(out) + "\n")
    print(path)


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--dir", required=True, help="stepper_study output directory")
    a = ap.parse_args()
    if not os.path.isdir(a.dir):
        fail(f"--dir: '{a.dir}' is not a directory")
    rows = read(os.path.join(a.dir, "work_precision.csv"))
    stab = read(os.path.join(a.dir, "stability.csv"))
    ref = read(os.path.join(a.dir, "reference.csv"))
    if not rows and not stab:
        fail(f"--dir: no work_precision.csv or stability.csv in '{a.dir}'")
    scene = (rows or stab)[0]["scene"]
    if rows:
        cs = curves(rows)
        tl, pl, el = LABELS.get(scene, LABELS["drop"])
        work_precision_chart(cs, os.path.join(a.dir, "work_precision_time.png"), "time_error", tl,
                             f"{scene}: time-integration error — work-precision")
        work_precision_chart(cs, os.path.join(a.dir, "work_precision_position.png"), "position_error", pl,
                             f"{scene}: time-integration error ({pl.split(' vs')[0].replace('max ', '')}) — work-precision")
        if el:
            work_precision_chart(cs, os.path.join(a.dir, "work_precision_total.png"), "error", el,
                                 f"{scene}: error against the exact solution / invariant")
    if stab or rows:
        stability_chart(stab, rows, os.path.join(a.dir, "stability.png"))
    summary(rows, stab, ref, os.path.join(a.dir, "summary.md"), scene)


if __name__ == "__main__":
    main()
