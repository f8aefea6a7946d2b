#!/usr/bin/env bash
# The wall-model table of docs/validation/lobovsky2d_wall_loads.md: `swell validate
# lobovsky2d --run-sph` once per wall model and shifting choice, the case edited with --set
# (nothing else changes: documented defaults), each into OUT/<variant>/, then one table of the
# sensor and sensor-face metrics (wall_models_table.py).
#
#   validation/lobovsky2d/wall_models.sh [-d DP] [-t THREADS] [-e END] [-o OUT] [VARIANT ...]
#
# VARIANT: dbc, mdbc, dbc_shift, mdbc_shift (shifting near walls too: mode full),
# dbc_shift_nb, mdbc_shift_nb (mode nobound: not within the support of a wall); the wall's
# tangential condition: mdbc_freeslip, mdbc_noslip (physics.boundary.slip), mdbc_laminar,
# dbc_laminar (water's laminar viscosity instead of the artificial); default: the first six.
# DP defaults to the case's
# 0.004 m; END to the manifest's 1.5 s. Cost here (2 cores, 2 threads): about 5-8 min per
# variant at dp 4 mm, 1 min at dp 1 cm. SWELL names the swell binary (default: build/swell of
# this source tree, else swell on PATH).
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
root="$(cd "$here/../.." && pwd)"
dp=0.004 threads=2 end="" out="out/lobovsky_wall_models"
while getopts "d:t:e:o:h" opt; do
  case "$opt" in
    d) dp="$OPTARG" ;;
    t) threads="$OPTARG" ;;
    e) end="$OPTARG" ;;
    o) out="$OPTARG" ;;
    *) sed -n '2,16p' "$0" | sed 's/^# \{0,1\}//'; exit 2 ;;
  esac
done
shift $((OPTIND - 1))
variants=("$@")
((${#variants[@]})) || variants=(mdbc mdbc_shift_nb mdbc_shift dbc dbc_shift_nb dbc_shift)
swell="${SWELL:-}"
if [ -z "$swell" ]; then
  if [ -x "$root/build/swell" ]; then swell="$root/build/swell"; else swell=swell; fi
fi
mkdir -p "$out"
for v in "${variants[@]}"; do
  case "$v" in
    dbc) sets=(--set physics.boundary.model=dbc) ;;
    mdbc) sets=(--set physics.boundary.model=mdbc) ;;
    dbc_shift) sets=(--set physics.boundary.model=dbc --set "physics.shifting={model: fickian}") ;;
    mdbc_shift) sets=(--set physics.boundary.model=mdbc --set "physics.shifting={model: fickian}") ;;
    dbc_shift_nb) sets=(--set physics.boundary.model=dbc
      --set "physics.shifting={model: fickian, mode: nobound}") ;;
    mdbc_shift_nb) sets=(--set physics.boundary.model=mdbc
      --set "physics.shifting={model: fickian, mode: nobound}") ;;
    mdbc_freeslip | mdbc_noslip) sets=(--set physics.boundary.model=mdbc
      --set "physics.boundary.slip=${v#mdbc_}") ;;
    mdbc_laminar | dbc_laminar) sets=(--set "physics.boundary.model=${v%_laminar}"
      --set "physics.viscosity={model: laminar, nu: 1.0e-6}") ;;
    *)
      echo "wall_models.sh: unknown variant '$v' (dbc, mdbc, dbc_shift, mdbc_shift," \
        "dbc_shift_nb, mdbc_shift_nb, mdbc_freeslip, mdbc_noslip, mdbc_laminar, dbc_laminar)" >&2
      exit 2
      ;;
  esac
  args=(validate "$here/validation.yaml" --run-sph -t "$threads" -o "$out/$v" "${sets[@]}")
  args+=(--resolution "$dp")  # one dp (the manifest lists four)
  [ -n "$end" ] && args+=(--end "$end")
  echo "wall_models: $v: $swell ${args[*]}"
  "$swell" "${args[@]}" > "$out.$v.log" 2>&1 || true   # targets may fail: the table reports
  mkdir -p "$out/$v"; mv "$out.$v.log" "$out/$v/validate.log"
done
python3 "$here/wall_models_table.py" "$out" "${variants[@]}"
