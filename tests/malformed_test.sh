#!/usr/bin/env bash
# The malformed-input corpus (tests/malformed/*.case): each case is a scene (the quick pile, a
# body of its own, /dev/zero, a FIFO, a folder) and command-line arguments that must be refused
# within seconds with the given exit code and error text, before the output folder is created.
# Header lines of a case: "# scene:", "# args:", "# exit:", "# error:"; the rest is its scene.
# {work} in args is a folder that exists, {self} a file that exists, {scene} the scene path.
set -uo pipefail
bin=$1 src=$2
source "$src/tests/lib.sh"
for case in "$src"/tests/malformed/*.case; do
  name=$(basename "$case" .case)
  field() { sed -n "s/^# $1: \{0,1\}//p" "$case" | head -1; }
  scene_kind=$(field scene) args=$(field args) want=$(field exit) error=$(field error)
  case "$scene_kind" in
    quick) scene="$src/examples/quick.toml" ;;
    body) scene="$work/$name.toml"; grep -v '^# \(scene\|args\|exit\|error\):' "$case" >"$scene" ;;
    fifo) scene="$work/$name.fifo"; mkfifo "$scene" ;;
    folder) scene="$work/$name.d"; mkdir -p "$scene" ;;
    *) scene=$scene_kind ;;
  esac
  out="$work/out_$name"
  args=${args//\{work\}/$work}
  args=${args//\{self\}/$case}
  error=${error//\{scene\}/$scene}
  error=${error//\{work\}/$work}
  error=${error//\{self\}/$case}
  if [[ $args == *--out-override* ]]; then out=${args#*--out-override }; args=""; fi
  # shellcheck disable=SC2086
  timeout 60 "$bin" run "$scene" --out "$out" -q --no-cache $args >"$work/stdout" 2>"$work/stderr"
  got=$?
  [ -n "${SHOW:-}" ] && echo "$name: $(cat "$work/stderr")"
  if [ "$got" -ne "$want" ] || ! grep -qF -- "$error" "$work/stderr"; then
    bad "$name: exit $got (want $want), stderr:"; sed 's/^/    /' "$work/stderr" | head -5
    echo "    want the text: $error"
  elif [ "$out" = "$work/out_$name" ] && [ -e "$out" ]; then
    bad "$name: refused, but $out was created"
  else
    ok
  fi
done
finish
