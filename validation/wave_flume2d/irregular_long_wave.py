#!/usr/bin/env python3
"""Long waves of an irregular sea (cases/wave_flume_jonswap2d.yaml): first- against
second-order generation.

Each gauge's record and the bound long wave the paddle is meant to make there (`swell waves
target ... --csv`, column eta_bound_X) are low-passed below the sea's first-order band (zero
phase, cosine taper from --fcut to 1.25 --fcut; the record mirrored at its ends), and over the
window a mean and a linear trend are removed from both (the SPH height gauge's mean level
drifts by a few mm in a wave run). Reported per run and gauge: the RMS of the bound wave, of
the measured long wave, of their difference (what is not bound: free long waves, their
reflections from the flume's ends, SPH noise) and their correlation. Writes a table (CSV) and a
figure.

usage: irregular_long_wave.py --target target.csv --gauges eta_1L:1.94,eta_2L:3.87 \\
           --window 10:60 RUN1 [RUN2 ...] -o OUTDIR
(--gauges: gauge name and its distance from the paddle's rest face [m], as given to
`swell waves target --at`)
"""
import argparse
import os
import sys

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from bound_long_wave import lowpass, read_csv, write_outputs  # noqa: E402


def detrend(t, y):
    m = np.column_stack([np.ones_like(t), t - t.mean()])
    c, *_ = np.linalg.lstsq(m, y, rcond=None)
    return y - m @ c


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("runs", nargs="+", help="swell run output folders")
    ap.add_argument("--target", required=True, help="CSV of `swell waves target`")
    ap.add_argument("--gauges", required=True, help="NAME:X,... (X from the paddle face [m])")
    ap.add_argument("--window", default="10:60", help="from:to [s]")
    ap.add_argument("--fcut", type=float, default=0.33, help="low-pass cut-off [Hz]")
    ap.add_argument("--still", type=float, default=1.0,
                    help="still level: the gauge's mean over t < this [s]")
    ap.add_argument("-o", "--out", required=True)
    a = ap.parse_args()

    th, tgt = read_csv(a.target)
    t0, t1 = (float(v) for v in a.window.split(":"))
    gauges = []
    for item in a.gauges.split(","):
        name, x = item.split(":")
        key = None
        for i, h in enumerate(th):
            if h.startswith("eta_bound_") and abs(float(h.split("_")[-1].split(" ")[0]) - float(x)) < 1e-6:
                key = i
        if key is None:
            sys.exit(f"{a.target}: no eta_bound column for x = {x} m ({name})")
        gauges.append((name, key))
    os.makedirs(a.out, exist_ok=True)
    tb_all = tgt[:, 0]
    table, series = [], {}
    for run in a.runs:
        gh, g = read_csv(os.path.join(run, "gauges_height.csv"))
        label = os.path.basename(os.path.normpath(run))
        names = [h.split(" ")[0] for h in gh]
        for name, key in gauges:
            if name not in names:
                sys.exit(f"{run}/gauges_height.csv: no gauge '{name}'")
            col = names.index(name)
            t = g[:, 0]
            still = np.mean(g[t < a.still, col])
            tu, eta_l = lowpass(t, g[:, col] - still, a.fcut)
            tb, bound_l = lowpass(tb_all, tgt[:, key], a.fcut)
            bound_i = np.interp(tu, tb, bound_l)
            m = (tu >= t0) & (tu <= t1)
            e = detrend(tu[m], eta_l[m])
            b = detrend(tu[m], bound_i[m])
            rb, rm, rd = (np.sqrt(np.mean(v ** 2)) for v in (b, e, e - b))
            corr = np.corrcoef(e, b)[0, 1]
            table.append([label, name, f"{t0:g}-{t1:g}", f"{1e3 * rb:.2f}", f"{1e3 * rm:.2f}",
                          f"{rm / rb:.2f}", f"{1e3 * rd:.2f}", f"{rd / rb:.2f}", f"{corr:.2f}"])
            series[(label, name)] = (tu[m], e, b, None)
    head = ["run", "gauge", "window [s]", "bound RMS [mm]", "measured long-wave RMS [mm]",
            "measured / bound", "difference RMS [mm]", "difference / bound", "correlation"]
    write_outputs(a.out, "irregular_long_wave", head, table, [n for n, _ in gauges],
                  [os.path.basename(os.path.normpath(r)) for r in a.runs], series,
                  "long wave [mm]")


if __name__ == "__main__":
    main()
