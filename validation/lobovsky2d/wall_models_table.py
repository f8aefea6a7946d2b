#!/usr/bin/env python3
"""Prints the wall-model table (Markdown) from the metrics.csv files that wall_models.sh's
`swell validate` runs wrote: per sensor (point probe) and sensor face, against the experiment,
the first peak p* and its time error, the mean p* over t* 3-7, the impulse over t* 2.4-3.5 and
the peak after the 1 ms boxcar.

    wall_models_table.py OUT [VARIANT ...]
"""
import csv
import os
import sys


def rows_of(path):
    with open(path, newline="") as f:
        lines = [line for line in f if not line.startswith("#")]
    return list(csv.DictReader(lines))


def num(row, key):
    try:
        return float(row.get(key, ""))
    except ValueError:
        return float("nan")


def main():
    if len(sys.argv) < 2:
        print(__doc__)
        return 2
    out = sys.argv[1]
    variants = sys.argv[2:] or ["mdbc", "mdbc_shift_nb", "mdbc_shift", "dbc", "dbc_shift_nb",
                                "dbc_shift"]
    print("| variant | run | gauge | peak (exp) | peak err | peak t err [s] | mean 3-7 (exp) | "
          "mean err | impulse (exp) | impulse err | 1 ms peak |")
    print("|---|---|---|---|---|---|---|---|---|---|---|")
    for v in variants:
        path = os.path.join(out, v, "metrics.csv")
        if not os.path.exists(path):
            print(f"| {v} | (no metrics.csv) |||||||||")
            continue
        for r in rows_of(path):
            g = r.get("gauge", "")
            if not (g.startswith("sensor") or g.startswith("face")):
                continue
            if r.get("reference", "") != "experiment" or not r.get("run", "").startswith("sph"):
                continue
            print(f"| {v} | {r['run']} | {g} | {num(r, 'peak'):.2f} ({num(r, 'ref_peak'):.2f}) | "
                  f"{100 * num(r, 'peak_error'):+.0f} % | {num(r, 'peak_time_error_s'):+.3f} | "
                  f"{num(r, 'mean'):.3f} ({num(r, 'ref_mean'):.3f}) | "
                  f"{100 * num(r, 'mean_error'):+.0f} % | {num(r, 'impulse'):.2f} "
                  f"({num(r, 'ref_impulse'):.2f}) | {100 * num(r, 'impulse_error'):+.0f} % | "
                  f"{num(r, 'filtered_peak'):.2f} |")
    return 0


if __name__ == "__main__":
    sys.exit(main())
