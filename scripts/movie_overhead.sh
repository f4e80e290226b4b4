#!/usr/bin/env bash
# Measures the wall time a movie adds to a run: the same scene with and without --movie,
# alternately, REPEAT times each; prints every time and the medians.
# Usage: scripts/movie_overhead.sh [SCENE] [REPEAT] [extra runout run options...]
set -euo pipefail
scene=${1:-examples/thesis_4_40.toml}
repeat=${2:-3}
shift $(( $# > 2 ? 2 : $# )) || true
bin=${RUNOUT:-build/apps/runout}
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
"$bin" run "$scene" --out "$out/warm" -q "$@" >/dev/null  # settle and cache the pile first
plain=() movie=()
for i in $(seq "$repeat"); do
  s=$(date +%s.%N); "$bin" run "$scene" --out "$out/plain" -q "$@" >/dev/null; e=$(date +%s.%N)
  plain+=("$(echo "$e - $s" | bc)")
  s=$(date +%s.%N); "$bin" run "$scene" --out "$out/movie" -q --movie "$out/movie/flow.mp4" "$@" >/dev/null; e=$(date +%s.%N)
  movie+=("$(echo "$e - $s" | bc)")
done
median() { printf '%s\n' "$@" | sort -n | awk '{a[NR]=$1} END {print (NR % 2) ? a[(NR+1)/2] : (a[NR/2] + a[NR/2+1]) / 2}'; }
mp=$(median "${plain[@]}"); mm=$(median "${movie[@]}")
echo "plain_seconds: ${plain[*]}"
echo "movie_seconds: ${movie[*]}"
echo "median_plain_seconds: $mp"
echo "median_movie_seconds: $mm"
echo "movie_overhead_percent: $(echo "scale=1; 100 * ($mm - $mp) / $mp" | bc)"
