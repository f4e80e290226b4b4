#!/usr/bin/env bash
# Measures the wall time a movie adds to a run: the same scene with and without --movie,
# alternately, REPEAT times each; prints every time, the medians, and each pair's overhead.
# The runs' own accounting (summary.json) is printed too: physics = contact forces +
# integration + list rebuilds, the same work in both runs, so its spread is the machine's
# drift; "rest" = the process's wall time - physics: start-up, setup, output, the movie's
# wait during the run (profile observers) and its setup and finish around the run.
# Usage: scripts/movie_overhead.sh [SCENE] [REPEAT] [extra runout run options...]
set -euo pipefail
scene=${1:-examples/thesis_4_40.toml}
repeat=${2:-3}
shift $(( $# > 2 ? 2 : $# )) || true
bin=${RUNOUT:-build/apps/runout}
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
"$bin" run "$scene" --out "$out/warm" -q "$@" >/dev/null  # settle and cache the pile first
accounts=()
account() {  # WALL FOLDER: wall physics rest observers, physics from the run's summary.json
  /usr/bin/python3 -c "
import json, sys
wall = float(sys.argv[1]); p = json.load(open(sys.argv[2]))['profile_seconds']
phys = p['contact_forces'] + p['integrate'] + p['rebuild']
print(f\"{wall:.2f} {phys:.2f} {wall - phys:.2f} {p['observers']:.2f}\")" "$1" "$2/summary.json"
}
plain=() movie=()
for i in $(seq "$repeat"); do
  s=$(date +%s.%N); "$bin" run "$scene" --out "$out/plain" -q "$@" >/dev/null; e=$(date +%s.%N)
  plain+=("$(echo "$e - $s" | bc)"); accounts+=("plain $(account "${plain[-1]}" "$out/plain")")
  s=$(date +%s.%N); "$bin" run "$scene" --out "$out/movie" -q --movie "$out/movie/flow.mp4" "$@" >/dev/null; e=$(date +%s.%N)
  movie+=("$(echo "$e - $s" | bc)"); accounts+=("movie $(account "${movie[-1]}" "$out/movie")")
done
median() { printf '%s\n' "$@" | sort -n | awk '{a[NR]=$1} END {print (NR % 2) ? a[(NR+1)/2] : (a[NR/2] + a[NR/2+1]) / 2}'; }
echo "# run wall_s physics_s rest_s observers_s"
printf '%s\n' "${accounts[@]}"
pairs=()
for i in $(seq 0 $((repeat - 1))); do pairs+=("$(echo "scale=1; 100 * (${movie[$i]} - ${plain[$i]}) / ${plain[$i]}" | bc)"); done
rest() { printf '%s\n' "${accounts[@]}" | awk -v k="$1" '$1 == k {print $4}'; }
mp=$(median "${plain[@]}"); mm=$(median "${movie[@]}")
rp=$(median $(rest plain)); rm_=$(median $(rest movie))
echo "plain_seconds: ${plain[*]}"
echo "movie_seconds: ${movie[*]}"
echo "pair_overhead_percent: ${pairs[*]}"
echo "median_plain_seconds: $mp"
echo "median_movie_seconds: $mm"
echo "movie_overhead_percent: $(echo "scale=1; 100 * ($mm - $mp) / $mp" | bc)"
echo "median_rest_seconds: plain $rp, movie $rm_"
echo "movie_rest_percent_of_plain: $(echo "scale=1; 100 * ($rm_ - $rp) / $mp" | bc)"
