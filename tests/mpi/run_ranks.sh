#!/bin/sh
# `mpirun -np N swell run` end to end (ctest Mpi.RunOnSeveralRanks): the 2D dam break
# (a/dp = 20, to 0.06 s)
#   - on 1 rank, and on 2 ranks: gauges, diagnostics and the final checkpoint agree
#     (check_ranks.py; the bounds and why are there);
#   - on 2 ranks to 0.03 s, then restarted on 2 ranks to 0.06 s: bit for bit the
#     uninterrupted 2-rank run; restarted on 1 and on 3 ranks: within the same bounds;
#   - a second run into a folder that holds one is refused by rank 0 with exit 2, the others
#     leave with it (no rank waits forever), and the folder keeps its files unchanged;
#   - the watchdog (rank 0's check) stops a run on 2 ranks with exit 3;
#   - SIGINT to one rank stops every rank with exit 130 and a checkpoint, whose restart ends
#     bit for bit as the uninterrupted run; a restart by another case is refused with exit 2;
#   - a command other than run on 2 ranks is refused with exit 2;
#   - output from every rank (parallel HDF5 snapshots and checkpoints, VTK pieces + .pvtp;
#     gauges from the particles within their reach) against rank 0 writing everything from a
#     whole gather (SWELL_GATHER_OUTPUT=1): the same data and gauge files, bit for bit, and the
#     .pvtp files list every rank's piece.
#   - the set-up distributed over the ranks (each fills its share) against every rank setting
#     up the whole case (SWELL_WHOLE_SETUP=1): the same files and gauges, bit for bit; and the
#     restart on 3 ranks (each reads a block of rows) against every rank reading the whole
#     checkpoint, likewise.
# Every run has a sensor face (averaged each interval: rank 0 gathers after every step).
#   - mDBC on 1 and 2 ranks (to 0.02 s);
#   - the regular-wave flume with an absorbing piston (FLUME, 0.1 s, fixed dt) on 1 and 2
#     ranks: the paddle's water level is reduced over the ranks; the runs agree as above; and
#     again with the measuring line moved onto the slab face (both ranks' particles in its
#     sums): the same runs, and the absorber's state in the checkpoints within check_ranks.py's bound;
#   - a plate that straddles the slab face and moves across it (a moving wall whose particles
#     migrate between the ranks; tests/data/mpi_plate2d.yaml) on 1 and 2 ranks: the runs agree
#     as above, and part of the plate crossed the face;
#   - periodic boundaries (cases/film_slope2d.yaml made 0.12 m long, so the slabs lie along the
#     periodic x axis and form a ring; fixed dt, 0.02 s) on 1, 2 and 3 ranks, and restarted
#     from a 2-rank checkpoint on 2 ranks (bit for bit) and on 3: the runs agree as above, and
#     particles crossed the periodic face;
#   - restart at the worst moment for the slabs: a 2-rank run (fixed dt, a rebalance every 50
#     steps) checkpointed at step 250, so the restart's first evaluation rebalances; bit for
#     bit the uninterrupted run (and check_ranks.py checks the checkpoint is at that step).
# Usage: run_ranks.sh SWELL MPIRUN CASE WORKDIR FLUME
set -eu
swell=$1 mpirun=$2 case=$3 work=$4 flume=$5
here=$(cd "$(dirname "$0")" && pwd)
rm -rf "$work"; mkdir -p "$work"; cd "$work"
# A sensor face too: it averages over each interval, so rank 0 gathers after every step.
face='gauges.4={name: face, kind: pressure, at: [0.28575, 0.005], normal: [-1, 0], size: 0.004}'
run() {  # ranks, then swell run arguments
  n=$1; shift
  if [ "$n" = 1 ]; then "$swell" run "$case" -q -t 1 --set dp=0.0028575 --set "$face" "$@"
  else "$mpirun" --oversubscribe -np "$n" "$swell" run "$case" -q -t 1 --set dp=0.0028575 \
    --set "$face" "$@"; fi
}
run 1 -o r1 --set time.end=0.06 > r1.log
run 2 -o r2 --set time.end=0.06 > r2.log
SWELL_GATHER_OUTPUT=1 run 2 -o r2g --set time.end=0.06 > r2g.log
SWELL_WHOLE_SETUP=1 run 2 -o r2w --set time.end=0.06 > r2w.log
run 2 -o half --set time.end=0.03 > half.log
for n in 1 2 3; do
  cp -r half "re$n"
  run "$n" --restart "re$n" --set time.end=0.06 > "re$n.log"
done
# On 3 ranks each reads a block of the 2-rank checkpoint's rows; against every rank reading
# all of it (SWELL_WHOLE_SETUP=1): bit for bit.
cp -r half re3w
SWELL_WHOLE_SETUP=1 run 3 --restart re3w --set time.end=0.06 > re3w.log
# Refused: the folder already holds a run (rank 0's check); its checkpoint stays as it was.
sum0=$(md5sum r2/checkpoint.h5)
rc=0; run 2 -o r2 --set time.end=0.06 > refused.log 2>&1 || rc=$?
if [ "$rc" != 2 ]; then echo "FAIL: a run into a used folder on 2 ranks exited $rc, not 2"; cat refused.log; exit 1; fi
grep -q "already holds a run" refused.log || { echo "FAIL: no message from rank 0"; cat refused.log; exit 1; }
[ "$(md5sum r2/checkpoint.h5)" = "$sum0" ] || { echo "FAIL: the refused run changed r2"; exit 1; }
# The watchdog (every rank checks its particles, the results reduced) stops a run: every rank
# leaves with exit 3.
rc=0; run 2 -o wd --set time.end=0.06 --set watchdog.max_density=1.0001 > wd.log 2>&1 || rc=$?
if [ "$rc" != 3 ]; then echo "FAIL: a watchdog stop on 2 ranks exited $rc, not 3"; cat wd.log; exit 1; fi
grep -q "went unstable" wd.log || { echo "FAIL: no watchdog message"; cat wd.log; exit 1; }
# SIGINT to rank 1 alone of a 2-rank run, at its first progress line (2 s into the loop, mid
# run): every rank stops at the same step (the ranks share the request through a reduction
# before each step), rank 0 writes the checkpoint and says how to continue, and the run exits
# 130; continued on 2 ranks it ends bit for bit as the uninterrupted run (check_ranks.py:
# sigref against sig). 0.3 s of simulated time: long enough to be stopped before its end.
run 2 -o sigref --set time.end=0.3 > sigref.log
run 2 -o sig --set time.end=0.3 > sig.log 2>&1 &
job=$!
i=0
until grep -q "^t = " sig/run.log 2> /dev/null; do
  i=$((i + 1)); [ "$i" -lt 600 ] || { echo "FAIL: the run to interrupt never stepped"; cat sig.log; exit 1; }
  sleep 0.1
done
for p in $(pgrep -f -- "-o sig --set time.end=0.3"); do
  if tr '\0' '\n' < "/proc/$p/environ" 2> /dev/null | grep -qx OMPI_COMM_WORLD_RANK=1; then kill -INT "$p"; fi
done
rc=0; wait "$job" || rc=$?
[ "$rc" = 130 ] || { echo "FAIL: SIGINT to rank 1 of 2 exited $rc, not 130"; cat sig.log; exit 1; }
grep -q "stopped by SIGINT" sig.log || { echo "FAIL: rank 0 did not say it stopped"; cat sig.log; exit 1; }
grep -q "continue with: swell run" sig.log || { echo "FAIL: no restart hint"; cat sig.log; exit 1; }
grep -q "continue with" sig.log && ! grep -q "^  simulated time" sig.log ||
  { echo "FAIL: the run ended before the signal"; cat sig.log; exit 1; }
run 2 --restart sig --set time.end=0.3 > sig_re.log
# A restart with another case (an edit that changes the case's identity) is refused by every
# rank with exit 2, rank 0 saying why; the folder keeps its checkpoint.
sum0=$(md5sum < sig/checkpoint.h5)
rc=0; run 2 --restart sig --set time.end=0.3 --set physics.coefsound=21 > mismatch.log 2>&1 || rc=$?
[ "$rc" = 2 ] || { echo "FAIL: a restart by another case on 2 ranks exited $rc, not 2"; cat mismatch.log; exit 1; }
grep -q "differs from it" mismatch.log || { echo "FAIL: no case-identity message"; cat mismatch.log; exit 1; }
[ "$(md5sum < sig/checkpoint.h5)" = "$sum0" ] || { echo "FAIL: the refused restart changed sig"; exit 1; }
# A rank whose rows of a shared file fail (test hook, as a full disk would; parallel HDF5
# builds): every rank leaves with exit 1 (none waits forever), the folder keeps its checkpoint
# and earlier snapshots, and no temporary file is left.
if ls half/vtk/*.pvtp > /dev/null 2>&1; then
  cp -r half fail
  sum0=$(md5sum < fail/checkpoint.h5)
  rc=0; SWELL_TEST_FAIL_ROWS=1 timeout 120 "$mpirun" --oversubscribe -np 2 "$swell" run "$case" \
    -q -t 1 --set dp=0.0028575 --set "$face" --restart fail --set time.end=0.06 > fail.log 2>&1 || rc=$?
  [ "$rc" = 1 ] || { echo "FAIL: a failed shared write on 2 ranks exited $rc, not 1"; cat fail.log; exit 1; }
  grep -q "another rank could not write its particles" fail.log || { echo "FAIL: no message"; cat fail.log; exit 1; }
  [ "$(md5sum < fail/checkpoint.h5)" = "$sum0" ] || { echo "FAIL: the checkpoint changed"; exit 1; }
  if find fail -name '*.tmp' | grep -q .; then echo "FAIL: temporary files left"; find fail -name '*.tmp'; exit 1; fi
else
  echo "no parallel HDF5 in this build: the failed shared write is not tested"
fi
# Only `swell run` is decomposed: another command on 2 ranks is refused (exit 2).
rc=0; "$mpirun" --oversubscribe -np 2 "$swell" waves 0.05 1.2 0.4 > waves.log 2>&1 || rc=$?
[ "$rc" = 2 ] || { echo "FAIL: swell waves on 2 ranks exited $rc, not 2"; cat waves.log; exit 1; }
# mDBC through `swell run` (its halo is wider: the ghost nodes' reach) on 2 ranks against 1.
run 1 -o m1 --set time.end=0.02 --set physics.boundary.model=mdbc > m1.log
run 2 -o m2 --set time.end=0.02 --set physics.boundary.model=mdbc > m2.log
fl="--set bodies.1.motion.absorption=true --set time.end=0.1 --set time.dt_fixed=2e-4"
"$swell" run "$flume" -q -t 1 -o a1 $fl > a1.log
"$mpirun" --oversubscribe -np 2 "$swell" run "$flume" -q -t 1 -o a2 $fl > a2.log
# The absorber's measuring line across the slab face (2 ranks cut this flume at x = 6.33 m; the
# line 6.19 m in front of the face at 0.14 m): its kernel sums come from both ranks.
cut='bodies.1.motion.absorption={distance: 6.19}'
"$swell" run "$flume" -q -t 1 -o c1 $fl --set "$cut" > c1.log
"$mpirun" --oversubscribe -np 2 "$swell" run "$flume" -q -t 1 -o c2 $fl --set "$cut" > c2.log
rb="--set time.dt_fixed=4e-5 --rebalance 50"
run 2 -o rb_full $rb --set time.end=0.014 > rb_full.log
run 2 -o rb_half $rb --set time.end=0.01 > rb_half.log
cp -r rb_half rb_re
run 2 --restart rb_re $rb --set time.end=0.014 > rb_re.log
# A moving wall whose particles cross the slab face (tests/data/mpi_plate2d.yaml): 2 ranks
# against 1. No rebalancing: the face stays where the set-up's fluid count put it (the middle);
# a rebalance by work would move it after the plate (its walls weigh where they are wet).
plate="$here/../data/mpi_plate2d.yaml"
"$swell" run "$plate" -q -t 1 -o p1 > p1.log
"$mpirun" --oversubscribe -np 2 "$swell" run "$plate" -q -t 1 -o p2 --rebalance 0 > p2.log
# Periodic boundaries with the slabs along the periodic axis (a ring): the film flume made
# 0.12 m long, pulled along x by 5 m/s^2 so that its surface crosses the periodic face.
film="$here/../../cases/film_slope2d.yaml"
pf="--set domain.max=[0.12,0.04] --set bodies.0.shape.box.max=[0.12,0.03]
  --set bodies.1.shape.box.max=[0.12,0.02] --set physics.gravity=[5.0,-9.8]
  --set time.dt_fixed=2e-5 --set output.every=0.01"
"$swell" run "$film" -q -t 1 -o pf1 $pf --set time.end=0.02 > pf1.log
"$mpirun" --oversubscribe -np 2 "$swell" run "$film" -q -t 1 -o pf2 $pf --set time.end=0.02 > pf2.log
"$mpirun" --oversubscribe -np 3 "$swell" run "$film" -q -t 1 -o pf3 $pf --set time.end=0.02 > pf3.log
"$mpirun" --oversubscribe -np 2 "$swell" run "$film" -q -t 1 -o pfh $pf --set time.end=0.01 > pfh.log
for n in 2 3; do
  cp -r pfh "pfre$n"
  "$mpirun" --oversubscribe -np "$n" "$swell" run "$film" -q -t 1 --restart "pfre$n" $pf \
    --set time.end=0.02 > "pfre$n.log"
done
exec python3 "$here/check_ranks.py" "$work"
