#!/usr/bin/python3
"""Regenerates the validation pages' figures from the committed results.

Reads only committed files (validation/*/results/*/gauges_*.csv and the reference tables
beside the manifests) and writes PNGs into docs/validation/_figures/. The PNGs are committed
too, so building the docs does not need this script; rerun it after a results folder changes:

    /usr/bin/python3 docs/validation/make_figures.py

Needs numpy and matplotlib (Debian: python3-numpy, python3-matplotlib); takes a few seconds.
The normalisations are those of each case's validation.yaml (copied here as numbers, so the
script needs no YAML reader); the figures are for reading, not for the metrics, which
`swell validate NAME` computes.
"""
import os
import sys

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.normpath(os.path.join(HERE, "..", ".."))
VAL = os.path.join(ROOT, "validation")
OUT = os.path.join(HERE, "_figures")

sys.path.insert(0, VAL)
try:  # the project's shared look (Okabe-Ito colours with dashes and markers)
    import plot_style  # noqa: E402

    RUN = plot_style.RUN_STYLES
    REF = plot_style.REF_STYLES
except ImportError:  # validation/ moved or incomplete: plain matplotlib defaults
    import matplotlib

    matplotlib.use("Agg")
    RUN = [dict(color=c, ls=l, marker=m) for c, l, m in
           zip(["#0072B2", "#D55E00", "#009E73", "#CC79A7"], ["-", "--", "-.", ":"], "s^Dv")]
    REF = [dict(color="black", ls="-", marker="o"), dict(color="0.4", ls="--", marker="x")]
import matplotlib.pyplot as plt  # noqa: E402

plt.rcParams["svg.hashsalt"] = "swell"


def read_csv(path):
    """A Swell gauge CSV or a reference table: '#' lines skipped, one header line, then
    numbers ('nan' allowed). Returns {column name without unit: numpy array}."""
    with open(path) as f:
        lines = [ln for ln in f if ln.strip() and not ln.startswith("#")]
    names = [c.strip().split(" [")[0] for c in lines[0].split(",")]
    data = np.array([[float(v) for v in ln.split(",")] for ln in lines[1:]])
    return {n: data[:, i] for i, n in enumerate(names)}


def results(case, label):
    return os.path.join(VAL, case, "results", label)


def line(ax, t, v, style, label, every=None):
    """A run (style from RUN) or reference (REF) as a line with sparse markers."""
    n = len(t)
    ax.plot(t, v, color=style["color"], ls=style["ls"], marker=style["marker"],
            markevery=every or max(1, n // 12), ms=4, lw=1.2, label=label,
            mfc="white" if style in RUN else style["color"])


def points(ax, t, v, style, label):
    ax.plot(t, v, ls="none", marker=style["marker"], color=style["color"], ms=5, label=label)


def window(ax, t0, t1):
    ax.axvspan(t0, t1, color="0.92", zorder=0)
    for x in (t0, t1):
        ax.axvline(x, color="0.6", ls="--", lw=0.8, zorder=0)


def finish(fig, axes, name):
    for ax in np.atleast_1d(axes).ravel():
        ax.grid(alpha=0.3)
    handles, labels = np.atleast_1d(axes).ravel()[0].get_legend_handles_labels()
    fig.legend(handles, labels, loc="lower center", ncol=min(3, len(labels)), frameon=False,
               fontsize=8)
    fig.tight_layout(rect=(0, 0.06 + 0.035 * ((len(labels) - 1) // 3), 1, 1))
    path = os.path.join(OUT, name)
    fig.savefig(path, dpi=110, metadata={"Software": None})
    plt.close(fig)
    print("wrote", os.path.relpath(path, ROOT))


def martin_moyce():
    ts, vs = 18.5285478819624, 17.497812773403325  # T = n t sqrt(g/a), Z = x/a
    tr, vr = 13.101661852875255, 8.748906386701663  # tau = t sqrt(g/a), H = h/(2a)
    runs = [("sph_dp0.0028575", "SPH dp 2.86 mm (a/20)"), ("sph_dp0.00142875", "SPH dp 1.43 mm (a/40)"),
            ("foam_dx0.0028575", "interFoam 2.86 mm cells"), ("foam_dx0.00142875", "interFoam 1.43 mm cells")]
    fig, ax = plt.subplots(1, 2, figsize=(9, 3.8))
    ref = read_csv(os.path.join(VAL, "reference", "martin_moyce_1952_front.csv"))
    points(ax[0], ref["T"], ref["Z"], REF[0], "experiment (Martin & Moyce 1952)")
    res = read_csv(os.path.join(VAL, "martin_moyce", "martin_moyce_1952_residual_height.csv"))
    points(ax[1], res["tau"], res["H"], REF[0], "experiment (Martin & Moyce 1952)")
    for (label, text), st in zip(runs, RUN):
        f = read_csv(os.path.join(results("martin_moyce", label), "gauges_front.csv"))
        line(ax[0], f["time"] * ts, f["front"] * vs, st, text)
        h = read_csv(os.path.join(results("martin_moyce", label), "gauges_height.csv"))
        line(ax[1], h["time"] * tr, h["H_back"] * vr, st, text)
    window(ax[0], 1.5, 3.3)
    window(ax[1], 0.5, 3.9)
    ax[0].set(xlim=(0, 4), ylim=(1, 5), xlabel="T = n t sqrt(g/a) [-]", ylabel="Z = x/a [-]",
              title="surge front")
    ax[1].set(xlim=(0, 4), ylim=(0, 1.05), xlabel="tau = t sqrt(g/a) [-]",
              ylabel="H = h/(2a) [-]", title="residual height at the back wall")
    finish(fig, ax, "martin_moyce.png")


def lobovsky():
    ts, ps, hs = 5.718391382198319, 3.397893306150187e-4, 3.3333333333333335
    exp = read_csv(os.path.join(VAL, "lobovsky2d", "lobovsky2014_pressure_1khz.csv"))
    # Pressures: the four sensors, experiment against the committed dp 4 mm run (the only one
    # with the sensor faces) and interFoam 5 mm.
    fig, axes = plt.subplots(2, 2, figsize=(9, 6.4))
    sph = read_csv(os.path.join(results("lobovsky2d", "sph_dp0.004"), "gauges_pressure.csv"))
    foam = read_csv(os.path.join(results("lobovsky2d", "foam_dx0.005"), "gauges_pressure.csv"))
    for k, ax in enumerate(axes.ravel(), start=1):
        line(ax, exp["t_star"], exp["p_star_sensor%d" % k], REF[0],
             "experiment (Lobovsky 2014, event 5, 1 ms means)", every=40)
        line(ax, sph["time"] * ts, sph["face%d" % k] * ps, RUN[0], "SPH dp 4 mm (DBC), sensor face")
        line(ax, sph["time"] * ts, sph["sensor%d" % k] * ps, RUN[3], "SPH dp 4 mm (DBC), point probe")
        line(ax, foam["time"] * ts, foam["face%d" % k] * ps, RUN[2], "interFoam 5 mm cells, face")
        window(ax, 2.2, 3.5)
        hi = max(4.0, 1.6 * np.nanmax(exp["p_star_sensor%d" % k]))
        ax.set(xlim=(1.5, 7.5), ylim=(-0.5, hi), title="sensor %d" % k,
               xlabel="t* = t sqrt(g/H) [-]", ylabel="p* = p/(rho g H) [-]")
        ax.text(0.99, 0.97, "clipped at p* %.1f" % hi, transform=ax.transAxes, ha="right",
                va="top", fontsize=7, color="0.4")
    finish(fig, axes, "lobovsky_pressure.png")

    lev = read_csv(os.path.join(VAL, "lobovsky2d", "lobovsky2014_water_levels.csv"))
    fig, axes = plt.subplots(2, 2, figsize=(9, 6.4))
    runs = [("sph_dp0.004", "SPH dp 4 mm"), ("sph_dp0.01", "SPH dp 10 mm"),
            ("foam_dx0.005", "interFoam 5 mm cells")]
    data = [read_csv(os.path.join(results("lobovsky2d", r), "gauges_height.csv")) for r, _ in runs]
    for k, ax in enumerate(axes.ravel(), start=1):
        col = "h_star_H%d_etsin01" % k
        line(ax, lev["t_star"], lev[col], REF[0], "experiment (ETSIN 01)", every=10)
        if k > 1:
            line(ax, lev["t_star"], lev["h_star_H%d_etsin02" % k], REF[1], "experiment (ETSIN 02)",
                 every=10)
        for (r, text), d, st in zip(runs, data, RUN):
            line(ax, d["time"] * ts, d["H%d" % k] * hs, st, text)
        ax.set(xlim=(0, 8), title="H%d" % k, xlabel="t* = t sqrt(g/H) [-]", ylabel="h* = h/H [-]")
    finish(fig, axes, "lobovsky_levels.png")


def foam_dambreak():
    ts, fs, hs, ps = 5.796196201903357, 6.844626967830253, 3.4246575342465757, 3.4909862734419726e-4
    runs = [("sph_dp0.004", "SPH dp 4 mm"), ("sph_dp0.002", "SPH dp 2 mm"),
            ("foam_dx0.008", "interFoam 8 mm cells"), ("foam_dx0.004", "interFoam 4 mm cells")]
    fig, axes = plt.subplots(2, 2, figsize=(9, 6.4))
    for (r, text), st in zip(runs, RUN):
        d = results("foam_dambreak2d", r)
        f = read_csv(os.path.join(d, "gauges_front.csv"))
        h = read_csv(os.path.join(d, "gauges_height.csv"))
        p = read_csv(os.path.join(d, "gauges_pressure.csv"))
        line(axes[0, 0], f["time"] * ts, f["front"] * fs, st, text)
        line(axes[0, 1], h["time"] * ts, h["H1"] * hs, st, text)
        line(axes[1, 0], p["time"] * ts, p["F_obstacle"] * ps, st, text)
        line(axes[1, 1], p["time"] * ts, p["F_wall"] * ps, st, text)
    window(axes[0, 0], 0.2, 1.0)
    window(axes[1, 0], 0.5, 2.0)
    window(axes[1, 1], 1.0, 3.0)
    axes[0, 0].set(xlim=(0, 2), ylim=(1, 2.6), title="front (to the obstacle at x/a = 2)",
                   ylabel="x/a [-]")
    axes[0, 1].set(xlim=(0, 6), title="H1 (in the column)", ylabel="h/H [-]")
    axes[1, 0].set(xlim=(0, 6), ylim=(-0.3, 2.5), title="sensor face F_obstacle",
                   ylabel="p/(rho g H) [-]")
    axes[1, 1].set(xlim=(0, 6), ylim=(-0.3, 2.5), title="sensor face F_wall",
                   ylabel="p/(rho g H) [-]")
    for ax in axes.ravel():
        ax.set_xlabel("t sqrt(g/H) [-]")
    for ax in axes[1]:
        ax.text(0.99, 0.97, "y clipped at 2.5", transform=ax.transAxes, ha="right", va="top",
                fontsize=7, color="0.4")
    finish(fig, axes, "foam_dambreak2d.png")


def spheric():
    ts, ps, hs = 4.22331192742895, 1.853396348809193e-4, 1.8181818181818181
    runs = [("sph_dp0.02", "SPH dp 20 mm (DBC)"), ("foam_dx0.04", "interFoam 40 mm cells"),
            ("foam_dx0.03", "interFoam 30 mm cells")]
    for kind, names, scale, ylab, name in [
            ("pressure", ["P1", "P2", "P3", "P4"], ps, "p/(rho g H) [-]", "spheric_test2_pressure.png"),
            ("height", ["H1", "H2", "H3", "H4"], hs, "h/H [-]", "spheric_test2_levels.png")]:
        fig, axes = plt.subplots(2, 2, figsize=(9, 6.4))
        data = [read_csv(os.path.join(results("spheric_test2", r), "gauges_%s.csv" % kind))
                for r, _ in runs]
        for g, ax in zip(names, axes.ravel()):
            for (r, text), d, st in zip(runs, data, RUN):
                line(ax, d["time"] * ts, d[g] * scale, st, text)
            ax.set(xlim=(0, 6.4), title=g, xlabel="t sqrt(g/H) [-]", ylabel=ylab)
            if kind == "pressure":
                ax.set_ylim(-1, 3)
                ax.text(0.99, 0.97, "y clipped at 3", transform=ax.transAxes, ha="right",
                        va="top", fontsize=7, color="0.4")
                window(ax, 1.0, 3.0)
        finish(fig, axes, name)


def wave_flume():
    runs = [("sph_dp0.02", "SPH dp 20 mm"), ("foam_dx0.02", "interFoam 20 mm cells"),
            ("foam_dx0.01", "interFoam 10 mm cells")]
    data = [read_csv(os.path.join(results("wave_flume2d", r), "gauges_height.csv")) for r, _ in runs]
    fig, axes = plt.subplots(3, 1, figsize=(9, 7.5), sharex=True)
    for g, ax in zip(["WG1", "WG2", "WG3"], axes):
        for (r, text), d, st in zip(runs, data, RUN):
            line(ax, d["time"], d[g], st, text, every=25)
        window(ax, 6, 12)
        ax.set(title="%s (%d m from the paddle)" % (g, int(g[-1])), ylabel="water level [m]")
    axes[-1].set(xlim=(0, 12), xlabel="t [s]")
    finish(fig, axes, "wave_flume2d.png")


def caisson():
    fig, axes = plt.subplots(2, 1, figsize=(9, 5.6), sharex=True)
    runs = [("sph_dp0.01", "regular waves, SPH dp 10 mm"), ("sph_dp0.02", "regular waves, SPH dp 20 mm"),
            ("sph_focused_dp0.01", "focused group, SPH dp 10 mm")]
    for (r, text), st in zip(runs, RUN):
        f = read_csv(os.path.join(results("caisson", r), "gauges_force.csv"))
        h = read_csv(os.path.join(results("caisson", r), "gauges_height.csv"))
        line(axes[0], h["time"], h["eta_wall"], st, text, every=40)
        line(axes[1], f["time"], f["F_caisson_fx"], st, text, every=40)
    axes[0].set(ylabel="level at the wall [m]", title="water level at the caisson face")
    axes[1].set(ylabel="F_x [N/m]", xlabel="t [s]", title="horizontal force on the caisson")
    window(axes[1], 5.5, 8.5)
    finish(fig, axes, "caisson_timeseries.png")


def main():
    global OUT
    import argparse

    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--out", default=OUT,
                    help="folder for the PNGs (default: docs/validation/_figures, committed)")
    OUT = ap.parse_args().out
    os.makedirs(OUT, exist_ok=True)
    for fn in (martin_moyce, lobovsky, foam_dambreak, spheric, wave_flume, caisson):
        fn()
    # Every figure the pages show is made here (none missing from the committed set).
    made = sorted(f for f in os.listdir(OUT) if f.endswith(".png"))
    committed = sorted(f for f in os.listdir(os.path.join(HERE, "_figures")) if f.endswith(".png"))
    missing = [f for f in committed if f not in made]
    if missing:
        sys.exit("make_figures: not made from the committed results: " + ", ".join(missing))


if __name__ == "__main__":
    main()
