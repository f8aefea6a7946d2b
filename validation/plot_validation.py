#!/usr/bin/env python3
"""Draws the validation plots of `swell compare` / `swell validate`.

Usage: plot_validation.py PLOTS.json

PLOTS.json (written by validation/validation_report.cpp) lists figures; each names its PNG
(written next to the JSON file; an SVG of the same name is written beside it, or a PDF where the
SVG would exceed 1 MB), title, axis labels (with units, built by the C++ side), the metric window
and peak window in normalised time, and its lines: a legend label (built from the run's own
run_info.yaml: "SPH dp 4 mm", "interFoam 5 mm cells", or the reference's label), a CSV file, a
column, and the scales that normalise it (t * time_scale, v * value_scale). CSV files are swell
gauge files or reference tables: '#' comment lines, a header whose first column is time, units
in brackets ("P1 [Pa]"), and empty cells where a gauge was not sampled.

Conventions: references in black/grey (open markers when sparse, lines when dense); runs in
colour-blind-safe colours, each with its own line style and marker so the figure reads in
greyscale; the metric window is a light band behind the curves with dashed edges and a labelled
bar above the data, the peak window a second bar; the legend sits below the axes.
"""
import csv
import json
import math
import os
import sys

sys.dont_write_bytecode = True  # no __pycache__ beside the script (an installed tree)
sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from plot_style import REF_STYLES, RUN_STYLES, save  # noqa: E402  (sets the Agg backend)

import matplotlib.pyplot as plt  # noqa: E402
from matplotlib.patches import Patch  # noqa: E402

MARKERS_PER_LINE = 12  # markers on a dense line (at most), so they mark, not blot


def column_name(header):
    """'P1 [Pa]' -> 'P1'."""
    return header.split("[")[0].strip()


def read_column(path, column):
    with open(path) as f:
        rows = [r for r in csv.reader(f) if r and not r[0].lstrip().startswith("#")]
    names = [column_name(h) for h in rows[0]]
    if column not in names:
        raise SystemExit(f"{path}: no column '{column}' (columns: {', '.join(names[1:])})")
    k = names.index(column)
    t, v = [], []
    for r in rows[1:]:
        if k >= len(r) or r[k].strip() == "":
            continue
        try:
            tv, vv = float(r[0]), float(r[k])
        except ValueError:
            continue
        if math.isfinite(tv) and math.isfinite(vv):
            t.append(tv)
            v.append(vv)
    return t, v


def finite(x):
    return x is not None and math.isfinite(x)


def draw(plot, out_dir):
    fig, ax = plt.subplots(figsize=(7.0, 4.2))
    lo, hi = plot["window"]
    plo, phi = plot["peak_window"]
    have_window = finite(lo) and finite(hi)
    n_ref = n_run = 0
    curves = []  # (t, v) drawn, for the y limits of the visible part
    for line in plot["lines"]:
        t, v = read_column(line["file"], line["column"])
        t = [x * line["time_scale"] for x in t]
        v = [x * line["value_scale"] for x in v]
        curves.append((t, v))
        if line["reference"]:
            s = REF_STYLES[n_ref % len(REF_STYLES)]
            n_ref += 1
            if len(t) < 60:  # a table of points: open markers, no line
                ax.plot(t, v, ls="none", marker=s["marker"], ms=6, mfc="none", mec=s["color"],
                        mew=1.3, color=s["color"], label=line["label"], zorder=4)
            else:
                ax.plot(t, v, color=s["color"], ls=s["ls"], lw=1.1, label=line["label"],
                        zorder=3)
        else:
            s = RUN_STYLES[n_run % len(RUN_STYLES)]
            n_run += 1
            every = max(1, len(t) // MARKERS_PER_LINE)
            # Stagger the markers of successive runs so they do not sit on top of each other.
            start = (n_run * every // 5) % every if every > 1 else 0
            ax.plot(t, v, color=s["color"], ls=s["ls"], lw=1.3, marker=s["marker"], ms=4.5,
                    markevery=(start, every), mfc="white", mew=1.0, label=line["label"],
                    zorder=2)

    # x range: the metric window with a margin either side, within the data.
    if have_window:
        span = hi - lo
        t_all = [x for t, _ in curves for x in t]
        x0, x1 = lo - 0.12 * span, hi + 0.12 * span
        if t_all:
            x0, x1 = max(x0, min(t_all)), min(x1, max(t_all))
            x0, x1 = min(x0, lo), max(x1, hi)
        ax.set_xlim(x0, x1)
    # y range from what is visible, with head room for the window bars. Isolated spikes of a
    # run (beyond its 0.5-99.5 percentiles and the references' range) would squash the rest:
    # they are clipped and the clipped extremes are written on the plot.
    xmin, xmax = ax.get_xlim()
    ref_vis, run_vis = [], []
    for line, (t, v) in zip(plot["lines"], curves):
        sel = [y for x, y in zip(t, v) if xmin <= x <= xmax]
        (ref_vis if line["reference"] else run_vis).extend(sel)
    clipped = None
    if ref_vis or run_vis:
        full0, full1 = min(ref_vis + run_vis), max(ref_vis + run_vis)
        y0, y1 = full0, full1
        if run_vis and len(run_vis) > 200:
            r = sorted(run_vis)
            q0, q1 = r[int(0.005 * (len(r) - 1))], r[int(0.995 * (len(r) - 1))]
            y0 = min([q0] + ref_vis)
            y1 = max([q1] + ref_vis)
            margin = 0.25 * (y1 - y0)
            if full0 >= y0 - margin:
                y0 = full0
            if full1 <= y1 + margin:
                y1 = full1
            if (y0, y1) != (full0, full1):
                clipped = (full0, full1)
        pad = 0.05 * (y1 - y0) if y1 > y0 else 0.5 * max(abs(y1), 1.0)
        bars = int(have_window) + int(finite(plo) and finite(phi))
        ax.set_ylim(y0 - pad, y1 + pad + 0.09 * bars * (y1 - y0 + 2 * pad))
    if clipped:
        ax.text(0.995, 0.015, "y axis clipped; values span %.3g to %.3g" % clipped,
                transform=ax.transAxes, ha="right", va="bottom", fontsize=7, color="0.3",
                bbox=dict(facecolor="white", edgecolor="0.7", lw=0.5, pad=1.5))

    extra = []
    bar_top = 1.0
    if have_window:
        ax.axvspan(lo, hi, color="0.5", alpha=0.07, lw=0, zorder=0)
        for x in (lo, hi):
            ax.axvline(x, color="0.45", lw=0.8, ls=(0, (4, 3)), zorder=1)
        ax.axvspan(lo, hi, ymin=bar_top - 0.035, ymax=bar_top, color="0.55", lw=0, zorder=5)
        ax.text(0.5 * (lo + hi), 1.0 - 0.045, "metric window", transform=ax.get_xaxis_transform(),
                ha="center", va="top", fontsize=7, color="0.25", zorder=6,
                bbox=dict(facecolor="white", edgecolor="none", alpha=0.8, pad=0.5))
        extra.append(Patch(facecolor="0.55", label="metric window (metrics use this span)"))
        bar_top -= 0.085
    if finite(plo) and finite(phi):
        ax.axvspan(plo, phi, ymin=bar_top - 0.035, ymax=bar_top, color="#E69F00", lw=0, zorder=5)
        ax.text(0.5 * (plo + phi), bar_top - 0.045, "peak window",
                transform=ax.get_xaxis_transform(), ha="center", va="top", fontsize=7,
                color="#8a5a00", zorder=6,
                bbox=dict(facecolor="white", edgecolor="none", alpha=0.8, pad=0.5))
        extra.append(Patch(facecolor="#E69F00", label="peak window (first peak)"))

    ax.set_title(plot["title"], fontsize=10)
    ax.set_xlabel(plot["xlabel"])
    ax.set_ylabel(plot["ylabel"])
    ax.grid(True, lw=0.3, color="0.8")
    handles, labels = ax.get_legend_handles_labels()
    handles += extra
    labels += [p.get_label() for p in extra]
    ax.legend(handles, labels, fontsize=8, loc="upper center", bbox_to_anchor=(0.5, -0.14),
              ncol=2 if len(labels) > 3 else len(labels), frameon=False, handlelength=3.2)
    written = save(fig, os.path.join(out_dir, plot["png"]))
    plt.close(fig)
    return written


def main():
    if len(sys.argv) != 2:
        raise SystemExit(__doc__)
    spec_path = sys.argv[1]
    with open(spec_path) as f:
        spec = json.load(f)
    out_dir = os.path.dirname(os.path.abspath(spec_path))
    for plot in spec["plots"]:
        for path in draw(plot, out_dir):
            print("wrote", path)


if __name__ == "__main__":
    main()
