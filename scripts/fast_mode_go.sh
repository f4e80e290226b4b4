#!/usr/bin/env bash
# Waits for the host's fast mode and measures two threads against one the moment it comes.
# On this VM kind the two vCPUs' cache-line round trip swings between ~100 ns (fast) and
# ~450 ns (slow), and the fast mode comes for seconds at a time (docs/performance_log.md, issue 11
# thirty-first session). This reads the round trip about once a second; when one is under
# LIMIT ns it runs the in-run comparison first (issue 11's figure, and the shortest: the
# fast mode often ends within a minute of load), then the nine-round thread_scaling go and the
# ceiling, into OUT/go_N.txt, and then goes back to waiting until MINUTES have passed.
# Every round trip read goes to OUT/round_trips.txt.
# Usage: scripts/fast_mode_go.sh BIN ROUND_TRIP_BIN [MINUTES=60] [OUT=fast_mode_gos] [LIMIT=160]
#   ROUND_TRIP_BIN: g++ -O2 -pthread scripts/line_round_trip.cpp -o /tmp/line_round_trip
set -euo pipefail
usage() { echo "usage: scripts/fast_mode_go.sh BIN ROUND_TRIP_BIN [MINUTES=60] [OUT=fast_mode_gos] [LIMIT=160]: $1" >&2; exit 2; }
[ $# -ge 2 ] || usage "BIN (runout) and ROUND_TRIP_BIN (scripts/line_round_trip.cpp, built) are both needed"
B=$1; RT=$2; M=${3:-60}; OUT=${4:-fast_mode_gos}; LIMIT=${5:-160}
for f in "$B" "$RT"; do [ -x "$f" ] || usage "$f is not an executable file"; done
[[ "$M" =~ ^[1-9][0-9]*$ ]] || usage "MINUTES $M is not a whole number >= 1"
[[ "$LIMIT" =~ ^[1-9][0-9]*$ ]] || usage "LIMIT $LIMIT is not a whole number of ns >= 1"
here=$(cd "$(dirname "$0")" && pwd)
mkdir -p "$OUT"
deadline=$(( $(date +%s) + 60 * M )); n=0
trip() { "$RT" | sed -n 's/^round trip: \([0-9]*\) ns$/\1/p'; }
while [ "$(date +%s)" -lt "$deadline" ]; do
  t=$(trip)
  echo "$(date -u +%H:%M:%S) $t" >> "$OUT/round_trips.txt"
  if [ -n "$t" ] && [ "$t" -lt "$LIMIT" ]; then
    n=$((n + 1))
    {
      echo "== start $(date -u +%H:%M:%S), round trip $t ns"
      echo "== bench --threads 2 --against-threads 1 --steps 20000 (round trip $(trip) ns)"
      "$B" bench --threads 2 --against-threads 1 --steps 20000 2>/dev/null | grep -E '^(particle_steps|against_particle|speedup|line_round_trip_ns)'
      echo "== thread_scaling 9 20000 (round trip $(trip) ns)"
      "$here/thread_scaling.sh" "$B" 9 20000
      echo "== bench --threads 2 --against-threads 1 --ceiling --steps 20000 (round trip $(trip) ns)"
      "$B" bench --threads 2 --against-threads 1 --ceiling --steps 20000 2>/dev/null | grep -E '^(speedup|ceiling_.*speedup|line_round_trip_ns)'
      echo "== end $(date -u +%H:%M:%S), round trip $(trip) ns"
    } > "$OUT/go_$n.txt.part"
    mv "$OUT/go_$n.txt.part" "$OUT/go_$n.txt"
    echo "$(date -u +%H:%M:%S) go $n" >> "$OUT/round_trips.txt"
  fi
  sleep 1
done
