#!/usr/bin/env bash
# One thread against two on the bench pile, alternating so the machine's drift hits both alike.
# Usage: scripts/thread_scaling.sh BIN [ROUNDS=5] [STEPS=40000] [extra bench options...]
# Prints each round's pair and the medians; the last line is "two/one: R" (ratio of medians).
# With ROUND_TRIP set to a built scripts/line_round_trip.cpp, each round also shows the host's
# cache-line round trip between the two CPUs, measured before and after it (its fast and slow
# modes: docs/performance.md, issue 11 sixteenth session).
set -euo pipefail
B=$1; R=${2:-5}; S=${3:-40000}; shift $(( $# < 3 ? $# : 3 ))
rate() { local t=$1; shift; "$B" bench --threads "$t" --steps "$S" "$@" 2>/dev/null | sed -n 's/^particle_steps_per_second: *//p'; }
trip() { [ -n "${ROUND_TRIP:-}" ] && "$ROUND_TRIP" | sed -n 's/^round trip: //p'; }
one=(); two=()
for i in $(seq "$R"); do
  before=$(trip || true)
  a=$(rate 1 "$@"); b=$(rate 2 "$@"); one+=("$a"); two+=("$b")
  after=$(trip || true)
  printf 'round %d: 1 thread %.3g, 2 threads %.3g particle-steps/s' "$i" "$a" "$b"
  if [ -n "${ROUND_TRIP:-}" ]; then printf ', two/one %.2f, line round trip %s / %s' "$(/usr/bin/python3 -c "print($b/$a)")" "$before" "$after"; fi
  echo
done
/usr/bin/python3 -c "
import statistics as s
a=[float(x) for x in '${one[*]}'.split()]; b=[float(x) for x in '${two[*]}'.split()]
print(f'medians: 1 thread {s.median(a):.3g}, 2 threads {s.median(b):.3g} particle-steps/s')
print(f'median of the rounds\' two/one: {s.median([y/x for x, y in zip(a, b)]):.2f}')
print(f'two/one: {s.median(b)/s.median(a):.2f}')"
