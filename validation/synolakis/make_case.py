#!/usr/bin/env python3
"""Write (and optionally run) a 2D Synolakis (1987) solitary-wave runup case for one H/d.

Flume: a piston paddle at x = 0.1 m, a flat bed of depth d, then a 1:19.85 beach. The toe of the
beach lies L/2 beyond the paddle's mid-stroke position, where the crest leaves the paddle
(Synolakis puts the crest L/2 seaward of the toe at t = 0), with the wave's length
L = (2/k) arccosh(sqrt(20)), k = sqrt(3H/(4d^3)) (the 5 % width of sech^2). The run ends when the
crest has had 1.15 times the linear shallow-water travel time 2 X0 / sqrt(g d) to climb the beach
(X0 = d cot beta) after reaching the toe.

  python3 validation/synolakis/make_case.py --hd 0.04 --d 0.3 --dp 0.015 -o runs/h040.yaml
  python3 validation/synolakis/make_case.py --hd 0.04 --run            # also `swell run -t 1`

The runup gauge R (sampling: max, above the still-water level) lies along the beach from its toe
to its top; the maximum of its column is the maximum runup R (validation/synolakis/runup_table.py).
R_connected is the same gauge with `edge: connected` (the edge of the tongue attached to the sea,
splashes cut off further up not counted); runup_table.py reads R.
"""
import argparse
import math
import os
import subprocess
import sys

COT_BETA = 19.85
G = 9.81


def geometry(hd, d, dp, paddle_cols=2):
    H = hd * d
    k = math.sqrt(3.0 * H / (4.0 * d**3))
    L = 2.0 / k * math.acosh(math.sqrt(20.0))
    c = math.sqrt(G * (d + H))
    stroke = 2.0 * H / (k * d)                      # Goring (1978) paddle stroke
    duration = 2.0 * (3.8 + hd) / (k * c)           # Goring's motion duration
    paddle = (0.1, 0.1 + paddle_cols * dp)          # plate at rest, one column per wall layer
    x_crest0 = paddle[1] + 0.5 * stroke             # crest leaves the paddle about here
    x_toe = x_crest0 + 0.5 * L
    r_law = 2.831 * math.sqrt(COT_BETA) * hd**1.25 * d
    top = d + min(1.5 * r_law, 1.0 * d)             # beach top: room above the expected runup
    x_top = x_toe + COT_BETA * top
    t_end = 0.5 * duration + 0.5 * L / c + 1.15 * 2.0 * COT_BETA * d / math.sqrt(G * d)
    return dict(H=H, k=k, L=L, c=c, stroke=stroke, paddle=paddle, x_toe=x_toe, top=top,
                x_top=x_top, t_end=t_end, r_law=r_law)


def case_text(hd, d, dp, coefsound, name=None, coefh=1.0, viscosity="artificial", boundary="dbc",
              settle=0.0):
    # Wall layers (and paddle columns) for the full support 2h: ceil(2 coefh sqrt(2) - 1/2), 3 at
    # coefh 1 and 4 at 1.5 (until 2026-12-06 the paddle and beach had 2 at coefh 1, which `swell
    # run` warns of: see docs/validation/synolakis.md); viscosity: artificial alpha 0.01 or
    # water's laminar nu 1e-6. boundary mdbc: walls with mDBC's hydrostatic wall pressure (the
    # linear rule shoots the thin water at the shoreline off the beach:
    # docs/user-guide/boundaries.md#beaches-and-thin-water-pressure-hydrostatic), and the tank
    # open at its far end, which the beach's plateau buries (mDBC refuses a wall particle inside
    # another body). settle > 0: a settling phase of that many seconds before the paddle starts
    # (the run ends that much later).
    layers = math.ceil(2.0 * coefh * math.sqrt(2.0) - 0.5)
    g = geometry(hd, d, dp, layers)
    coefh = f"{coefh:.1f}" if coefh == round(coefh, 1) else f"{coefh:g}"
    visc = "{model: laminar, nu: 1.0e-6}" if viscosity == "laminar" else "{model: artificial, alpha: 0.01}"
    flags = (f" --coefh {coefh}" if coefh != "1.0" else "") + (
        f" --viscosity {viscosity}" if viscosity != "artificial" else "") + (
        f" --boundary {boundary}" if boundary != "dbc" else "") + (
        f" --settle {settle:g}" if settle > 0 else "")
    walls = "\n  boundary: {model: mdbc, pressure: hydrostatic}" if boundary == "mdbc" else ""
    tank_open = "[ymax, xmax]" if boundary == "mdbc" else "[ymax]"
    t_end = g["t_end"] + settle
    settling = f", settling: {{duration: {settle:g}}}" if settle > 0 else ""
    start = f", start: {settle:g}" if settle > 0 else ""
    f = lambda v: f"{v:.6g}"
    x_end = g["x_top"] + 3 * dp
    ytop = g["top"] + 0.1 * d
    return f"""# Synolakis (1987) solitary-wave runup on a 1:19.85 beach, H/d = {hd:g} (written by
# validation/synolakis/make_case.py --hd {hd:g} --d {d:g} --dp {dp:g}{flags}).
# d = {f(d)} m, H = {f(g['H'])} m (H/dp = {g['H']/dp:.2f}), L = {f(g['L'])} m, toe at x = {f(g['x_toe'])} m,
# law R = 2.831 sqrt(cot beta) (H/d)^(5/4) d = {f(g['r_law'])} m.
name: {name or f"synolakis_h{round(hd * 1000):03d}"}
dim: 2
dp: {f(dp)}
physics:
  rho0: 1000
  gravity: [0, -9.81]
  coefsound: {f(coefsound)}
  coefh: {coefh}
  viscosity: {visc}
  density_diffusion: {{model: fourtakas, delta: 0.1}}{walls}
time: {{end: {f(t_end)}, cfl: 0.2{settling}}}
bodies:
  - name: tank
    kind: boundary
    shape: {{box: {{min: [0, 0], max: [{f(x_end)}, {f(ytop)}]}}}}
    walls: inside
    layers: {layers}
    open: {tank_open}
  - name: paddle                       # piston, Goring (1978) solitary-wave trajectory
    kind: boundary
    shape: {{box: {{min: [{f(g['paddle'][0])}, 0], max: [{f(g['paddle'][1])}, {f(ytop)}]}}}}
    walls: outside
    layers: {layers}
    motion: {{type: wave, wave: solitary, depth: {f(d)}, height: {f(g['H'])}{start}}}
  - name: beach                        # 1:19.85 from the toe to the top
    kind: boundary
    shape: {{polygon: {{points: [[{f(g['x_toe'])}, 0], [{f(g['x_top'])}, {f(g['top'])}], [{f(x_end)}, {f(g['top'])}], [{f(x_end)}, 0]]}}}}
    walls: outside
    layers: {layers}
  - name: water
    kind: fluid
    shape: {{box: {{min: [{f(g['paddle'][1] + 0.5 * dp)}, 0], max: [{f(x_end)}, {f(d)}]}}}}
gauges:
  - {{name: R, kind: runup, from: [{f(g['x_toe'])}, 0], to: [{f(g['x_top'])}, {f(g['top'])}], swl: {f(d)}, sampling: max}}
  - {{name: R_connected, kind: runup, from: [{f(g['x_toe'])}, 0], to: [{f(g['x_top'])}, {f(g['top'])}], swl: {f(d)}, sampling: max, edge: connected}}
  - {{name: eta_toe, kind: height, at: [{f(g['x_toe'] - 0.5 * d)}, 0]}}
  - {{name: eta_mid, kind: height, at: [{f(0.5 * (g['paddle'][1] + g['x_toe']))}, 0]}}
output: {{every: {f(t_end / 20)}, vtk: false, hdf5: true, gauge_every: 0.02}}
"""


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--hd", type=float, required=True, help="H/d")
    ap.add_argument("--d", type=float, default=0.3, help="depth d [m] (default 0.3)")
    ap.add_argument("--dp", type=float, default=0.015, help="particle spacing [m] (default 0.015)")
    ap.add_argument("--coefsound", type=float, default=10.0, help="physics.coefsound (default 10: half the steps of 20; the flow stays below Mach 0.2)")
    ap.add_argument("--coefh", type=float, default=1.0, help="physics.coefh (default 1); walls and paddle get the layers of the full support (3 at coefh 1, 4 at 1.5)")
    ap.add_argument("--viscosity", choices=["artificial", "laminar"], default="artificial", help="artificial alpha 0.01 (default) or water's laminar nu 1e-6")
    ap.add_argument("--boundary", choices=["dbc", "mdbc"], default="dbc", help="wall model (default dbc); mdbc: hydrostatic wall pressure, tank open at its far end")
    ap.add_argument("--settle", type=float, default=0.0, help="settling phase [s] before the paddle starts (default 0; 3 with mdbc, whose water first settles onto the stepped beach)")
    ap.add_argument("--name", help="case name (default synolakis_hNNN, NNN = 1000 H/d)")
    ap.add_argument("-o", "--out", help="case file to write (default runs/synolakis_hNNN.yaml)")
    ap.add_argument("--run", action="store_true", help="run it: swell run -t 1")
    ap.add_argument("--swell", default="build/swell")
    a = ap.parse_args()
    for key in ("hd", "d", "dp", "coefsound", "coefh"):
        if not getattr(a, key) > 0:
            ap.error(f"--{key}: expected a number > 0, got {getattr(a, key)}")
    if not a.settle >= 0:
        ap.error(f"--settle: expected a number >= 0, got {a.settle}")
    path = a.out or f"runs/synolakis_h{round(a.hd * 1000):03d}.yaml"
    os.makedirs(os.path.dirname(path) or ".", exist_ok=True)
    with open(path, "w") as fh:
        fh.write(case_text(a.hd, a.d, a.dp, a.coefsound, a.name, a.coefh, a.viscosity, a.boundary,
                           a.settle))
    print(path)
    if a.run:
        out = os.path.splitext(path)[0]
        sys.exit(subprocess.call([a.swell, "run", path, "-t", "1", "-q", "-o", out, "--overwrite"]))


if __name__ == "__main__":
    main()
