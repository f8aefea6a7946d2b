#!/usr/bin/env python3
"""Plots the scaling sweep of `swell bench --sweep`.

Usage: plot_scaling.py scaling.csv scaling.png

Draws the cost per particle-step (ns) against the particle count on a log axis, with the
split by phase; a flat line means the cost is O(N). Writes the PNG and an SVG beside it (same
name, .svg). Each line has its own colour, dash pattern and marker (readable in greyscale); the
legend sits below the axes; the sweep's header line (machine, date) is printed under it.
"""
import csv
import os
import sys

# The shared figure style (validation/plot_style.py, beside this folder in the source tree and
# in an installed share/swell).
sys.dont_write_bytecode = True  # no __pycache__ beside the script (an installed tree)
sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "validation"))
from plot_style import RUN_STYLES as STYLES, save  # noqa: E402  (sets the Agg backend)

import matplotlib.pyplot as plt  # noqa: E402


def main(src, png):
    title = ""
    rows = []
    with open(src) as f:
        lines = [l for l in f if l.strip()]
    for l in lines:
        if l.startswith("#"):
            title = l[1:].strip()
    reader = csv.DictReader(l for l in lines if not l.startswith("#"))
    for r in reader:
        rows.append({k: float(v) for k, v in r.items()})
    rows.sort(key=lambda r: r["particles"])
    n = [r["particles"] for r in rows]
    fig, ax = plt.subplots(figsize=(7, 4.5))
    lines = [("total, per particle", [r["ns_per_particle_step"] for r in rows]),
             ("total, per fluid particle", [r["ns_per_fluid_particle_step"] for r in rows])]
    for phase in ("interaction", "neighbour", "integration"):
        lines.append(("%s phase, per particle" % phase,
                      [1e9 * r[phase] / (r["particles"] * r["steps"]) for r in rows]))
    for (label, ns), style in zip(lines, STYLES):
        ax.plot(n, ns, lw=1.4, ms=5, mfc="white", mew=1.1, label=label, **style)
    ax.set_xscale("log")
    ax.set_ylim(bottom=0)
    ax.set_xlabel("particles N [count, log scale]")
    ax.set_ylabel("wall time per particle-step [ns]")
    ax.set_title("B3D scaling sweep (flat = O(N))", fontsize=11)
    ax.grid(True, which="both", alpha=0.3)
    leg = ax.legend(fontsize=8, loc="upper center", bbox_to_anchor=(0.5, -0.14), ncol=2,
              frameon=False, handlelength=3.2)
    # The sweep's header (machine, date) under the legend, wrapped.
    words, text, line = title.split(), [], ""
    for w in words:
        if len(line) + len(w) > 110:
            text.append(line)
            line = ""
        line += (" " if line else "") + w
    if line:
        text.append(line)
    fig.canvas.draw()
    below = leg.get_window_extent().transformed(fig.transFigure.inverted()).y0
    fig.text(0.5, below - 0.01, "\n".join(text), fontsize=6.5, ha="center", va="top", color="0.3")
    save(fig, png)

if __name__ == "__main__":
    if len(sys.argv) != 3:
        sys.exit("usage: plot_scaling.py scaling.csv scaling.png")
    main(sys.argv[1], sys.argv[2])
