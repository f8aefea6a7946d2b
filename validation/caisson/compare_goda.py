#!/usr/bin/env python3
"""Wave pressures and force on the caisson of cases/caisson_*2d.yaml against Goda's formula.

    /usr/bin/python3 validation/caisson/compare_goda.py --run out/caisson_regular2d \\
        [--case cases/caisson_regular2d.yaml] [--swell build/swell] [--out DIR] [--window t0,t1]
    ... --run out/caisson_focused2d --case cases/caisson_focused2d.yaml --window 6.5,8.5

Reads the run's gauge CSVs (gauges_pressure.csv, gauges_height.csv, gauges_force.csv) and the
case file (gauge positions, depth, period, caisson face and crest), and writes to --out:

  goda_distribution.csv  `swell waves goda` for the measured incident wave (the formula lives in
                         waves/goda.cpp only; this script interpolates its table)
  goda_comparison.csv    per probe: height, Goda's p, the measured per-wave maxima (mean, min,
                         max over the window) and their ratio to Goda; then the force rows
  goda_comparison.png    the distribution against the probes, and the force record (and
                         goda_comparison.svg beside it); the legend names the run "SPH dp
                         10 mm" from --dp, else the run's run_info.yaml, else the case's dp

Method (all stated in the output too):
  * still-water reference: each probe's and the force's mean over the still window (after the
    settling, before the first wave reaches the caisson) is subtracted, so the comparison is of
    the wave pressure, as Goda's p is below the SWL (above it Goda's p is the whole pressure and
    the still reading there is the probe's reading of the air, ~0);
  * incident wave: the first harmonic (least squares at 1/T over whole periods of the window)
    of the three height gauges eta_a, eta_b, eta_c, split into incident and reflected waves,
    Z_j = A exp(-i k x_j) + B exp(i k x_j) (k from the length `swell waves goda` prints);
    H_i = 2 |A| is Goda's H (the formula takes the incident height, not the standing wave's);
  * acoustic noise: the pressure and force records are smoothed by a centred boxcar one
    period of the depth's quarter-wave acoustic mode long, 4 h / c0 (c0 = coefsound sqrt(g h));
  * for reference only, linear theory of the standing wave (Kr = 1) of the same incident
    height under its crest: p = rho g H_i cosh k(h + z) / cosh kh below the SWL, force
    rho g H_i tanh(kh) / k (column "linear standing");
  * focused group (a `wave: focused` case): no separation at one frequency; H is estimated as
    the largest run-up at the wall (twice the incident crest at a reflecting wall, linear), T
    is Tp, and the maxima are taken once over the whole window;
  * per-wave maxima: the window is cut into periods T; in each the maximum of the probe's
    wave pressure and of the horizontal force; the window starts after the ramp has reached the
    caisson and ends before the waves re-reflected by the paddle come back (--window).
numpy and matplotlib only.
"""
import argparse
import csv
import math
import os
import re
import subprocess
import sys

import numpy as np

sys.dont_write_bytecode = True  # no __pycache__ beside the script (an installed tree)
sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))
from plot_style import length_text, save  # noqa: E402  (validation/plot_style.py; Agg backend)

import matplotlib.pyplot as plt  # noqa: E402


def read_gauges(path):
    """{column name without unit: numpy array}; empty cells and 'nan' become NaN."""
    rows = [r for r in csv.reader(open(path)) if r and not r[0].lstrip().startswith("#")]
    names = [h.split("[")[0].strip() for h in rows[0]]
    data = {n: [] for n in names}
    for r in rows[1:]:
        for n, v in zip(names, r + [""] * (len(names) - len(r))):
            v = v.strip()
            data[n].append(float(v) if v and v != "nan" else math.nan)
    return {n: np.array(v) for n, v in data.items()}


def case_numbers(path):
    """Gauge positions and the wave, from the case file's flow-style lines (this case's layout)."""
    text = open(path).read()
    gauges = {}
    for m in re.finditer(r"\{name: (\w+), kind: (\w+), at: \[([^\]]+)\]", text):
        gauges[m.group(1)] = (m.group(2), [float(v) for v in m.group(3).split(",")])
    wave = re.search(r"wave: regular, depth: ([\d.]+), height: ([\d.]+), period: ([\d.]+)", text)
    focused = re.search(r"wave: focused, depth: ([\d.]+), amplitude: ([\d.]+), tp: ([\d.]+)", text)
    if focused:  # nominal H: twice the linear crest amplitude at the focus; T: the peak period
        wave = focused
    if not wave:
        raise SystemExit(f"{path}: no 'wave: regular, depth: .., height: .., period: ..' line "
                         "nor 'wave: focused, depth: .., amplitude: .., tp: ..'")
    rho = float(re.search(r"rho0: ([\d.]+)", text).group(1))
    coefsound = float(re.search(r"coefsound: ([\d.]+)", text).group(1))
    g = -float(re.search(r"gravity: \[0, (-?[\d.]+)\]", text).group(1))
    caisson = re.search(r"caisson_vertical.stl, translate: \[([\d.]+), 0, 0\]", text)
    return {
        "gauges": gauges,
        "depth": float(wave.group(1)),
        "height": float(wave.group(2)) * (2.0 if focused else 1.0),
        "focused": bool(focused),
        "period": float(wave.group(3)),
        "rho": rho,
        "g": g,
        "coefsound": coefsound,
        "face_x": float(caisson.group(1)),
        "crest": 0.6,  # cases/geometry/caisson_vertical.stl is 0.6 m high, on the bed
    }


def run_dp(run, case_path, given):
    """The run's particle spacing [m] and where it was read: --dp, run_info.yaml, the case."""
    if given:
        return given, "--dp"
    info = os.path.join(run, "run_info.yaml")
    if os.path.exists(info):
        m = re.search(r"^resolution:\s*([0-9.eE+-]+)", open(info).read(), re.M)
        if m:
            return float(m.group(1)), info
    m = re.search(r"^dp:\s*([0-9.eE+-]+)", open(case_path).read(), re.M)
    if not m:
        raise SystemExit(f"{case_path}: no 'dp:' line, and no --dp or {info}")
    return float(m.group(1)), case_path


def first_harmonic(t, y, omega):
    """Complex amplitude Z of y ~ a0 + Re(Z exp(i omega t)), least squares."""
    m = np.isfinite(y)
    a = np.column_stack([np.ones(m.sum()), np.cos(omega * t[m]), np.sin(omega * t[m])])
    c = np.linalg.lstsq(a, y[m], rcond=None)[0]
    return c[1] - 1j * c[2]


def goda(swell, h_inc, c, csv_path):
    """Runs `swell waves goda` for the incident height; returns (scalars, z, p)."""
    cmd = [swell, "waves", "goda", "%.6g" % h_inc, "%.6g" % c["period"], "%.6g" % c["depth"],
           "--hc", "%.6g" % (c["crest"] - c["depth"]), "--rho", "%.6g" % c["rho"],
           "-g", "%.6g" % c["g"], "--csv", csv_path]
    report = subprocess.run(cmd, check=True, capture_output=True, text=True).stdout
    scalars, z, p = {}, [], []
    for row in open(csv_path):
        if row.startswith("# swell"):
            continue
        if row.startswith("# ") and ": " in row:
            key, value = row[2:].rsplit(": ", 1)
            try:
                scalars[key] = float(value)
            except ValueError:  # the provenance lines (version, commit, ...) are not numbers
                continue
        elif row[0] not in "#z":
            zz, pp = row.split(",")
            z.append(float(zz))
            p.append(float(pp))
    shown = [os.path.relpath(a) if os.path.isabs(a) else a for a in cmd]
    return scalars, np.array(z), np.array(p), report, " ".join(shown)


def boxcar(t, y, width):
    """Centred moving mean over `width` seconds (rows about evenly spaced); NaN where any is."""
    n = max(1, int(round(width / np.median(np.diff(t)))))
    return np.convolve(y, np.ones(n) / n, mode="same"), n * np.median(np.diff(t))


def per_wave_maxima(t, y, t0, t1, period):
    """Maximum of y in each whole period [t0 + nT, t0 + (n+1)T) inside [t0, t1] (one maximum
    when the period is the window)."""
    n = int(math.floor((t1 - t0) / period + 1e-9))
    out = []
    for i in range(n):
        m = (t >= t0 + i * period) & (t < t0 + (i + 1) * period) & np.isfinite(y)
        if m.any():
            out.append(y[m].max())
    return np.array(out)


def main(argv):
    root = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--run", required=True, help="output folder of swell run")
    ap.add_argument("--case", default=os.path.join(root, "cases", "caisson_regular2d.yaml"))
    ap.add_argument("--swell", default=os.path.join(root, "build", "swell"))
    ap.add_argument("--out", default=os.path.join(root, "validation", "caisson", "results"))
    ap.add_argument("--window", default="5.5,8.5", help="steady window t0,t1 [s]")
    ap.add_argument("--still", default="1.0,2.0", help="still-water window t0,t1 [s]")
    ap.add_argument("--label", default="", help="text for the plot title (dp, wall time)")
    ap.add_argument("--dp", type=float, default=None,
                    help="the run's particle spacing [m] for the legend (default: the run's "
                    "run_info.yaml, else the case file's dp)")
    args = ap.parse_args(argv)
    if args.dp is not None and not args.dp > 0:
        ap.error("--dp: expected a particle spacing > 0 [m], got %g" % args.dp)
    t0, t1 = (float(v) for v in args.window.split(","))
    s0, s1 = (float(v) for v in args.still.split(","))
    os.makedirs(args.out, exist_ok=True)

    c = case_numbers(args.case)
    h, T, rho, g = c["depth"], c["period"], c["rho"], c["g"]
    pres = read_gauges(os.path.join(args.run, "gauges_pressure.csv"))
    level = read_gauges(os.path.join(args.run, "gauges_height.csv"))
    force = read_gauges(os.path.join(args.run, "gauges_force.csv"))
    if pres["time"][-1] < t1:
        raise SystemExit(f"{args.run}: the record ends at t = {pres['time'][-1]:.3g} s < {t1} s")

    # Incident wave from the three level gauges (first harmonic, whole periods of the window).
    omega = 2 * math.pi / T
    n_periods = int(math.floor((t1 - t0) / T + 1e-9))
    tw1 = t0 + n_periods * T
    if c["focused"]:  # one event: the maximum over the whole window
        n_periods, tw1 = 1, t1
    dist_csv = os.path.join(args.out, "goda_distribution.csv")
    nominal, _, _, _, _ = goda(args.swell, c["height"], c, dist_csv)
    k = 2 * math.pi / nominal["L [m]"]
    tl = level["time"]
    mw = (tl >= t0) & (tl < tw1)
    names = ["eta_a", "eta_b", "eta_c"]
    xs = np.array([c["gauges"][n][1][0] for n in names])
    z = np.array([first_harmonic(tl[mw], level[n][mw], omega) for n in names])
    a = np.column_stack([np.exp(-1j * k * xs), np.exp(1j * k * xs)])
    (amp_i, amp_r), *_ = np.linalg.lstsq(a, z, rcond=None)
    h_inc, h_ref = 2 * abs(amp_i), 2 * abs(amp_r)
    still_level = np.nanmean(level["eta_wall"][(tl >= s0) & (tl < s1)])
    span = tw1 - t0 if c["focused"] else T  # the interval of each maximum
    runup = per_wave_maxima(tl, level["eta_wall"] - still_level, t0, tw1, span)
    incident_method = "first harmonic, 3-gauge separation"
    if c["focused"]:
        # A transient group has no single frequency to separate at. Estimate instead: at a
        # fully reflecting wall the level is twice the incident one (linear), so the largest
        # run-up is twice the incident crest, i.e. H for a symmetric linear wave. The regular
        # case measures the bias of this estimate (run-up / separated H_i = 1.07 at dp 0.01).
        h_inc, h_ref = runup.max(), math.nan
        incident_method = "focused group: largest run-up at the wall, = 2 x incident crest"

    scal, gz, gp, report, command = goda(args.swell, h_inc, c, dist_csv)

    # The readings carry the acoustic oscillation of WCSPH (the quarter-wave mode of the depth,
    # f = c0 / 4h: 14 Hz here, tens of Pa): a boxcar of that period removes it and keeps the
    # wave's first harmonic to sinc(width / T) (0.99 here).
    c0 = c["coefsound"] * math.sqrt(g * h)
    width = 4 * h / c0
    # Probes: wave pressure = reading - its still-water mean; per-wave maxima.
    tp = pres["time"]
    still = (tp >= s0) & (tp < s1)
    rows = []
    for name, (kind, at) in c["gauges"].items():
        if kind != "pressure":
            continue
        y = at[1]
        p0 = np.nanmean(pres[name][still])
        hydro = rho * g * max(h - y, 0.0)
        filtered, width_s = boxcar(tp, pres[name] - p0, width)
        wave = per_wave_maxima(tp, filtered, t0, tw1, span)
        raw = per_wave_maxima(tp, pres[name] - p0, t0, tw1, span)
        goda_p = float(np.interp(y - h, gz, gp, left=0.0, right=0.0))
        rows.append((name, y, y - h, goda_p, wave.mean(), wave.min(), wave.max(), p0, hydro,
                     raw.mean()))

    tf = force["time"]
    fx = force["F_caisson_fx"]
    f0 = np.nanmean(fx[(tf >= s0) & (tf < s1)])
    fx_box, _ = boxcar(tf, fx - f0, width)
    f_raw = per_wave_maxima(tf, fx - f0, t0, tw1, span)
    f_box = per_wave_maxima(tf, fx_box, t0, tw1, span)
    hydro_force = 0.5 * rho * g * h * h

    # Force from the probes: trapezoid rule over the probe heights of the simultaneous wave
    # pressures (the distribution between probes taken linear), per-wave maxima.
    heights = np.array([r[1] for r in rows])
    order = np.argsort(heights)
    series = np.array([pres[rows[i][0]] - rows[i][7] for i in order])
    zs = heights[order]
    edges = np.concatenate([[0.0], zs, [zs[-1] + 0.01]])
    vals = np.vstack([series[0], series, np.zeros_like(series[0])])
    probe_force = np.trapz(np.nan_to_num(vals), edges, axis=0)
    probe_force, _ = boxcar(tp, probe_force, width)
    f_probe = per_wave_maxima(tp, probe_force, t0, tw1, span)
    # Linear standing wave in front of a wall (Kr = 1, incident H_i), for reference only:
    # p = rho g H_i cosh k(h + z) / cosh kh under the crest, below the SWL.
    zl = np.linspace(-h, 0.0, 50)
    p_linear = rho * g * h_inc * np.cosh(k * (h + zl)) / np.cosh(k * h)

    table = os.path.join(args.out, "goda_comparison.csv")
    with open(table, "w", newline="\n") as f:
        f.write("# %s against Goda (1974, 2000): %s\n" % (os.path.relpath(args.case), args.label))
        f.write("# run %s; window %.3g-%.3g s (%d waves), still window %.3g-%.3g s, boxcar "
                "%.3g s (sph columns; 'raw' without it)\n" % (args.run, t0, tw1, n_periods, s0, s1,
                                                             width_s))
        f.write("# incident H (%s) %.5g m, reflected %.5g m, Kr %.4g; target H %.5g m\n"
                % (incident_method, h_inc, h_ref, h_ref / h_inc, c["height"]))
        f.write("# wall run-up (eta_wall per-wave max above still level): mean %.5g m\n"
                % runup.mean())
        f.write("# Goda: %s\n" % command)
        f.write("probe,y [m],z [m],goda [Pa],sph mean max [Pa],sph min [Pa],sph max [Pa],"
                "ratio,still reading [Pa],rho g (h-y) [Pa],sph raw mean max [Pa],linear standing [Pa]\n")
        for r in rows:
            ratio = r[4] / r[3] if r[3] > 0 else math.nan
            lin = (rho * g * h_inc * math.cosh(k * r[1]) / math.cosh(k * h)) if r[2] <= 0 else math.nan
            f.write("%s,%.4g,%.4g,%.5g,%.5g,%.5g,%.5g,%.4g,%.5g,%.5g,%.5g,%.5g\n"
                    % (r[0], r[1], r[2], r[3], r[4], r[5], r[6], ratio, r[7], r[8], r[9], lin))
        f.write("force,,,%.5g,%.5g,%.5g,%.5g,%.4g,%.5g,%.5g,,%.5g\n"
                % (scal["force [N/m]"], f_box.mean(), f_box.min(), f_box.max(),
                   f_box.mean() / scal["force [N/m]"], f0, hydro_force,
                   rho * g * h_inc * math.tanh(k * h) / k))
        f.write("force (raw),,,%.5g,%.5g,%.5g,%.5g,%.4g,,,,\n"
                % (scal["force [N/m]"], f_raw.mean(), f_raw.min(), f_raw.max(),
                   f_raw.mean() / scal["force [N/m]"]))
        f.write("force (probes),,,%.5g,%.5g,%.5g,%.5g,%.4g,,,,\n"
                % (scal["force [N/m]"], f_probe.mean(), f_probe.min(), f_probe.max(),
                   f_probe.mean() / scal["force [N/m]"]))

    dp, dp_from = run_dp(args.run, args.case, args.dp)
    sph = "SPH dp " + length_text(dp)
    fig, (ax1, ax2) = plt.subplots(1, 2, figsize=(12, 5.2),
                                   gridspec_kw={"width_ratios": [1, 1.6]})
    ax1.plot(gp, gz, color="black", ls="-", lw=1.3,
             label="Goda (1974, 2000), H = %.4g m (incident)" % h_inc)
    ym = np.array([r[2] for r in rows])
    ax1.errorbar([r[4] for r in rows], ym,
                 xerr=[[r[4] - r[5] for r in rows], [r[6] - r[4] for r in rows]],
                 fmt="o", color="#0072B2", mfc="white", mew=1.3, capsize=3,
                 label=sph + (", maximum of the group" if c["focused"] else
                              ", per-wave maxima (mean, range)"))
    ax1.plot(p_linear, zl, color="0.35", ls=(0, (1, 1.5)), lw=1.5,
             label="linear standing wave (reference)")
    ax1.axhline(0.0, color="0.6", lw=0.8)
    ax1.text(ax1.get_xlim()[0], 0.0, " SWL", ha="left", va="bottom", fontsize=7, color="0.4")
    ax1.set_xlabel("wave pressure p [Pa]")
    ax1.set_ylabel("z above SWL [m]")
    ax1.set_title("pressure on the seaward face", fontsize=10)
    ax1.legend(fontsize=8, loc="upper center", bbox_to_anchor=(0.5, -0.13), frameon=False)
    ax1.grid(alpha=0.3)
    ax2.plot(tf, fx - f0, color="0.7", ls="-", lw=0.6, label=sph + ", F_x - still (raw)")
    ax2.plot(tf, fx_box, color="#0072B2", ls="-", lw=1.2,
             label=sph + ", F_x - still, %.2g s boxcar" % width_s)
    ax2.plot(tp, probe_force, color="#009E73", ls="--", lw=1.1,
             label=sph + ", from the pressure probes")
    ax2.axhline(scal["force [N/m]"], color="black", ls="-.", lw=1.2,
                label="Goda %.4g N/m" % scal["force [N/m]"])
    ax2.axvspan(t0, tw1, color="0.5", alpha=0.08, lw=0, zorder=0)
    for x in (t0, tw1):
        ax2.axvline(x, color="0.45", lw=0.8, ls=(0, (4, 3)))
    ax2.text(0.5 * (t0 + tw1), 0.98, "maxima window", transform=ax2.get_xaxis_transform(),
             ha="center", va="top", fontsize=7, color="0.25",
             bbox=dict(facecolor="white", edgecolor="none", alpha=0.8, pad=0.5))
    ax2.set_xlabel("t [s]")
    ax2.set_ylabel("horizontal wave force per metre [N/m]")
    ax2.set_title("force on the caisson (2D: per metre of width)", fontsize=10)
    ax2.legend(fontsize=8, loc="upper center", bbox_to_anchor=(0.5, -0.13), ncol=2,
               frameon=False, handlelength=3.2)
    ax2.grid(alpha=0.3)
    name = os.path.splitext(os.path.basename(args.case))[0]
    fig.suptitle("%s vs Goda: %s" % (name, args.label or sph), fontsize=10)
    png, svg = save(fig, os.path.join(args.out, "goda_comparison.png"), dpi=110)
    print("legend: %s (dp from %s)" % (sph, dp_from))

    print(report, end="")
    print("incident H %.5g m (target %.5g), reflected %.5g m, Kr %.4g; window %.3g-%.3g s, %d waves"
          % (h_inc, c["height"], h_ref, h_ref / h_inc, t0, tw1, n_periods))
    print(open(table).read(), end="")
    print("wrote %s, %s, %s, %s" % (dist_csv, table, png, svg))
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
