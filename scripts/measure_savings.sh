#!/usr/bin/env bash
# Measures what "compute only what a scene needs" saves (docs/performance.md), each figure the
# median of REPEAT alternating runs on one thread:
#  friction:  bench particle-steps/s of the thesis D/d = 4, 40 % pile with mu = 0 (no tangential
#             springs) against mu = 1e-300 (the same flow, springs kept and computed)
#  pictures:  peak RSS, shared objects and start-up time of the binary with no picture option
#  series:    wall time of a run of SCENE with output.series = [] against every series
#  snapshots: wall time of SCENE with --snapshots 0,20,40, with and without --end-at-last-snapshot
# Usage: scripts/measure_savings.sh [SCENE] [REPEAT]
set -euo pipefail
scene=${1:-examples/thesis_2_10.toml}
repeat=${2:-3}
bin=${RUNOUT:-build/apps/runout}
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
median() { printf '%s\n' "$@" | sort -n | awk '{a[NR]=$1} END {print (NR % 2) ? a[(NR+1)/2] : (a[NR/2] + a[NR/2+1]) / 2}'; }
# $EPOCHREALTIME, not $(date): a second date process was timed with the command. The fork of
# the shell that starts the command is still timed with it. Bash writes $EPOCHREALTIME with the
# locale's decimal mark, which bc reads only as a point: hence C.
export LC_ALL=C
seconds() { local s=$EPOCHREALTIME; "$@" >/dev/null 2>&1; echo "$EPOCHREALTIME - $s" | bc; }

echo "== friction (bench, 1 thread)"
for mu in 0 1e-300; do "$bin" bench --threads 1 --steps 100 --set material.friction=$mu --set material.wall_friction=$mu >/dev/null 2>&1; done
zero=() tiny=()
for i in $(seq "$repeat"); do
  zero+=("$("$bin" bench --threads 1 --set material.friction=0 --set material.wall_friction=0 2>/dev/null | awk '/particle_steps_per_second/ {print $2}')")
  tiny+=("$("$bin" bench --threads 1 --set material.friction=1e-300 --set material.wall_friction=1e-300 2>/dev/null | awk '/particle_steps_per_second/ {print $2}')")
done
echo "mu_0_particle_steps_per_second: ${zero[*]} median $(median "${zero[@]}")"
echo "mu_1e-300_particle_steps_per_second: ${tiny[*]} median $(median "${tiny[@]}")"

echo "== pictures (no picture option)"
/usr/bin/time -f "plain_run_peak_rss_kib: %M" "$bin" run examples/quick.toml --out "$out/q" -q >/dev/null
echo "shared_objects_mapped_at_start: $(ldd "$bin" | wc -l)"
starts=()
for i in $(seq 20); do starts+=("$(seconds "$bin" --version)"); done
echo "start_up_seconds_median_of_20: $(median "${starts[@]}")"

# compare LABEL_A LABEL_B -- ARGS_A -- ARGS_B: REPEAT alternating timed `runout run SCENE` runs.
compare() {
  local la=$1 lb=$2; shift 3
  local args_a=() args_b=()
  while [ "$1" != "--" ]; do args_a+=("$1"); shift; done; shift
  args_b=("$@")
  local ta=() tb=()
  for i in $(seq "$repeat"); do
    ta+=("$(seconds "$bin" run "$scene" --out "$out/$la" -q --threads 1 "${args_a[@]}")")
    tb+=("$(seconds "$bin" run "$scene" --out "$out/$lb" -q --threads 1 "${args_b[@]}")")
  done
  echo "${la}_seconds: ${ta[*]} median $(median "${ta[@]}")"
  echo "${lb}_seconds: ${tb[*]} median $(median "${tb[@]}")"
}

echo "== series ($scene)"
"$bin" run "$scene" --out "$out/warm" -q --threads 1 >/dev/null  # settle and cache the pile first
compare all_series no_series -- -- --set 'output.series=[]'

echo "== snapshots 0,20,40 ($scene)"
compare to_rest end_at_last_snapshot -- --snapshots 0,20,40 -- --snapshots 0,20,40 --end-at-last-snapshot
grep -h '"t_star_end"' "$out/to_rest/summary.json" "$out/end_at_last_snapshot/summary.json"
