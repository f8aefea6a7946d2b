#!/usr/bin/env python3
"""Weak-scaling projection of `mpirun -np P swell run` (issue #16): a model, not a measurement.

Inputs measured here (docs/user-guide/several-ranks.md; bench/RESULTS.md): the cost of one
particle-step on one thread (B3D, 1.60 M particle-steps/s), the record sizes the exchange sends
(3D: 103 B per halo image in a build, 56 B in a refresh), the calls per step: 2 migrations and 5 halo
exchanges (2 builds, 3 refreshes), each two rounds of point-to-point messages with the two
neighbouring ranks (sizes, then data), one allreduce per migration (whether any particle jumps
further than one slab: then, and after a rebalance, an all-to-all; rare, left out) and 6 more
small allreduces. Assumed, for a
typical cluster (state them when quoting): one rank per node of T = 32 threads with perfect
OpenMP scaling, latency 2 us, bandwidth 10 GB/s per node; an all-to-all of counts costs
latency x log2 P (Bruck), an all-to-allv latency x P (OpenMPI's linear exchange: every rank
posts P messages, even empty ones), a neighbour round one latency, an allreduce latency x
log2 P. Slabs along one axis: a
rank's halo is its two faces, independent of P in weak scaling.

Output is left out: each rank writes its own rows of the snapshot and checkpoint files
(parallel HDF5) and rank 0 gathers only the particles near the gauges, so it adds the file
system's time per snapshot, not a per-step cost. Also left out: the set-up, which every rank
still does for the whole case (its memory, ~140 B per particle of the case, bounds the run
size until the set-up is distributed).

Usage: scaling_projection.py [--per-rank N] [--threads T] [--latency S] [--bandwidth B/s]"""
import argparse
import math

p = argparse.ArgumentParser()
p.add_argument("--per-rank", type=float, default=1e6, help="particles per rank")
p.add_argument("--threads", type=int, default=32)
p.add_argument("--latency", type=float, default=2e-6)
p.add_argument("--bandwidth", type=float, default=10e9)
a = p.parse_args()

COST = 1.0 / 1.60e6           # s per particle-step, 1 thread (B3D, measured)
BUILD_B, REFRESH_B = 103, 56  # bytes per halo image (3D record; pos + vel + rho)
SUPPORT_DP = 2 * math.sqrt(3)  # halo depth in dp (2h, h = sqrt(3) dp, coefh 1)


def step_time(n_rank, ranks, cross_dp2):
    """Seconds per step: compute, latency, halo bandwidth (cross_dp2: slab face in dp^2)."""
    compute = n_rank * COST / a.threads
    lg = math.log2(max(ranks, 2))
    latency = a.latency * (2 * (lg + 2) + 5 * 2 + 6 * lg)
    images = 2 * cross_dp2 * SUPPORT_DP  # both faces
    halo = images * (2 * BUILD_B + 3 * REFRESH_B) / a.bandwidth
    return compute, latency, halo


# Weak scaling: a cube of per_rank particles per rank (face = per_rank^(2/3) dp^2).
face = a.per_rank ** (2.0 / 3.0)
print(f"weak scaling, {a.per_rank:.3g} particles per rank (a cube: face {face:.3g} dp^2), "
      f"{a.threads} threads per rank, latency {a.latency * 1e6:.3g} us, "
      f"bandwidth {a.bandwidth / 1e9:.3g} GB/s")
print("| ranks | compute [ms/step] | latency [ms/step] | halo transfer [ms/step] | efficiency |")
print("|---|---|---|---|---|")
for ranks in (1, 2, 8, 64, 256, 1024):
    c, l, h = step_time(a.per_rank, ranks, face if ranks > 1 else 0.0)
    if ranks == 1:
        l = h = 0.0
    print(f"| {ranks} | {c * 1e3:.3g} | {l * 1e3:.3g} | {h * 1e3:.3g} | {c / (c + l + h):.2f} |")

# A 30 s 3D caisson run on 64 ranks: flume 20 m x 1 m x 1 m of water (walls +50 %: N = 30 /
# dp^3), c0 = 20 sqrt(g d) with d = 1 m, dt = 0.2 h / c0 with h = sqrt(3) dp; slabs along the
# 20 m, face 1 m x 1.5 m.
print("\n30 s of a 3D caisson flume (20 x 1 x 1 m of water, N = 30/dp^3) on 64 ranks:")
print("| dp [m] | particles | steps | hours |")
print("|---|---|---|---|")
c0 = 20 * math.sqrt(9.81 * 1.0)
for dp in (0.02, 0.01, 0.0075, 0.006, 0.005):
    n = 30.0 / dp ** 3
    dt = 0.2 * math.sqrt(3) * dp / c0
    steps = 30.0 / dt
    c, l, h = step_time(n / 64, 64, 1.5 / dp ** 2)
    print(f"| {dp} | {n:.3g} | {steps:.3g} | {steps * (c + l + h) / 3600:.3g} |")
