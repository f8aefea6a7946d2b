"""Shared look of Swell's figures (validation, compare, bench, caisson, runup).

Imported by validation/plot_validation.py, validation/caisson/compare_goda.py,
validation/synolakis/runup_table.py and bench/plot_scaling.py (each puts this folder on
sys.path). Conventions: Okabe-Ito colours (distinguishable with colour-vision deficiency), each
paired with its own dash pattern and marker so a figure reads in greyscale; references in black
and greys; text kept as text in the SVG (searchable, small) and no timestamps in it, so a rerun
on the same data writes the same file; every PNG gets a vector copy beside it: an SVG, or a PDF
where the SVG would exceed 1 MB.
"""
import os

import matplotlib

matplotlib.use("Agg")

matplotlib.rcParams["svg.fonttype"] = "none"
matplotlib.rcParams["svg.hashsalt"] = "swell"
matplotlib.rcParams["path.simplify_threshold"] = 0.5

MAX_SVG_BYTES = 1_000_000

# Runs: filled-white markers; references: circles, crosses and pluses, so a reference's points
# never look like a run's marker.
RUN_STYLES = [
    dict(color="#0072B2", ls="-", marker="s"),
    dict(color="#D55E00", ls="--", marker="^"),
    dict(color="#009E73", ls="-.", marker="D"),
    dict(color="#CC79A7", ls=(0, (1, 1.2)), marker="v"),
    dict(color="#E69F00", ls=(0, (6, 1.5, 1, 1.5, 1, 1.5)), marker="P"),
    dict(color="#56B4E9", ls=(0, (9, 2.5)), marker="*"),
]
REF_STYLES = [
    dict(color="black", ls="-", marker="o"),
    dict(color="0.40", ls="--", marker="x"),
    dict(color="0.55", ls=":", marker="+"),
]


def length_text(metres):
    """A resolution for a legend: '4 mm', '2.86 mm', '0.2 m'."""
    return "%.3g mm" % (1000 * metres) if metres < 0.1 else "%.3g m" % metres


def save(fig, png, dpi=120):
    """Writes png and its vector copy beside it; returns [png, vector file]."""
    fig.savefig(png, dpi=dpi, bbox_inches="tight")
    stem = os.path.splitext(png)[0]
    fig.savefig(stem + ".svg", bbox_inches="tight", metadata={"Date": None})
    if os.path.getsize(stem + ".svg") <= MAX_SVG_BYTES:
        return [png, stem + ".svg"]
    os.remove(stem + ".svg")
    fig.savefig(stem + ".pdf", bbox_inches="tight",
                metadata={"CreationDate": None, "ModDate": None})
    return [png, stem + ".pdf"]
