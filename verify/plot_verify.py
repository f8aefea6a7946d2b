"""Plots of `swell verify`: reads DIR/plots.tsv (written by apps/verify_command.cpp: file, title,
table, x, y columns separated by ';', log_x, log_y, style) and the tables DIR/<table>.csv, and
writes DIR/<file>.png (+ SVG) with the shared style of validation/plot_style.py.

Usage: plot_verify.py DIR
"""
import csv
import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "validation"))
import plot_style  # noqa: E402
import matplotlib.pyplot as plt  # noqa: E402


def read_table(path):
    with open(path, newline="") as f:
        rows = list(csv.reader(f))
    header, data = rows[0], rows[1:]
    cols = {h: [] for h in header}
    for r in data:
        for h, v in zip(header, r):
            cols[h].append(float(v))
    return cols


def main(d):
    spec = os.path.join(d, "plots.tsv")
    if not os.path.exists(spec):
        return 0
    with open(spec) as f:
        lines = [l.rstrip("\n").split("\t") for l in f if l.strip()]
    for name, title, table, x, ys, log_x, log_y, style in lines:
        cols = read_table(os.path.join(d, table + ".csv"))
        fig, ax = plt.subplots(figsize=(6.4, 4.4))
        for i, y in enumerate(ys.split(";")):
            st = plot_style.RUN_STYLES[i % len(plot_style.RUN_STYLES)]
            kw = dict(color=st["color"], label=y)
            if "lines" in style:
                kw["ls"] = st["ls"]
            else:
                kw["ls"] = "none"
            if "points" in style:
                kw.update(marker=st["marker"], mfc="white", ms=5)
            pts = [(a, b) for a, b in zip(cols[x], cols[y]) if b == b]  # drop NaN
            ax.plot([p[0] for p in pts], [p[1] for p in pts], **kw)
        if log_x == "1":
            ax.set_xscale("log")
        if log_y == "1":
            ax.set_yscale("log")
        ax.set_xlabel(x)
        ax.set_title(title, fontsize=10)
        ax.grid(True, alpha=0.3, which="both")
        ax.legend(fontsize=8, loc="upper center", bbox_to_anchor=(0.5, -0.15), ncol=2,
                  frameon=False)
        fig.tight_layout()
        plot_style.save(fig, os.path.join(d, name + ".png"))
        plt.close(fig)
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1]))
