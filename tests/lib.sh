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
finish() {
  echo "$pass passed, $fail failed"
  [ "$fail" -eq 0 ]
}
