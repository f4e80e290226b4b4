#!/usr/bin/env bash
# One thread against two on the bench pile, alternating so the machine's drift hits both alike.
# Usage: scripts/thread_scaling.sh BIN [ROUNDS=5] [STEPS=40000] [extra bench options...]
# Prints each round's pair and the medians, the rounds' median two/one by the host's state (the
# line round trip read by the two-thread bench, split at scripts/turn_log_plot.py's edges: fast
# < 250 ns, slow > 400 ns); the last line is "two/one: R" (ratio of medians).
# Each round also shows what the two-thread bench read of the host (medians of its reads): the
# cache-line round trip between two threads (its fast and slow modes) and two threads' arithmetic
# over one's (about 1 while the host keeps both threads on one core; docs/performance.md, issue 11).
set -euo pipefail
usage() { echo "usage: scripts/thread_scaling.sh BIN [ROUNDS >= 1, default 5] [STEPS >= 1, default 40000] [bench options...]: $1" >&2; exit 2; }
[ $# -ge 1 ] || usage "BIN (the runout binary) is missing"
B=$1; R=${2:-5}; S=${3:-40000}; shift $(( $# < 3 ? $# : 3 ))
[ -x "$B" ] || usage "BIN $B is not an executable file"
[[ "$R" =~ ^[1-9][0-9]*$ ]] || usage "ROUNDS $R is not a whole number >= 1"
[[ "$S" =~ ^[1-9][0-9]*$ ]] || usage "STEPS $S is not a whole number >= 1"
out=$(mktemp); err=$(mktemp); trap 'rm -f "$out" "$err"' EXIT
# A bench that fails ends the go with its own message (the subshell's exit fails the assignment).
rate() {
  local t=$1; shift
  if ! "$B" bench --threads "$t" --steps "$S" "$@" 2>"$err" >"$out"; then
    { echo "thread_scaling.sh: $B bench --threads $t failed:"; tail -n 5 "$err"; } >&2; exit 1
  fi
  sed -n 's/^particle_steps_per_second: *//p' "$out"
}
one=(); two=(); trips=()
for i in $(seq "$R"); do
  a=$(rate 1 "$@"); b=$(rate 2 "$@"); one+=("$a"); two+=("$b")
  trip=$(sed -n 's/^line_round_trip_ns_median: *//p' "$out")
  pair=$(sed -n 's/^arithmetic_pair_speedup_median: *//p' "$out")
  trips+=("${trip:-nan}")
  printf 'round %d: 1 thread %.3g, 2 threads %.3g particle-steps/s, two/one %.2f, line round trip %s ns, arithmetic x%s\n' \
    "$i" "$a" "$b" "$(/usr/bin/python3 -c "print($b/$a)")" "${trip:-?}" "${pair:-?}"
done
PYTHONPATH="$(dirname "$0")" /usr/bin/python3 -c "
import statistics as s
from turn_log_plot import FAST_BELOW_NS as fast, SLOW_ABOVE_NS as slow
a=[float(x) for x in '${one[*]}'.split()]; b=[float(x) for x in '${two[*]}'.split()]
trip=[float(x) for x in '${trips[*]}'.split()]
print(f'medians: 1 thread {s.median(a):.3g}, 2 threads {s.median(b):.3g} particle-steps/s')
print(f'median of the rounds\' two/one: {s.median([y/x for x, y in zip(a, b)]):.2f}')
for name, keep in ((f'fast (< {fast} ns)', lambda t: t < fast), (f'slow (> {slow} ns)', lambda t: t > slow),
                   ('between or not read', lambda t: not (t < fast or t > slow))):
    r = [y / x for x, y, t in zip(a, b, trip) if keep(t)]
    print(f'rounds with the round trip {name}: {len(r)}' + (f', median two/one {s.median(r):.2f}' if r else ''))
print(f'two/one: {s.median(b)/s.median(a):.2f}')"
