#!/usr/bin/env python3
"""Long waves of a bichromatic group (cases/wave_bound_long2d.yaml): first- against second-order
generation.

For each run (a `swell run` output folder) and gauge, the surface elevation is low-passed
(zero-phase FFT filter, cosine taper from --fcut to 1.25 --fcut; the group's components are at
0.65 and 0.80 Hz, its difference frequency 0.15 Hz) and set against the second-order bound long
wave the paddle is meant to make there (`swell waves target ... --csv`, column eta_bound_X,
low-passed alike, for the figure). Over each gauge's window the raw record is fitted by least
squares with a harmonic at the group's difference frequency together with the two components,
their sum and double frequencies, a mean and a linear trend (the SPH height gauge's mean level
drifts by a few mm in a wave run), and the bound wave with the same difference harmonic: the
amplitudes, the phase lag, the part of
the measured harmonic that is not the bound wave (the free long waves a paddle sheds), the fit's
residual and the correlation of the low-passed series; and, since the bound wave goes as the
product of the two amplitudes, the two first-order amplitudes measured at the gauge against the
target's and the measured long wave against the bound wave of those measured amplitudes.
Writes a table (CSV) and a figure.

usage: bound_long_wave.py --target target.csv --face 0.14 RUN1 [RUN2 ...] -o OUTDIR
(target.csv: `swell waves target CASE --at X1,X2,.. --end T --every 0.01 --csv target.csv`,
X = gauge x - face)
"""
import argparse
import csv
import os
import sys

import numpy as np


def read_csv(path):
    rows, header = [], None
    with open(path) as f:
        for line in f:
            if line.startswith("#"):
                continue
            if header is None:
                header = [h.strip() for h in line.strip().split(",")]
                continue
            if line.strip():
                rows.append([float(v) for v in line.split(",")])
    return header, np.array(rows)


def lowpass(t, y, fcut):
    """Zero-phase low-pass on a uniform resampling of (t, y); cosine taper fcut..1.25 fcut. The
    record is mirrored at both ends first, so the filter sees no jump where it wraps round."""
    dt = np.median(np.diff(t))
    tu = np.arange(t[0], t[-1], dt)
    yu = np.interp(tu, t, y)
    n = len(yu)
    ext = np.concatenate([yu[::-1], yu, yu[::-1]])
    f = np.fft.rfftfreq(len(ext), dt)
    w = np.clip((1.25 * fcut - f) / (0.25 * fcut), 0.0, 1.0)
    w = 0.5 - 0.5 * np.cos(np.pi * w)
    return tu, np.fft.irfft(np.fft.rfft(ext) * w, len(ext))[n:2 * n]


def amplitudes(t, y, freqs):
    """Least-squares amplitudes of y at the given frequencies (with a mean)."""
    cols = [np.ones_like(t)]
    for f in freqs:
        cols += [np.cos(2 * np.pi * f * t), np.sin(2 * np.pi * f * t)]
    c, *_ = np.linalg.lstsq(np.column_stack(cols), y, rcond=None)
    return [np.hypot(c[1 + 2 * i], c[2 + 2 * i]) for i in range(len(freqs))]


def harmonic(t, y, f, others=()):
    """Least-squares fit y ~ A cos(2 pi f t - phi) + the harmonics at `others` + c0 + c1 t:
    (A, phi, residual RMS)."""
    cols = [np.ones_like(t), t - t.mean()]
    for fo in (f,) + tuple(others):
        cols += [np.cos(2 * np.pi * fo * t), np.sin(2 * np.pi * fo * t)]
    m = np.column_stack(cols)
    c, *_ = np.linalg.lstsq(m, y, rcond=None)
    res = y - m @ c
    return np.hypot(c[2], c[3]), np.arctan2(c[3], c[2]), np.sqrt(np.mean(res ** 2))


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("runs", nargs="+", help="swell run output folders")
    ap.add_argument("--target", required=True, help="CSV of `swell waves target`")
    ap.add_argument("--face", type=float, required=True, help="paddle face x at rest [m]")
    ap.add_argument("--fcut", type=float, default=0.4, help="low-pass cut-off [Hz]")
    ap.add_argument("--still", type=float, default=1.0,
                    help="still level: the gauge's mean over t < this [s]")
    ap.add_argument("--window", default="2m:4:17,4m:5.5:16,6m:7:15",
                    help="per gauge suffix: from:to [s] (the window before long waves return)")
    ap.add_argument("--freqs", default="0.65,0.80",
                    help="the group's two component frequencies [Hz]")
    ap.add_argument("-o", "--out", required=True)
    a = ap.parse_args()

    th, tgt = read_csv(a.target)
    f1, f2 = (float(v) for v in a.freqs.split(","))
    a.fgroup = abs(f2 - f1)
    windows = {}
    for item in a.window.split(","):
        name, t0, t1 = item.split(":")
        windows[name] = (float(t0), float(t1))
    os.makedirs(a.out, exist_ok=True)
    table = []
    series = {}
    for run in a.runs:
        gh, g = read_csv(os.path.join(run, "gauges_height.csv"))
        label = os.path.basename(os.path.normpath(run))
        for col, name in enumerate(gh[1:], start=1):
            gname = name.split(" ")[0]
            suffix = gname.split("_")[-1]
            x = float(suffix.rstrip("m")) - a.face
            key = None
            for i, h in enumerate(th):
                if h.startswith("eta_bound_") and abs(float(h.split("_")[-1].split(" ")[0]) - x) < 1e-6:
                    key = i
            if key is None:
                sys.exit(f"{a.target}: no eta_bound column for x = {x:g} m ({gname})")
            t = g[:, 0]
            still = np.mean(g[t < a.still, col])
            # The first-order waves that arrived: their amplitudes at this gauge against the
            # target's (the target's elevation less its bound part), over the same window.
            t0, t1 = windows.get(suffix, (t[0], t[-1]))
            wm = (t >= t0) & (t <= t1)
            wt = (tgt[:, 0] >= t0) & (tgt[:, 0] <= t1)
            am1, am2 = amplitudes(t[wm], g[wm, col] - still, (f1, f2))
            at1, at2 = amplitudes(tgt[wt, 0], tgt[wt, key - 1] - tgt[wt, key], (f1, f2))
            scale = am1 * am2 / (at1 * at2)
            tu, eta_l = lowpass(t, g[:, col] - still, a.fcut)
            tb, bound_l = lowpass(tgt[:, 0], tgt[:, key], a.fcut)
            bound_i = np.interp(tu, tb, bound_l)
            m = (tu >= t0) & (tu <= t1)
            # The long wave's harmonic from the raw record, fitted together with the two
            # components and their second-order sum and double frequencies (no filter in the
            # way); the bound wave's from the target alike.
            ab, pb, _ = harmonic(tgt[wt, 0], tgt[wt, key], a.fgroup)
            am, pm, res = harmonic(t[wm], g[wm, col] - still, a.fgroup,
                                   (f1, f2, f1 + f2, 2 * f1, 2 * f2))
            dphase = (pm - pb + np.pi) % (2 * np.pi) - np.pi  # + : the measured wave lags
            # The part at the group frequency that is not the bound wave (free long waves).
            free = np.hypot(am * np.cos(pm) - ab * np.cos(pb), am * np.sin(pm) - ab * np.sin(pb))
            corr = np.corrcoef(eta_l[m], bound_i[m])[0, 1]
            table.append([label, gname, f"{t0:g}-{t1:g}", f"{1e3 * ab:.2f}", f"{1e3 * am:.2f}",
                          f"{am / ab:.2f}", f"{dphase / (2 * np.pi):+.3f}", f"{1e3 * free:.2f}",
                          f"{free / ab:.2f}", f"{1e3 * res:.2f}", f"{corr:.2f}",
                          f"{am1 / at1:.3f} / {am2 / at2:.3f}", f"{am / (ab * scale):.2f}"])
            series[(label, gname)] = (tu, eta_l, bound_i, (t0, t1))
    head = ["run", "gauge", "window [s]", "bound amplitude [mm]", "measured amplitude [mm]",
            "measured / bound", "phase lag [group periods]", "not bound [mm]",
            "not bound / bound", "fit residual RMS [mm]", "correlation",
            "first-order a1 / a2 vs target", "measured / bound of the measured a1 a2"]
    gauges = sorted({k[1] for k in series}, key=lambda s: float(s.split("_")[-1].rstrip("m")))
    write_outputs(a.out, "bound_long_wave", head, table, gauges,
                  [os.path.basename(os.path.normpath(r)) for r in a.runs], series,
                  "low-passed [mm]")


def write_outputs(out, stem, head, table, gauges, labels, series, ylabel):
    """OUT/STEM.csv (and the table as Markdown on stdout) and OUT/STEM.png: per gauge, the
    theory's bound wave and each run's long wave; series[(label, gauge)] = (t, measured, bound,
    window or None)."""
    with open(os.path.join(out, stem + ".csv"), "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(head)
        w.writerows(table)
    print("| " + " | ".join(head) + " |")
    print("|" + "---|" * len(head))
    for r in table:
        print("| " + " | ".join(r) + " |")

    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, axes = plt.subplots(len(gauges), 1, figsize=(8, 2.4 * len(gauges)), sharex=True)
    axes = np.atleast_1d(axes)
    for ax, gname in zip(axes, gauges):
        for i, label in enumerate(labels):
            tt, measured, bound, window = series[(label, gname)]
            if i == 0:
                ax.plot(tt, 1e3 * bound, "k--", lw=1.2, label="bound long wave (theory)")
                if window:
                    ax.axvspan(window[0], window[1], color="0.92")
            ax.plot(tt, 1e3 * measured, lw=1.0, label=f"SPH {label}")
        ax.set_ylabel(f"{gname}\n{ylabel}")
        ax.grid(alpha=0.3)
    axes[0].legend(fontsize=8, loc="upper left")
    axes[-1].set_xlabel("t [s]")
    fig.tight_layout()
    fig.savefig(os.path.join(out, stem + ".png"), dpi=120)
    print("written:", os.path.join(out, stem + ".csv"), os.path.join(out, stem + ".png"))


if __name__ == "__main__":
    main()
