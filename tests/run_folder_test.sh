#!/usr/bin/env bash
# The output folder, resume, the two checkpoints and signals, with real processes and real
# signals (docs/reliability.md). Exact means every field of summary.json (wall times aside)
# and every byte of timeseries.csv equal those of a run that was never stopped.
set -uo pipefail
bin=$1 src=$2
source "$src/tests/lib.sh"
same_summary() {  # same_summary A B: every field but the wall times
  "$py" - "$1" "$2" <<'PY'
import json, sys
a, b = (json.load(open(p)) for p in sys.argv[1:3])
for k in ("wall_seconds", "particle_steps_per_second", "profile_seconds", "preparation_seconds",
          "pile_from_cache", "preparation", "threads_fewest"):
    a.pop(k, None); b.pop(k, None)
diff = sorted(k for k in set(a) | set(b) if a.get(k) != b.get(k))
if diff:
    print("differ:", ", ".join(f"{k}: {a.get(k)} vs {b.get(k)}" for k in diff))
    sys.exit(1)
PY
}
box=$src/fuzz/checkpoint_scene.toml
quick=$src/examples/quick.toml
cache=(--cache-dir "$work/cache")
cp "$src/tests/data/two_discs.toml" "$work/two.toml"

# 1. Another scene's folder is refused and left exactly as it was; its checkpoint still renders.
pictures=()
[ -e "$(dirname "$bin")/runout_pictures.so" ] && pictures=(--snapshots 0,1)
"$bin" run "$box" --out "$work/A" -q --dump-every 0.5 --vtk-every 0.5 "${pictures[@]}" >/dev/null || bad "box run"
[ -e "$work/A/dump" ] && [ -s "$work/A/vtk/frames.pvd" ] && [ ! -e "$work/A/.partial" ] && ok ||
  bad "the box run's results were not published: $(ls -a "$work/A")"
before=$(tree_sum "$work/A")
out=$("$bin" run "$work/two.toml" --out "$work/A" -q 2>&1); rc=$?
[ $rc -eq 2 ] && grep -q "holds the results of another scene" <<<"$out" && ok || bad "other scene: exit $rc: $out"
out=$("$bin" run "$work/two.toml" --out "$work/A" -q --resume 2>&1); rc=$?
[ $rc -eq 1 ] && grep -q "written for a different scene" <<<"$out" && ok || bad "resume other scene: exit $rc: $out"
[ "$(tree_sum "$work/A")" = "$before" ] && ok || bad "a refused run changed the folder"
if [ -e "$(dirname "$bin")/runout_pictures.so" ]; then
  "$bin" render "$work/A/checkpoint.bin" -o "$work/A.png" 2>/dev/null && ok || bad "the folder's checkpoint no longer renders"
fi

# 2. --overwrite replaces runout's own files only (the old dump frames go, a user's file stays).
echo "mine" >"$work/A/notes.txt"
"$bin" run "$work/two.toml" --out "$work/A" -q --overwrite >/dev/null && ok || bad "--overwrite run"
[ -e "$work/A/notes.txt" ] && [ ! -e "$work/A/dump" ] && [ ! -e "$work/A/vtk" ] && ! ls "$work/A"/snapshot_t*.png >/dev/null 2>&1 &&
  [ -s "$work/A/summary.json" ] && ok || bad "--overwrite cleared the wrong files: $(ls "$work/A")"
# the same scene again replaces its own complete result without --overwrite
"$bin" run "$work/two.toml" --out "$work/A" -q >/dev/null && ok || bad "rerun of the same scene"

# 3. Undefined values: the head-on pair's centre of mass does not move, so mu is null, and no
# nan or inf appears in the time series; output.end_time is met to the step.
"$py" - "$work/A/summary.json" <<'PY' && ok || bad "two-disc summary"
import json, sys
s = json.load(open(sys.argv[1]))
assert s["mu_global"] is None, s["mu_global"]
half = 0.5 / s["steps_per_t_star"]
assert abs(s["t_star_end"] - 5.0) <= half + 1e-12, s["t_star_end"]
PY
grep -qiE "nan|inf" "$work/A/timeseries.csv" && bad "nan or inf in timeseries.csv" || ok
# a lone disc and no walls: no potential energy to measure E_k against, so those are empty
printf '[species.disc]\ndiameter = 0.5\n[[particles]]\nx = 0.0\ny = 0.0\nvx = 1.0\n[output]\nend_time = 2.0\n' >"$work/lone.toml"
"$bin" run "$work/lone.toml" --out "$work/lone" -q >/dev/null 2>&1
[ -s "$work/lone/timeseries.csv" ] && ! grep -qiE "nan|inf" "$work/lone/timeseries.csv" && ok || bad "lone disc: $(head -3 "$work/lone/timeseries.csv" 2>&1)"
# resuming the ended run changes nothing and adds no row
cp "$work/A/timeseries.csv" "$work/two_series.csv"; cp "$work/A/summary.json" "$work/two_summary.json"
"$bin" run "$work/two.toml" --out "$work/A" -q --resume >/dev/null && ok || bad "resume of an ended run"
cmp -s "$work/A/timeseries.csv" "$work/two_series.csv" && same_summary "$work/A/summary.json" "$work/two_summary.json" && ok || bad "resuming an ended run changed its results"
# ... and keeps its published dump frames and states (the resumed run stages empty folders)
"$bin" run "$work/two.toml" --out "$work/S" -q --dump-every 0.5 --vtk-every 0.5 --states 0,0.5 >/dev/null || bad "run with states"
listing=$(cd "$work/S" && sha256sum dump/* vtk/* states/*)
[ "$(ls "$work/S/states" | wc -l)" -eq 2 ] && [ "$(ls "$work/S/dump" | wc -l)" -gt 1 ] &&
  [ "$(ls "$work/S/vtk" | wc -l)" -eq "$(( $(ls "$work/S/dump" | wc -l) + 1 ))" ] && ok || bad "states/dump/vtk: $listing"
"$bin" run "$work/two.toml" --out "$work/S" -q --resume --dump-every 0.5 --vtk-every 0.5 --states 0,0.5 >/dev/null &&
  [ "$(cd "$work/S" && sha256sum dump/* vtk/* states/*)" = "$listing" ] && ok || bad "resuming an ended run lost its dump or VTK frames or states: $(ls -R "$work/S")"
# ... and run on to a later end, its collection lists the frames of both parts, as one run to
# that end has them
"$bin" run "$work/two.toml" --out "$work/S" -q --resume --dump-every 0.5 --vtk-every 0.5 --set output.end_time=7 >/dev/null &&
  "$bin" run "$work/two.toml" --out "$work/S7" -q --dump-every 0.5 --vtk-every 0.5 --set output.end_time=7 >/dev/null &&
  diff -r "$work/S/vtk" "$work/S7/vtk" >/dev/null && ok || bad "a run continued to a later end: vtk/ differs from one run to it"

# 4. The reference: the quick pile run without a stop (this also settles the cached pile).
"$bin" run "$quick" --out "$work/ref" -q "${cache[@]}" --set output.checkpoint_every=3.7 --vtk-every 5 >/dev/null || bad "reference run"

# 5. Signals: SIGINT and SIGTERM stop after a whole step with a checkpoint, exit 130 / 143,
# remove the unfinished movie, leave no summary; the unfinished folder refuses a plain rerun;
# --resume finishes it exactly as the reference.
for sig in INT TERM; do
  d="$work/sig$sig"
  args=(run "$quick" --out "$d" -q "${cache[@]}" --set output.checkpoint_every=3.7 --vtk-every 5)
  movie=()
  [ -e "$(dirname "$bin")/runout_pictures.so" ] && movie=(--movie "$d/flow.mp4")
  "$bin" "${args[@]}" "${movie[@]}" >/dev/null 2>"$work/sig.err" &
  pid=$!
  # The first checkpoint (t* = 3.7) comes early in a run to rest at t* ~ 100.
  until_written "$d/checkpoint.bin" $pid || bad "SIG$sig: the run ended or stalled before its first checkpoint"
  kill -s "$sig" $pid
  wait $pid; rc=$?
  want=$([ $sig = INT ] && echo 130 || echo 143)
  [ $rc -eq "$want" ] && grep -q "stopped by SIG$sig" "$work/sig.err" && ok || bad "SIG$sig: exit $rc (want $want): $(cat "$work/sig.err")"
  [ ! -e "$d/summary.json" ] && [ -s "$d/checkpoint.bin" ] && ! ls "$d"/*.part >/dev/null 2>&1 && ok || bad "SIG$sig left: $(ls "$d")"
  out=$("$bin" "${args[@]}" 2>&1); rc=$?
  [ $rc -eq 2 ] && grep -q "unfinished run" <<<"$out" && ok || bad "plain rerun of an unfinished run: exit $rc: $out"
  "$bin" "${args[@]}" --resume >/dev/null && ok || bad "SIG$sig resume"
  same_summary "$d/summary.json" "$work/ref/summary.json" && cmp -s "$d/timeseries.csv" "$work/ref/timeseries.csv" \
    && diff -r "$d/vtk" "$work/ref/vtk" >/dev/null && ok || bad "SIG$sig + --resume differs from the run never stopped"
done

# 6. kill -9 while the run writes or has just written its second checkpoint, then a damaged
# newest checkpoint: the run falls back to the one before, says so, and still ends exactly as the
# reference.
d="$work/kill9"
args=(run "$quick" --out "$d" -q "${cache[@]}" --set output.checkpoint_every=3.7 --vtk-every 5)
"$bin" "${args[@]}" >/dev/null 2>&1 &
pid=$!
until_written "$d/checkpoint.prev.bin" $pid || bad "kill -9: the run ended or stalled before its second checkpoint"
kill -9 $pid; wait $pid 2>/dev/null
# A frame's temporary left in the staged frames by a writer that is gone (what a kill -9 during
# a VTK frame's write leaves): the resumed run must not publish it.
true & dead=$!; wait $dead
mkdir -p "$d/.partial/vtk" && echo partial >"$d/.partial/vtk/frame.000000007.vtp.tmp.$dead"
# (Both must be there: a kill between keeping the old checkpoint as checkpoint.prev.bin and
# renaming the new one into place leaves only the previous one, which a resume takes as it is.)
if [ -e "$d/checkpoint.prev.bin" ] && [ -e "$d/checkpoint.bin" ]; then
  printf '\x55' | dd of="$d/checkpoint.bin" bs=1 seek=200 conv=notrunc status=none
  out=$("$bin" "${args[@]}" --resume 2>&1 >/dev/null); rc=$?
  [ $rc -eq 0 ] && grep -q "checkpoint.bin: checkpoint checksum mismatch" <<<"$out" && grep -q "resuming from the previous checkpoint" <<<"$out" \
    && ok || bad "fallback: exit $rc: $out"
else
  "$bin" "${args[@]}" --resume >/dev/null 2>&1 || bad "resume after kill -9"
fi
same_summary "$d/summary.json" "$work/ref/summary.json" && cmp -s "$d/timeseries.csv" "$work/ref/timeseries.csv" \
  && diff -r "$d/vtk" "$work/ref/vtk" >/dev/null && ok || bad "kill -9 + --resume differs from the run never stopped"

# 7. A dangling checkpoint symlink is named, not silently taken as "no checkpoint"; stale
# temporaries of dead runs are removed, a live process's are not.
d="$work/dangling"; mkdir -p "$d"
"$bin" run "$work/two.toml" --out "$d" -q >/dev/null
rm -f "$d/checkpoint.bin" "$d/checkpoint.prev.bin" "$d/summary.json"; ln -s "$work/nowhere.bin" "$d/checkpoint.bin"
out=$("$bin" run "$work/two.toml" --out "$d" -q --resume 2>&1); rc=$?
[ $rc -eq 1 ] && grep -q "checkpoint.bin: no such file" <<<"$out" && ok || bad "dangling symlink: exit $rc: $out"
d="$work/stale"; mkdir -p "$d"
touch "$d/checkpoint.bin.tmp.999999999" "$d/summary.json.tmp.$$"
"$bin" run "$work/two.toml" --out "$d" -q >/dev/null
[ ! -e "$d/checkpoint.bin.tmp.999999999" ] && [ -e "$d/summary.json.tmp.$$" ] && ok || bad "stale temporaries: $(ls "$d")"

# 8. A bad picture option is refused before the pile is settled.
out=$("$bin" run "$quick" --out "$work/size" --no-cache --size 0x0 --snapshots 0 2>&1); rc=$?
[ $rc -eq 2 ] && ! grep -q "settling" <<<"$out" && [ ! -e "$work/size" ] && ok || bad "--size 0x0: exit $rc: $out"

# 9. compare: 0 match, 1 differ, 2 bad input (an unwritable --diff is bad input, checked first).
if [ -e "$work/A.png" ]; then
  "$bin" compare "$work/A.png" "$work/A.png" >/dev/null; rc=$?
  [ $rc -eq 0 ] && ok || bad "compare same: exit $rc"
  "$bin" compare "$work/A.png" "$work/A.png" --diff /nonexistent/d.png >/dev/null 2>&1; rc=$?
  [ $rc -eq 2 ] && ok || bad "compare --diff /nonexistent: exit $rc (want 2)"
  "$bin" compare "$work/A.png" "$work/nope.png" >/dev/null 2>&1; rc=$?
  [ $rc -eq 2 ] && ok || bad "compare missing file: exit $rc (want 2)"
fi

finish
