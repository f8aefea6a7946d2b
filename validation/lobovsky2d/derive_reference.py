#!/usr/bin/env python3
"""Derives this folder's reference tables from the full-rate Lobovsky et al. (2014) files.

Usage: derive_reference.py SHARED_REFERENCE_DIR   (the folder holding the INDEX.md data set)

- lobovsky2014_pressure_1khz.csv: the single-realisation wall pressures (20 kHz) averaged over
  1 ms blocks (1 kHz, the SPH gauge rate); peaks drop by <= 2 % (sensor 1: 3.04 -> 2.98).
- lobovsky2014_water_levels.csv: the water levels linearly resampled on a t* grid of 0.05.
Values stay normalised as in the sources: t* = t sqrt(g/H), p* = p/(rho g H), h* = h/H.
"""
import os
import sys

import numpy as np

G, H = 9.81, 0.3
TSCALE = np.sqrt(G / H)


def read(path):
    lines = [l for l in open(path) if l.strip() and not l.startswith("#")]
    header = lines[0].strip().split(",")
    data = np.array([[float(x) for x in l.strip().split(",")] for l in lines[1:]])
    return header, data


def main():
    src = sys.argv[1]
    here = os.path.dirname(os.path.abspath(__file__))

    name = "lobovsky_2014_H300_pressure_event5.csv"
    header, d = read(os.path.join(src, name))
    t = d[:, 0] / TSCALE  # seconds
    block = 1e-3
    n = int(t[-1] / block)
    idx = np.floor(t / block).astype(int)
    rows = []
    for j in range(n):
        sel = idx == j
        if not np.any(sel):
            continue
        rows.append([(j + 0.5) * block * TSCALE] + list(d[sel, 1:].mean(axis=0)))
    with open(os.path.join(here, "lobovsky2014_pressure_1khz.csv"), "w") as f:
        f.write("# Lobovsky et al. (2014) J. Fluids Struct. 48:407-434, H = 0.3 m dam break: pressure on the\n")
        f.write("# downstream wall, sensors 1 (3 mm), 2 and 2L (15 mm), 3 (30 mm), 4 (80 mm), one realisation\n")
        f.write(f"# ('peak event 5', the paper's Fig. 18 data). Derived from shared/reference/{name}\n")
        f.write("# (TNL-Project/TNL-SPH @ 0c3d51fc, examples/resources/damBreak2D/.../pressure/) by\n")
        f.write("# validation/lobovsky2d/derive_reference.py: 20 kHz samples averaged over 1 ms blocks,\n")
        f.write("# time = block centre. t_star = t sqrt(g/H), p_star = p/(rho g H), g = 9.81, H = 0.3 m.\n")
        f.write("# Caveat: impact peaks scatter strongly between repeats; this is a single realisation.\n")
        f.write(",".join(header) + "\n")
        for r in rows:
            f.write(",".join(f"{v:.6g}" for v in r) + "\n")

    name = "lobovsky_2014_H300_water_levels.csv"
    header, d = read(os.path.join(src, name))
    campaign = {"H1_2": "etsin01", "H2_3": "etsin02", "H2_4": "etsin01", "H3_3": "etsin02",
                "H3_4": "etsin01", "H4_4": "etsin02", "H4_5": "etsin01"}
    cols = []
    for h in header[1:]:
        tag = h.replace("h_star_", "")
        cols.append(f"h_star_{tag.split('_')[0]}_{campaign[tag]}")
    grid = np.arange(0.0, d[-1, 0] + 1e-9, 0.05)
    with open(os.path.join(here, "lobovsky2014_water_levels.csv"), "w") as f:
        f.write("# Lobovsky et al. (2014) J. Fluids Struct. 48:407-434, H = 0.3 m dam break: water levels at\n")
        f.write("# H1-H4 (x = 0.3, 0.865, 1.114, 1.3625 m from the upstream wall). Derived from\n")
        f.write(f"# shared/reference/{name} (TNL-Project/TNL-SPH @ 0c3d51fc, .../waterLevel/Fig16_*)\n")
        f.write("# by validation/lobovsky2d/derive_reference.py: linear resampling on a t* step of 0.05.\n")
        f.write("# etsin01 / etsin02: the paper's two measurement campaigns (H2-H4 measured in both).\n")
        f.write("# t_star = t sqrt(g/H), h_star = h/H, g = 9.81, H = 0.3 m.\n")
        f.write("t_star," + ",".join(cols) + "\n")
        for tg in grid:
            vals = [np.interp(tg, d[:, 0], d[:, k]) for k in range(1, d.shape[1])]
            f.write(f"{tg:.4g}," + ",".join(f"{v:.5g}" for v in vals) + "\n")


if __name__ == "__main__":
    main()
