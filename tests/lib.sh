# What the shell tests share (sourced after `bin=$1 src=$2`): a scratch folder removed on exit,
# the pass and fail counts, and the closing line whose status is the test's.
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
pass=0 fail=0
ok() { pass=$((pass + 1)); }
bad() { echo "FAIL $*"; fail=$((fail + 1)); }
# Debian's interpreter, which sees Debian's python3-* packages (a python3 earlier on PATH may not).
py=python3; [ -x /usr/bin/python3 ] && py=/usr/bin/python3
# tree_sum DIR [FIND_TESTS...]: one line per file below DIR (path and SHA-256), in path order.
tree_sum() {
  local dir=$1
  shift
  (cd "$dir" && find . -type f "$@" -print0 | sort -z | xargs -0 sha256sum)
}
# until_written PATH PID: waits (10 ms polls, at most a minute) until PATH exists, or for a glob
# until something matches it, while process PID runs; fails if PID ends first. Signals in the
# tests wait for what a run has written, not for a fixed time: on a fast host the quick pile and
# the tiny sweep ended within the seconds the tests once slept, and the signal found no run.
until_written() {
  local i
  for i in $(seq 6000); do
    compgen -G "$1" >/dev/null && return 0
    kill -0 "$2" 2>/dev/null || { compgen -G "$1" >/dev/null; return; }
    sleep 0.01
  done
  return 1
}
finish() {
  echo "$pass passed, $fail failed"
  [ "$fail" -eq 0 ]
}
