#!/usr/bin/env python3
"""Charts of the cylinder-lattice scene (seed 004, §8).

  cylinder_lattice.py fig9 OUT [maps...]   Fig. 9: v_y contours of the medium runs, OUT/<map>/fields_*.csv
  cylinder_lattice.py fig10 OUT            Fig. 10: mean t_max vs v0 per map, OUT/ensemble.csv (+ table)
  cylinder_lattice.py table OUT            OUT/ensemble_table.md: reach t_final, mean t_max, reasons
  cylinder_lattice.py compare OUT_A OUT_B [maps...]   the same map's v_y fields of two medium runs
                                           (e.g. two CFL numbers): RMS difference / RMS v_y, final and
                                           mean over the last 2 time units, beside each run's noise floor

Fig. 9: particle v_y is interpolated onto a 200 x 200 grid by the normalised SPH sum
f(x) = sum_b V_b f_b W(x - x_b, h_b) / sum_b V_b W(x - x_b, h_b) (Wendland C4, V_b = 1/rho_b up to the
equal mass, periodic box); heat map: mirror map, red contours: mirror, blue: nonlinear, levels
{0, +-1/12, +-1/6, +-1/4} as in the paper. Printed: RMS of the difference of the gridded fields
relative to the RMS of v_y, for the final frame and for the mean over the frames of the last 2 time units.
"""
import csv
import glob
import math
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

HALF = 0.5
R = 0.2
LEVELS = [-0.25, -1 / 6, -1 / 12, 0, 1 / 12, 1 / 6, 0.25]


def wendland_c4_2d(q):
    t = np.clip(0.5 * q, 0, 1)
    return 9 / (4 * math.pi) * (1 - t) ** 6 * (1 + 6 * t + 35 / 3 * t * t)


def read_frame(path):
    with open(path) as f:
        t = float(f.readline().split("=")[1])
        data = np.loadtxt(f, delimiter=",", skiprows=1)
    return t, data


def grid_vy(data, n=200):
    x, y, vy, rho, h = data[:, 0], data[:, 1], data[:, 3], data[:, 4], data[:, 5]
    dg = 2 * HALF / n
    centres = -HALF + (np.arange(n) + 0.5) * dg
    num = np.zeros((n, n))
    den = np.zeros((n, n))
    ix = np.floor((x + HALF) / dg).astype(int)
    iy = np.floor((y + HALF) / dg).astype(int)
    k = int(math.ceil(2 * h.max() / dg)) + 1
    vol = 1 / rho
    for di in range(-k, k + 1):
        for dj in range(-k, k + 1):
            gi = (ix + di) % n
            gj = (iy + dj) % n
            dx = centres[gi] - x
            dy = centres[gj] - y
            dx -= 2 * HALF * np.round(dx / (2 * HALF))
            dy -= 2 * HALF * np.round(dy / (2 * HALF))
            w = vol * wendland_c4_2d(np.hypot(dx, dy) / h) / h**2
            np.add.at(num, (gj, gi), w * vy)
            np.add.at(den, (gj, gi), w)
    f = np.where(den > 0, num / np.where(den > 0, den, 1), np.nan)
    X, Y = np.meshgrid(centres, centres)
    f[np.hypot(X, Y) < R] = np.nan
    return X, Y, f


def rel_rms(a, b):
    m = np.isfinite(a) & np.isfinite(b)
    return float(np.sqrt(np.mean((a[m] - b[m]) ** 2)) / np.sqrt(np.mean(0.5 * (a[m] ** 2 + b[m] ** 2))))


def fields(out, m, count):
    files = sorted(glob.glob(os.path.join(out, m, "fields_*.csv")))[:count]
    if not files:
        raise SystemExit(f"cylinder_lattice.py: no {out}/{m}/fields_*.csv")
    frames = [read_frame(p) for p in files]
    t_end = frames[-1][0]
    X, Y, last = grid_vy(frames[-1][1])
    late = [grid_vy(d)[2] for t, d in frames if t >= t_end - 2 - 1e-9]
    return X, Y, last, np.nanmean(np.array(late), axis=0) if late else last, t_end, len(late)


def fig9(out, maps):
    # the frames both runs have (a run still going, or stopped early, has fewer)
    count = min(len(glob.glob(os.path.join(out, m, "fields_*.csv"))) for m in maps)
    res = {m: fields(out, m, count) for m in maps}
    lines = []
    for kind, idx in (("final", 2), ("mean_last_2", 3)):
        fig, ax = plt.subplots(figsize=(6.4, 5.6))
        X, Y = res[maps[0]][0], res[maps[0]][1]
        base = res[maps[0]][idx]
        im = ax.pcolormesh(X, Y, base, cmap="viridis", vmin=-0.3, vmax=0.3, shading="auto")
        fig.colorbar(im, ax=ax, label=f"$v_y$ ({maps[0]} map)")
        colours = {"mirror": "red", "nonlinear": "blue"}
        for m in maps:
            f = np.ma.masked_invalid(res[m][idx])
            ax.contour(X, Y, f, levels=LEVELS, colors=colours.get(m, "k"), linewidths=0.9)
        ax.add_patch(plt.Circle((0, 0), R, color="white", zorder=3))
        ax.set_aspect("equal")
        ax.set_xlim(-HALF, HALF)
        ax.set_ylim(-HALF, HALF)
        what = f"t = {res[maps[0]][4]:.3g}" if kind == "final" else f"mean over last 2 time units ({res[maps[0]][5]} frames)"
        ax.set_title(f"$v_y$: heat map {maps[0]}; contours red = mirror, blue = nonlinear\n{what}", fontsize=9)
        fig.tight_layout()
        name = os.path.join(out, f"fig9_{kind}.png")
        fig.savefig(name, dpi=130)
        plt.close(fig)
        if len(maps) == 2:
            a, b = res[maps[0]][idx], res[maps[1]][idx]
            lines.append(f"{kind}: rms(vy_{maps[0]} - vy_{maps[1]}) / rms(vy) = {rel_rms(a, b):.3f}, "
                         f"rms(vy) {maps[0]} {np.sqrt(np.nanmean(a**2)):.4f}, {maps[1]} {np.sqrt(np.nanmean(b**2)):.4f}")
        print(name)
    if lines:
        # noise floor: final frame against the late mean, same map
        for m in maps:
            lines.append(f"noise floor {m}: rms(vy_final - vy_mean_last_2) / rms(vy) = {rel_rms(res[m][2], res[m][3]):.3f}")
        with open(os.path.join(out, "fig9_agreement.txt"), "w") as f:
            f.write("\n".join(lines) + "\n")
        print("\n".join(lines))


def compare(out_a, out_b, maps):
    for m in maps:
        count = min(len(glob.glob(os.path.join(o, m, "fields_*.csv"))) for o in (out_a, out_b))
        a, b = fields(out_a, m, count), fields(out_b, m, count)
        print(f"{m}: final {rel_rms(a[2], b[2]):.3f}, mean_last_2 {rel_rms(a[3], b[3]):.3f} "
              f"(noise floor {rel_rms(a[2], a[3]):.3f} / {rel_rms(b[2], b[3]):.3f}; t = {a[4]:.3g}, {a[5]} frames)")


def fig10(out):
    rows = list(csv.DictReader(open(os.path.join(out, "ensemble.csv"))))
    maps = sorted({r["map"] for r in rows}, key=lambda m: m != "mirror")
    fig, (a1, a2) = plt.subplots(1, 2, figsize=(11, 4.2))
    colours = {"mirror": "red", "nonlinear": "blue"}
    for m in maps:
        v0s = sorted({float(r["v0"]) for r in rows if r["map"] == m})
        mean, sd, lo, hi, frac = [], [], [], [], []
        for v in v0s:
            t = np.array([float(r["t_max"]) for r in rows if r["map"] == m and float(r["v0"]) == v])
            reach = [r["reason"] == "t_end" for r in rows if r["map"] == m and float(r["v0"]) == v]
            mean.append(t.mean())
            sd.append(t.std())
            lo.append(t.min())
            hi.append(t.max())
            frac.append(np.mean(reach))
        c = colours.get(m, "k")
        a1.errorbar(v0s, mean, yerr=sd, color=c, marker="o", capsize=3, label=f"{m} map (mean ± std)")
        a1.fill_between(v0s, lo, hi, color=c, alpha=0.12, label=f"{m}: min-max")
        a2.plot(v0s, frac, color=c, marker="o", label=m)
    a1.set_xlabel("$v_0$")
    a1.set_ylabel("$t_{max}$")
    a1.set_title("Maximum simulated time (seed 004 Fig. 10)")
    a1.legend(fontsize=8)
    a2.set_xlabel("$v_0$")
    a2.set_ylabel("fraction of runs reaching $t_{final}$")
    a2.set_ylim(-0.05, 1.05)
    a2.legend(fontsize=8)
    fig.tight_layout()
    name = os.path.join(out, "fig10.png")
    fig.savefig(name, dpi=130)
    print(name)


def table(out):
    """Markdown table: per v0 and map, runs reaching t_final, mean +- std of t_max, reasons."""
    rows = list(csv.DictReader(open(os.path.join(out, "ensemble.csv"))))
    maps = sorted({r["map"] for r in rows}, key=lambda m: m != "mirror")
    v0s = sorted({float(r["v0"]) for r in rows})
    head = "| v0 | " + " | ".join(f"{m}: reach t_end | {m}: mean t_max (std) | {m}: pen / acc / fail" for m in maps) + " |"
    lines = [head, "|" + "---|" * (1 + 3 * len(maps))]
    for v in v0s:
        cells = [f"{v:.2f}"]
        for m in maps:
            sel = [r for r in rows if r["map"] == m and float(r["v0"]) == v]
            t = np.array([float(r["t_max"]) for r in sel])
            n = len(sel)
            reach = sum(r["reason"] == "t_end" for r in sel)
            pen = sum(r["reason"] == "penetration" for r in sel)
            acc = sum(r["reason"] == "accumulation" for r in sel)
            cells += [f"{reach}/{n}", f"{t.mean():.2f} ({t.std():.2f})", f"{pen} / {acc} / {n - reach - pen - acc}"]
        lines.append("| " + " | ".join(cells) + " |")
    text = "\n".join(lines) + "\n"
    with open(os.path.join(out, "ensemble_table.md"), "w") as f:
        f.write(text)
    print(text)


if __name__ == "__main__":
    if len(sys.argv) < 3 or sys.argv[1] not in ("fig9", "fig10", "table", "compare"):
        raise SystemExit(__doc__)
    if sys.argv[1] == "compare" and len(sys.argv) >= 4:
        compare(sys.argv[2], sys.argv[3], sys.argv[4:] or ["mirror", "nonlinear"])
    elif sys.argv[1] == "fig9":
        fig9(sys.argv[2], sys.argv[3:] or ["mirror", "nonlinear"])
    elif sys.argv[1] == "fig10":
        fig10(sys.argv[2])
        table(sys.argv[2])
    else:
        table(sys.argv[2])
