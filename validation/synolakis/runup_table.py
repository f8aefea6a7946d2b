#!/usr/bin/env python3
"""Maximum runup R/d of Synolakis runs against the lab points and the runup law.

  python3 validation/synolakis/runup_table.py RUN_DIR [RUN_DIR ...] -o validation/synolakis/results

Each RUN_DIR is the output folder of a case written by make_case.py (its gauges_runup.csv holds
R above the still-water level; the case's header comment gives H/d and d). R_max is the largest
value of the R column; R_rest its value when the paddle starts (its first row, or its last row
before the paddle's `start` when the case settles first: the shoreline at rest, which the
discrete wedge puts below the still-water level), and R_max - R_rest the runup corrected for that offset. Both are
listed against the law R/d = 2.831 sqrt(cot beta) (H/d)^(5/4) and the mean of the lab points
within +-0.005 of the run's H/d (../shared/reference/synolakis_1987_runup_lab.csv; lab waves break
for H/d > 0.045). Writes runup_table.csv, runup.png and runup.svg beside it (matplotlib, numpy
only). The legend names each run by method and particle spacing from the case written by
make_case.py ("Swell SPH dp 15 mm"); axes are the dimensionless H/d and R/d.

  python3 validation/synolakis/runup_table.py --replot validation/synolakis/results/runup_table.csv

redraws the figure from a table written earlier (no run folders needed).
"""
import argparse
import csv
import glob
import math
import os
import re
import sys

import numpy as np

COT_BETA = 19.85
LAB = os.path.join(os.path.dirname(__file__), "..", "..", "..", "shared", "reference",
                   "synolakis_1987_runup_lab.csv")


def law(hd):
    return 2.831 * math.sqrt(COT_BETA) * hd ** 1.25


def read_lab(path):
    rows = [l for l in open(path) if l.strip() and not l.startswith("#")]
    data = np.array([[float(v) for v in l.split(",")[:2]] for l in rows[1:]])
    return data[:, 0], data[:, 1]


def read_run(folder):
    # The case beside the folder or in it; a run folder also holds run_info.yaml (no header).
    case = glob.glob(folder.rstrip("/") + ".yaml") + sorted(glob.glob(os.path.join(folder, "*.yaml")))
    meta = {}
    for path in case:
        text = open(path).read()
        m = re.search(r"--hd ([0-9.eE+-]+) --d ([0-9.eE+-]+) --dp ([0-9.eE+-]*[0-9])", text)
        if m:
            meta = dict(hd=float(m.group(1)), d=float(m.group(2)), dp=float(m.group(3)))
            c = re.search(r"^\s*coefh:\s*([0-9.eE+-]+)", text, re.M)
            v = re.search(r"^\s*viscosity:\s*\{\s*model:\s*(\w+)", text, re.M)
            meta["settings"] = "coefh %g, %s" % (float(c.group(1)) if c else 1.0,
                                                 v.group(1) if v else "artificial")
            b = re.search(r"^\s*boundary:\s*\{\s*model:\s*(\w+)(?:,\s*pressure:\s*(\w+))?", text, re.M)
            if b and b.group(1) != "dbc":
                meta["settings"] += ", " + b.group(1) + (" " + b.group(2) if b.group(2) else "")
            st = re.search(r"motion:\s*\{[^}]*start:\s*([0-9.eE+-]+)", text)
            meta["start"] = float(st.group(1)) if st else 0.0
            break
    if not meta:
        raise SystemExit(f"{folder}: no case written by make_case.py next to it ({folder}.yaml)")
    t, r = [], []
    with open(os.path.join(folder, "gauges_runup.csv")) as fh:
        for row in csv.reader(l for l in fh if not l.startswith("#")):
            if row[0].startswith("time") or len(row) < 2 or row[1] == "":
                continue
            t.append(float(row[0]))
            r.append(float(row[1]))
    t, r = np.array(t), np.array(r)
    k = int(np.argmax(r))
    wall = ""
    summary = os.path.join(folder, "run_summary.txt")
    if os.path.exists(summary):
        m = re.search(r"wall time:\s+(\S+) s", open(summary).read())
        wall = m.group(1) if m else ""
    before = np.nonzero(t <= meta["start"])[0]
    rest = r[before[-1]] if len(before) else r[0]
    return dict(meta, r_max=r[k], t_max=t[k], r_rest=rest, t_end=t[-1], wall=wall)


def read_table(path):
    """The rows of a runup_table.csv written by this script (numbers as floats)."""
    with open(path) as fh:
        reader = csv.DictReader(l for l in fh if not l.startswith("#"))
        rows = []
        for r in reader:
            rows.append({k: (float(v) if k not in ("breaking_in_lab", "wall_s", "settings") else v)
                         for k, v in r.items()})
            rows[-1].setdefault("settings", "")
    need = {"H_over_d", "dp_m", "R_over_d", "R_corr_over_d"}
    if not rows or not need <= set(rows[0]):
        sys.stderr.write(f"{path}: expected a runup_table.csv with rows and the columns "
                         f"{', '.join(sorted(need))}\n")
        sys.exit(2)
    return rows


def plot(rows, lab_h, lab_r, png):
    sys.dont_write_bytecode = True  # no __pycache__ beside the script (an installed tree)
    sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))
    from plot_style import length_text, save  # sets the Agg backend
    import matplotlib.pyplot as plt
    fig, ax = plt.subplots(figsize=(6, 4.8))
    ax.loglog(lab_h, lab_r, ls="none", marker="o", ms=3.5, mfc="none", mec="black", mew=0.8,
              label="experiment (Synolakis 1987, lab points)")
    hh = np.logspace(np.log10(0.005), np.log10(0.7), 100)
    ax.loglog(hh, [law(h) for h in hh], color="black", ls="--", lw=1,
              label="runup law 2.831 sqrt(cot beta) (H/d)^1.25")
    ax.axvline(0.045, color="0.6", lw=0.8, ls=":")
    ax.text(0.047, 0.012, "breaking (lab)", color="0.4", fontsize=8)
    # Okabe-Ito, then four more, so each run group has its own colour
    colours = ["#D55E00", "#0072B2", "#009E73", "#CC79A7", "#E69F00", "#56B4E9", "#8C564B",
               "#7F7F7F", "#9467BD", "#BCBD22"]
    groups = sorted({(r["dp_m"], r.get("settings", "")) for r in rows})
    for i, (dp, settings) in enumerate(groups):
        sel = [r for r in rows if r["dp_m"] == dp and r.get("settings", "") == settings]
        hs = [r["H_over_d"] for r in sel]
        name = "Swell SPH dp " + length_text(dp) + (f" ({settings})" if settings else "")
        colour = colours[i % len(colours)]
        ax.loglog(hs, [r["R_over_d"] for r in sel], ls="none", marker="s", ms=7, color=colour,
                  label=name + ", R max")
        ax.loglog(hs, [r["R_corr_over_d"] for r in sel], ls="none", marker="^", ms=7,
                  mfc="white", mew=1.3, color=colour, label=name + ", R max - R at rest")
    negative = [r for r in rows if r["R_over_d"] <= 0]
    if negative:  # a log axis cannot show them: say so on the plot
        ax.text(0.02, 0.97, "R max <= 0, not on the log axis:\n" + "\n".join(
            "H/d %.3g: R/d %.3g" % (r["H_over_d"], r["R_over_d"]) for r in negative),
            transform=ax.transAxes, ha="left", va="top", fontsize=7, color="#D55E00")
    ax.set_xlabel("H/d, wave height / depth [-]")
    ax.set_ylabel("R/d, maximum runup / depth [-]")
    ax.set_ylim(0.01, 2)
    ax.grid(True, which="both", alpha=0.25)
    ax.legend(fontsize=8, loc="upper center", bbox_to_anchor=(0.5, -0.14), ncol=1,
              frameon=False)
    ax.set_title("Solitary-wave runup on a 1:19.85 beach")
    save(fig, png)


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("runs", nargs="*")
    ap.add_argument("-o", "--out", default="validation/synolakis/results")
    ap.add_argument("--lab", default=LAB)
    ap.add_argument("--replot", metavar="TABLE", help="redraw runup.png/.svg from this table")
    a = ap.parse_args()
    lab_h, lab_r = read_lab(a.lab)
    if a.replot:
        if not os.path.isfile(a.replot):
            ap.error(f"--replot {a.replot}: no such file (a runup_table.csv written earlier)")
        out = os.path.dirname(os.path.abspath(a.replot))
        plot(read_table(a.replot), lab_h, lab_r, os.path.join(out, "runup.png"))
        return
    if not a.runs:
        ap.error("give run folders, or --replot TABLE")
    os.makedirs(a.out, exist_ok=True)
    rows = []
    for folder in a.runs:
        run = read_run(folder.rstrip("/"))
        hd, d = run["hd"], run["d"]
        near = lab_r[np.abs(lab_h - hd) <= 0.005 + 1e-9]
        lab_mean = float(np.mean(near)) if len(near) else float("nan")
        rows.append(dict(
            H_over_d=hd, d_m=d, dp_m=run["dp"], H_over_dp=hd * d / run["dp"],
            R_over_d=run["r_max"] / d, R_rest_over_d=run["r_rest"] / d,
            R_corr_over_d=(run["r_max"] - run["r_rest"]) / d, t_max_s=run["t_max"],
            law_R_over_d=law(hd), lab_mean_R_over_d=lab_mean, lab_points=len(near),
            err_vs_lab=(run["r_max"] / d) / lab_mean - 1.0,
            err_corr_vs_lab=((run["r_max"] - run["r_rest"]) / d) / lab_mean - 1.0,
            breaking_in_lab=hd > 0.045, wall_s=run["wall"], settings=run["settings"]))
    path = os.path.join(a.out, "runup_table.csv")
    with open(path, "w", newline="") as fh:
        fh.write("# max runup of swell runs (make_case.py; R above swl, gauge sampling: max); "
                 "lab: mean of Synolakis (1987) points within +-0.005 of H/d; "
                 "law: 2.831 sqrt(cot beta) (H/d)^1.25\n")
        w = csv.DictWriter(fh, fieldnames=list(rows[0].keys()))
        w.writeheader()
        for r in rows:
            w.writerow({k: (f"{v:.4g}" if isinstance(v, float) else v) for k, v in r.items()})
    print(open(path).read())
    plot(rows, lab_h, lab_r, os.path.join(a.out, "runup.png"))

if __name__ == "__main__":
    main()
