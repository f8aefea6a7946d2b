#!/usr/bin/env python3
"""Plots the scaling sweep of `swell bench --sweep`.

Usage: plot_scaling.py scaling.csv scaling.png

Draws the cost per particle-step (ns) against the particle count on a log axis, with the
split by phase; a flat line means the cost is O(N).
"""
import csv
import sys

import matplotlib

matplotlib.use("Agg")
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
    ax.plot(n, [r["ns_per_particle_step"] for r in rows], "o-", label="total, per particle")
    ax.plot(n, [r["ns_per_fluid_particle_step"] for r in rows], "^-",
            label="total, per fluid particle")
    for phase in ("interaction", "neighbour", "integration"):
        ns = [1e9 * r[phase] / (r["particles"] * r["steps"]) for r in rows]  # per particle
        ax.plot(n, ns, "s--", ms=4, label=phase)
    ax.set_xscale("log")
    ax.set_ylim(bottom=0)
    ax.set_xlabel("particles N")
    ax.set_ylabel("wall time per particle-step [ns]")
    ax.set_title("B3D scaling sweep (flat = O(N))", fontsize=11)
    ax.grid(True, which="both", alpha=0.3)
    ax.legend()
    fig.text(0.01, 0.01, title[:140], fontsize=6)
    fig.tight_layout(rect=(0, 0.03, 1, 1))
    fig.savefig(png, dpi=120)


if __name__ == "__main__":
    if len(sys.argv) != 3:
        sys.exit("usage: plot_scaling.py scaling.csv scaling.png")
    main(sys.argv[1], sys.argv[2])
