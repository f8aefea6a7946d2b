#!/usr/bin/env python3
"""Draws the validation plots of `swell compare` / `swell validate`.

Usage: plot_validation.py PLOTS.json

PLOTS.json (written by validation/validation_report.cpp) lists figures; each names its PNG
(written next to the JSON file), title, axis labels, the metric window and peak window in
normalised time, and its lines: a CSV file, a column, and the scales that normalise it
(t * time_scale, v * value_scale). CSV files are swell gauge files or reference tables: '#'
comment lines, a header whose first column is time, units in brackets ("P1 [Pa]"), and empty
cells where a gauge was not sampled.
"""
import csv
import json
import math
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def column_name(header):
    """'P1 [Pa]' -> 'P1'."""
    return header.split("[")[0].strip()


def read_column(path, column):
    rows = [r for r in csv.reader(open(path)) if r and not r[0].lstrip().startswith("#")]
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


def draw(plot, out_dir):
    fig, ax = plt.subplots(figsize=(7.0, 4.0))
    lo, hi = plot["window"]
    ref_styles = [dict(color="black", ls="-"), dict(color="0.45", ls="--"), dict(color="0.6", ls=":")]
    n_ref = 0
    for line in plot["lines"]:
        t, v = read_column(line["file"], line["column"])
        t = [x * line["time_scale"] for x in t]
        v = [x * line["value_scale"] for x in v]
        if line["reference"]:
            style = dict(lw=1.0, **ref_styles[n_ref % len(ref_styles)])
            if len(t) < 60:
                style = dict(color=style["color"], ls="none", marker="os^"[n_ref % 3], ms=4, mfc="none")
            n_ref += 1
            ax.plot(t, v, label=line["label"], **style)
        else:
            ax.plot(t, v, label=line["label"], lw=1.2)
    if lo is not None and hi is not None:
        span = hi - lo
        ax.set_xlim(lo - 0.05 * span, hi + 0.05 * span)
        ax.axvspan(lo, hi, color="0.93", zorder=0, label="metric window")
    plo, phi = plot["peak_window"]
    if plo is not None and phi is not None:
        ax.axvspan(plo, phi, color="#fde7c8", zorder=0, label="peak window")
    ax.set_title(plot["title"], fontsize=10)
    ax.set_xlabel(plot["xlabel"])
    ax.set_ylabel(plot["ylabel"])
    ax.grid(True, lw=0.3)
    ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(os.path.join(out_dir, plot["png"]), dpi=110)
    plt.close(fig)


def main():
    if len(sys.argv) != 2:
        raise SystemExit(__doc__)
    spec_path = sys.argv[1]
    spec = json.load(open(spec_path))
    out_dir = os.path.dirname(os.path.abspath(spec_path))
    for plot in spec["plots"]:
        draw(plot, out_dir)
        print("wrote", os.path.join(out_dir, plot["png"]))


if __name__ == "__main__":
    main()
