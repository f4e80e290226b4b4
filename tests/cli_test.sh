#!/usr/bin/env bash
# End-to-end checks of the runout command line: exit codes, error messages, files written.
# Usage: cli_test.sh RUNOUT_BINARY SOURCE_DIR
set -u
bin=$1 src=$2
source "$src/tests/lib.sh"
check() {  # check NAME EXPECTED_EXIT PATTERN -- command...
  local name=$1 want=$2 pattern=$3
  shift 4
  local out
  out=$("$@" 2>&1)
  local got=$?
  if [ "$got" -ne "$want" ] || ! grep -qE "$pattern" <<<"$out"; then
    bad "$name: exit $got (want $want); output:"
    echo "$out" | tail -5
  else
    ok
  fi
}

# Bad input: exit 1, the message names file, key and allowed range; nothing claims success.
printf '[species.a]\ndiameter = 1.0\narea_share = 1.0\n[avalanche]\n[material]\nrestitution = 2.0\n' >"$work/bad.toml"
check bad_range 1 'bad.toml: material.restitution: value 2 is out of the allowed range \[0.01, 1\]' -- \
  "$bin" run "$work/bad.toml" --out "$work/bad" -q
[ -e "$work/bad/summary.json" ] && bad "bad_range wrote a summary"
check bad_set 1 'contact.normal_model: "hooke" is not one of' -- \
  "$bin" run --out "$work/bad2" -q --set contact.normal_model=hooke
check missing_file 2 'scene' -- "$bin" run "$work/nope.toml" --out "$work/x"
check no_out 2 'out' -- "$bin" run

# A short explicit scene: two discs collide on a floor; a summary and a time series appear.
cp "$src/tests/data/two_discs.toml" "$work/two.toml"
check explicit 0 'mu_global' -- "$bin" run "$work/two.toml" --out "$work/two" -q --threads 1
for f in summary.json timeseries.csv scene.resolved.toml checkpoint.bin; do
  [ -s "$work/two/$f" ] || bad "explicit: $f missing"
done
# Threads bound by the user (OMP_PROC_BIND, OMP_PLACES) keep a core each: runout's own restart
# (for shorter OpenMP spins) must not inherit the one CPU libgomp pinned its first thread to.
# libgomp prints each thread's place at the first parallel region (OMP_DISPLAY_AFFINITY).
if [ "$(nproc)" -ge 2 ]; then
  for bind in OMP_PROC_BIND=spread OMP_PLACES=cores; do
    places=$(env -u OMP_WAIT_POLICY -u GOMP_SPINCOUNT "$bind" OMP_DISPLAY_AFFINITY=true \
      "$bin" run "$work/two.toml" --out "$work/bound" -q --threads 2 --overwrite 2>&1 |
      awk '/^level 1 thread/ { seen[$NF] = 1 } END { print length(seen) }')
    if [ "$places" -ge 2 ]; then ok; else
      bad "bound_threads: with $bind the two threads shared $places place(s)"; fi
  done
fi
# A thread limit below --threads (OMP_THREAD_LIMIT) gives a smaller team: the run still
# completes, to the same numbers as one thread.
check thread_limit 0 'mu_global' -- env OMP_THREAD_LIMIT=1 "$bin" run "$work/two.toml" --out "$work/limited" -q --threads 2
a=$(grep -E '"(H_cm|L_cm|steps)"' "$work/two/summary.json")
b=$(grep -E '"(H_cm|L_cm|steps)"' "$work/limited/summary.json" 2>/dev/null)
[ "$a" = "$b" ] || bad "thread_limit: summary differs from one thread's"
# The resolved scene runs again to the same summary numbers.
check resolved 0 'mu_global' -- "$bin" run "$work/two/scene.resolved.toml" --out "$work/two_again" -q --threads 2
a=$(grep -E '"(H_cm|L_cm|steps)"' "$work/two/summary.json")
b=$(grep -E '"(H_cm|L_cm|steps)"' "$work/two_again/summary.json")
[ "$a" = "$b" ] || bad "resolved: summaries differ"

# Dumps: LAMMPS dump custom frames.
check dump 0 'mu_global' -- "$bin" run "$work/two.toml" --out "$work/dump" -q --dump-every 1
grep -q 'ITEM: ATOMS id type x y z radius vx vy vz omegaz' "$work"/dump/dump/frame.000000000.lammpstrj ||
  bad "dump: no frame 0"

# Resume: a run stopped early and resumed matches the run made in one go.
check oneshot 0 'mu_global' -- "$bin" run "$work/two.toml" --out "$work/one" -q --set output.checkpoint_every=1
check first_half 0 'mu_global' -- "$bin" run "$work/two.toml" --out "$work/res" -q --set output.end_time=2.5
check second_half 0 'resuming' -- "$bin" run "$work/two.toml" --out "$work/res" --resume
a=$(grep -E '"(com_rest|H_cm|L_cm|steps)"' -A2 "$work/one/summary.json")
b=$(grep -E '"(com_rest|H_cm|L_cm|steps)"' -A2 "$work/res/summary.json")
[ "$a" = "$b" ] || { bad "resume: summaries differ"; echo "$a"; echo "$b"; }

# An avalanche pile reports its preparation, settled afresh or read from the cache (its report
# is kept beside the cached pile); an explicit scene has none.
check pile_fresh 0 'pile settled at t\* = .*without damping' -- "$bin" run --out "$work/pile1" --cache-dir "$work/cache" --threads 1 --set output.end_time=0.1
check pile_cached 0 'settled pile from cache' -- "$bin" run --out "$work/pile2" --cache-dir "$work/cache" --threads 1 --set output.end_time=0.1
# Without --threads: one thread below 800 discs, every core from 800 (apps/run_command.cpp).
threads_of() { /usr/bin/python3 -c 'import json, sys; print(json.load(open(sys.argv[1]))["threads"])' "$1/summary.json"; }
check default_threads_small 0 'mu_global' -- "$bin" run "$src/examples/quick.toml" --out "$work/few" --cache-dir "$work/cache" -q --set output.end_time=0.1
[ "$(threads_of "$work/few")" = 1 ] && ok || bad "default_threads_small: 250 discs ran on $(threads_of "$work/few") threads, not 1"
check default_threads_large 0 'mu_global' -- "$bin" run "$src/examples/thesis_3_10.toml" --out "$work/many" --cache-dir "$work/cache" -q --set output.end_time=0.1
[ "$(threads_of "$work/many")" = "$(nproc)" ] && ok || bad "default_threads_large: 900 discs ran on $(threads_of "$work/many") threads, not $(nproc)"
a=$(grep -A6 '"preparation"' "$work/pile1/summary.json")
b=$(grep -A6 '"preparation"' "$work/pile2/summary.json")
{ grep -q '"ek_over_ep_undamped"' <<<"$a" && [ "$a" = "$b" ]; } ||
  { bad "pile_report: fresh and cached preparation reports differ"; echo "$a"; echo "$b"; }
grep -q '"preparation": null' "$work/two/summary.json" ||
  bad "explicit_report: an explicit scene reports a preparation"
printf '[species.disc]\ndiameter = 0.5\n[[walls]]\npoints = [[-5.0, 0.0], [5.0, 0.0]]\n[[particles]]\nx = 0.0\ny = 0.25\n' >"$work/noside.toml"
check wall_inside 1 'noside.toml: walls\[0\].inside: is required' -- "$bin" run "$work/noside.toml" --out "$work/noside" -q

# bench: --warmup-steps 0 means no warm-up (it used to mean the default, to t* = 5).
check bench_no_warmup 0 't_star_start: 0.000' -- "$bin" bench --scene "$work/two.toml" --steps 10 --warmup-steps 0
check bench_warmup 0 't_star_start: 5.0' -- "$bin" bench --scene "$work/two.toml" --steps 10
# Two thread counts in turns of 3 steps: each runs all 10 (3 + 3 + 3 + 1), and the speedup is printed.
check bench_turns 0 'against_steps: 10' -- "$bin" bench --scene "$work/two.toml" --steps 10 --threads 2 --against-threads 1 --turn-steps 3
check bench_speedup 0 'speedup: [0-9]+\.[0-9]{3}' -- "$bin" bench --scene "$work/two.toml" --steps 10 --threads 2 --against-threads 1 --turn-steps 3
# --ledger times the step as runs keep it (the energy series on): the pass books its losses.
check bench_ledger 0 'ledger_dissipated_joules: [1-9][0-9.]*(e[-+][0-9]+)?$' -- "$bin" bench --scene "$work/two.toml" --steps 10 --threads 2 --ledger
check bench_no_ledger 0 'ledger: off' -- "$bin" bench --scene "$work/two.toml" --steps 10
check bench_bad_against 2 'against-threads' -- "$bin" bench --scene "$work/two.toml" --steps 10 --against-threads 0
check bench_turns_alone 2 'turn-steps requires --against-threads or --ceiling' -- "$bin" bench --scene "$work/two.toml" --steps 10 --turn-steps 3
# --ceiling: the copies run as many steps as the timed world, in turns, and need two threads.
check bench_ceiling 0 'ceiling_steps: 10' -- "$bin" bench --scene "$work/two.toml" --steps 10 --threads 2 --ceiling --turn-steps 3
check bench_ceiling_speedup 0 'ceiling_lockstep_speedup: [0-9]+\.[0-9]{3}' -- "$bin" bench --scene "$work/two.toml" --steps 10 --threads 2 --ceiling --against-threads 1
check bench_frames_not_with_ceiling 2 'ceiling excludes --frames' -- "$bin" bench --scene "$work/two.toml" --threads 2 --frames 1 --ceiling
check bench_frames_not_with_against 2 'against-threads excludes --frames' -- "$bin" bench --scene "$work/two.toml" --threads 2 --frames 1 --against-threads 1
check bench_ceiling_one_thread 2 'ceiling needs --threads 2 or more' -- "$bin" bench --scene "$work/two.toml" --steps 10 --ceiling
# --ceiling-halo: the copies read the discs from the middle of the pile on, as many as there are
# (two discs: one past the middle), and only with --ceiling.
check bench_ceiling_halo 0 'ceiling_halo_discs: 1$' -- "$bin" bench --scene "$work/two.toml" --steps 10 --threads 2 --ceiling --ceiling-halo 5 --turn-steps 3
check bench_ceiling_halo_speedup 0 'ceiling_halo_speedup: [0-9]+\.[0-9]{3}' -- "$bin" bench --scene "$work/two.toml" --steps 10 --threads 2 --ceiling --ceiling-halo 0
check bench_ceiling_halo_needs_ceiling 2 'ceiling-halo requires --ceiling' -- "$bin" bench --scene "$work/two.toml" --steps 10 --threads 2 --ceiling-halo 5
check bench_ceiling_halo_negative 2 'ceiling-halo: Value -1 not in range' -- "$bin" bench --scene "$work/two.toml" --steps 10 --threads 2 --ceiling --ceiling-halo -1
# bench at two threads reads the host's cache-line round trip and two threads' arithmetic over
# one's before every turn and after the last: 10 steps in turns of 3 are 4 turns, so 5 reads;
# min <= median <= max; neither at one thread.
"$bin" bench --scene "$work/two.toml" --steps 10 --threads 2 --against-threads 1 --turn-steps 3 >"$work/probes.txt" 2>/dev/null
for probe in line_round_trip arithmetic_pair_speedup; do
  if ! grep -q "^${probe}_reads: 5$" "$work/probes.txt"; then
    bad "bench_${probe}_reads: $(grep "^${probe}_reads" "$work/probes.txt")"
  else ok; fi
done
for probe in line_round_trip_ns arithmetic_pair_speedup; do
  spread=$(sed -n "s/^${probe}_\(min\|median\|max\): //p" "$work/probes.txt" | tr '\n' ' ')
  if ! awk -v t="$spread" 'BEGIN { n = split(t, v, " "); exit !(n == 3 && v[1] > 0 && v[1] <= v[2] && v[2] <= v[3]) }'; then
    bad "bench_${probe}_order: min, median, max = '$spread'"
  else ok; fi
done
if "$bin" bench --scene "$work/two.toml" --steps 10 --threads 1 2>/dev/null | grep -q 'line_round_trip\|arithmetic_pair'; then
  bad "bench_probes_one_thread: printed at one thread"
else ok; fi
# Two threads held to one CPU take turns: their arithmetic together takes twice one's (about 1,
# where two cores give about 2; the median of 11 reads, and this test runs alone: CMakeLists),
# and the round trip, passed at each switch, stays short (it spun a whole time slice a trip
# before: 16 s a read, so the 60 s limit would end it).
if command -v taskset >/dev/null; then
  cpu=$(taskset -pc $$ | sed 's/.*: //; s/[-,].*//')
  timeout 60 taskset -c "$cpu" "$bin" bench --scene "$work/two.toml" --steps 10 --threads 2 --against-threads 1 --turn-steps 1 >"$work/one_cpu.txt" 2>/dev/null
  one_cpu=$(sed -n 's/^arithmetic_pair_speedup_median: //p' "$work/one_cpu.txt")
  if ! awk -v x="$one_cpu" 'BEGIN { exit !(x != "" && x > 0.7 && x < 1.4) }'; then
    bad "bench_pair_speedup_one_cpu: '$one_cpu', not about 1"
  else ok; fi
else
  echo "SKIP bench_pair_speedup_one_cpu: no taskset"
fi
# --turn-log: a CSV row per turn (10 steps in turns of 3: 3, 3, 3, 1), read back with Python's csv
# module: the steps add up to --steps, each speed-up is its turn's seconds' ratio, and each turn's
# round trip and arithmetic after are the next turn's before. A missing folder is refused before any work.
check bench_turn_log 0 'speedup: ' -- "$bin" bench --scene "$work/two.toml" --steps 10 --threads 2 --against-threads 1 --turn-steps 3 --turn-log "$work/turns.csv"
/usr/bin/python3 - "$work/turns.csv" <<'PY' || bad "bench_turn_log_rows"
import csv, sys
rows = list(csv.DictReader(open(sys.argv[1])))
assert [int(r["steps"]) for r in rows] == [3, 3, 3, 1], rows
assert all(r["threads"] == "2" and r["against_threads"] == "1" for r in rows)
for r in rows:
    s, a = float(r["seconds"]), float(r["against_seconds"])
    assert s > 0 and a > 0 and abs(float(r["speedup"]) - a / s) <= 1e-4 * a / s + 6e-5, r
for probe in ("line_round_trip_ns", "arithmetic_pair_speedup"):
    assert all(float(r[probe + "_before"]) > 0 and float(r[probe + "_after"]) > 0 for r in rows), probe
    assert all(rows[k][probe + "_after"] == rows[k + 1][probe + "_before"] for k in range(len(rows) - 1)), probe
assert all(r["ceiling_alone_seconds"] == r["ceiling_lockstep_seconds"] == r["ceiling_lockstep_speedup"] == "" for r in rows)
PY
# With --ceiling the log also holds each turn's copies: alone over lockstep is the printed ratio.
check bench_turn_log_ceiling 0 'ceiling_lockstep_speedup: ' -- "$bin" bench --scene "$work/two.toml" --steps 10 --threads 2 --against-threads 1 --ceiling --turn-steps 5 --turn-log "$work/turns_ceiling.csv"
/usr/bin/python3 - "$work/turns_ceiling.csv" <<'PY' || bad "bench_turn_log_ceiling_rows"
import csv, sys
rows = list(csv.DictReader(open(sys.argv[1])))
assert [int(r["steps"]) for r in rows] == [5, 5], rows
for r in rows:
    alone, lockstep = float(r["ceiling_alone_seconds"]), float(r["ceiling_lockstep_seconds"])
    assert alone > 0 and lockstep > 0 and abs(float(r["ceiling_lockstep_speedup"]) - alone / lockstep) <= 1e-4 * alone / lockstep + 6e-5, r
PY
# scripts/turn_log_plot.py on turns made up here, one log row per "SECONDS AGAINST_SECONDS
# TRIP_BEFORE TRIP_AFTER PAIR_BEFORE PAIR_AFTER" (its speed-up is their ratio).
made_log() {  # made_log FILE ROW...
  local file=$1 row; shift
  printf 'turn,steps,threads,seconds,against_threads,against_seconds,speedup,line_round_trip_ns_before,line_round_trip_ns_after,arithmetic_pair_speedup_before,arithmetic_pair_speedup_after\n' >"$file"
  for row; do
    set -- $row; printf '0,1000,2,%s,1,%s,%s,%s,%s,%s,%s\n' "$1" "$2" "$(awk -v a="$2" -v b="$1" 'BEGIN{print a/b}')" "$3" "$4" "${5-}" "${6-}" >>"$file"
  done
}
# By round trip: three fast turns (1.7, 1.8, 1.9: median 1.8), two slow ones (1.5, 1.6), one
# between; no arithmetic reads (empty cells, as where none were read), so no split by them.
made_log "$work/made.csv" "10 17 100 120" "10 18 120 110" "10 19 130 140" "10 15 500 600" "10 16 600 450" "10 20 200 500"
check turn_log_plot_fast 0 'fast \(both < 250 ns\): 3 turns, speed-up median 1\.800' -- /usr/bin/python3 "$src/scripts/turn_log_plot.py" "$work/made.csv"
check turn_log_plot_slow 0 'slow \(both > 400 ns\): 2 turns, speed-up median 1\.550' -- /usr/bin/python3 "$src/scripts/turn_log_plot.py" "$work/made.csv"
# By two threads' arithmetic over one's: three turns with both reads >= 1.8 (speed-ups 1.7, 1.8,
# 1.9: median 1.8), two with both <= 1.3 (1.0, 1.2: median 1.1), one with a read each side.
made_log "$work/made_pairs.csv" "10 17 300 300 1.9 2.0" "10 18 300 300 1.8 1.95" "10 19 300 300 2.0 1.85" "10 10 300 300 1.0 1.1" "10 12 300 300 1.3 1.05" "10 20 300 300 1.9 1.2"
check turn_log_plot_two_cores 0 "two cores' worth \\(both ≥ 1\\.8\\): 3 turns, speed-up median 1\\.800" -- /usr/bin/python3 "$src/scripts/turn_log_plot.py" "$work/made_pairs.csv"
check turn_log_plot_one_core 0 "one core's \\(both ≤ 1\\.3\\): 2 turns, speed-up median 1\\.100" -- /usr/bin/python3 "$src/scripts/turn_log_plot.py" "$work/made_pairs.csv"
printf 'a,b\n1,2\n' >"$work/not_a_log.csv"
check turn_log_plot_bad_file 1 'not_a_log.csv:2: not a row of runout bench --turn-log' -- /usr/bin/python3 "$src/scripts/turn_log_plot.py" "$work/not_a_log.csv"
# It draws the bench's own log as a PNG.
check turn_log_plot_draws 0 'drawn: ' -- /usr/bin/python3 "$src/scripts/turn_log_plot.py" "$work/turns.csv" --out "$work/turns.png"
/usr/bin/python3 -c "import sys; sys.exit(open(sys.argv[1], 'rb').read(8) != b'\x89PNG\r\n\x1a\n')" "$work/turns.png" || bad "turn_log_plot_png"
check bench_turn_log_folder 2 'turn-log: folder .*/nowhere does not exist' -- "$bin" bench --scene "$work/two.toml" --steps 10 --threads 2 --against-threads 1 --turn-log "$work/nowhere/turns.csv"
check bench_turn_log_needs_against 2 'turn-log requires --against-threads' -- "$bin" bench --scene "$work/two.toml" --steps 10 --threads 2 --turn-log "$work/t.csv"

# scripts/thread_scaling.sh: three rounds on the two discs; its rounds by round trip must be
# the rounds' own round trips classed here (fast < 250 ns, slow > 400 ns), and the last line
# the ratio of the medians.
scaling=$("$src/scripts/thread_scaling.sh" "$bin" 3 10 --scene "$work/two.toml" 2>&1)
if [ "$(grep -c '^round [0-9]: ' <<<"$scaling")" = 3 ] && grep -qE '^two/one: [0-9]+\.[0-9]{2}$' <<<"${scaling##*$'\n'}" &&
  [ "$(awk '/^round /{for (i = 1; i < NF; ++i) if ($i == "trip") t = $(i + 1); c = t < 250 ? "fast" : t > 400 ? "slow" : "between"; n[c]++}
            END {printf "%d %d %d", n["fast"], n["slow"], n["between"]}' <<<"$scaling")" = \
    "$(sed -n 's/^rounds with the round trip [^:]*: \([0-9]*\).*/\1/p' <<<"$scaling" | tr '\n' ' ' | sed 's/ $//')" ]; then
  ok
else
  bad "thread_scaling_states:"; echo "$scaling" | tail -6
fi
check thread_scaling_no_bin 2 'BIN \(the runout binary\) is missing' -- "$src/scripts/thread_scaling.sh"
check thread_scaling_bad_rounds 2 'ROUNDS 0 is not a whole number >= 1' -- "$src/scripts/thread_scaling.sh" "$bin" 0 10
check thread_scaling_bench_fails 1 'bench --threads 1 failed:$' -- "$src/scripts/thread_scaling.sh" "$bin" 1 10 --scene "$work/nope.toml"
check thread_scaling_bench_says_why 1 'File does not exist: .*nope.toml' -- "$src/scripts/thread_scaling.sh" "$bin" 1 10 --scene "$work/nope.toml"
# The accuracy study: every variant runs (or is reported as failed) and the table is whole.
check study 0 'reference' -- "$bin" study accuracy "$work/two.toml" --out "$work/study" --seeds 2 --set output.end_time=1.0
[ "$(wc -l <"$work/study/study.csv")" -eq 12 ] || bad "study: study.csv should have 11 rows"
[ "$(wc -l <"$work/study/runs.csv")" -eq 23 ] || bad "study: runs.csv should have 11 x 2 rows"
# The plot is matplotlib's (scripts/runout_plot.py), PNG and PDF.
[ -s "$work/study/study.png" ] && [ -s "$work/study/study.pdf" ] || bad "study: no plot"
# Resuming a finished study reruns nothing: the same rows, the same table.
cp "$work/study/runs.csv" "$work/runs.before"
check study-resume 0 'reference' -- "$bin" study accuracy "$work/two.toml" --out "$work/study" --seeds 2 --resume --set output.end_time=1.0
cmp -s "$work/runs.before" "$work/study/runs.csv" || bad "study-resume: runs.csv changed"

# Pictures come from a module loaded on demand: the binary itself links no rendering library,
# a run without picture options works with no module at all, and one with them says what is
# missing instead of drawing nothing.
if ldd "$bin" | grep -Ei 'osmesa|llvm|avcodec|avformat|swscale|libpng|freetype'; then
  bad "no_render_libs: the runout binary links a rendering library"
else
  ok
fi
check no_module_plain 0 'mu_global' -- env RUNOUT_PICTURES_MODULE="$work/none.so" "$bin" run "$work/two.toml" --out "$work/plain" -q
check no_module_snapshots 1 'picture module runout_pictures.so was not found' -- \
  env RUNOUT_PICTURES_MODULE="$work/none.so" "$bin" run "$work/two.toml" --out "$work/nopic" -q --snapshots 1
if [ -e "$(dirname "$bin")/runout_pictures.so" ]; then
  check snapshots 0 'mu_global' -- "$bin" run "$work/two.toml" --out "$work/pic" -q --snapshots 0,2 --size 320x180
  for f in snapshot_t0.png snapshot_t2.png; do
    [ -s "$work/pic/$f" ] || bad "snapshots: $f missing"
  done
  check compare_same 0 'match: yes' -- "$bin" compare "$work/pic/snapshot_t0.png" "$work/pic/snapshot_t0.png"
  # A run asked to end with its last snapshot stops there (t* = 2 of the scene's 5).
  check end_at_snapshot 0 'mu_global' -- "$bin" run "$work/two.toml" --out "$work/endsnap" -q --snapshots 0,2 \
    --size 320x180 --end-at-last-snapshot
  awk -F': ' '/"t_star_end"/ { t = $2 + 0; ok = (t > 1.9 && t < 2.1) } END { exit !ok }' "$work/endsnap/summary.json" ||
    { bad "end_at_snapshot: did not stop at t* = 2"; grep t_star_end "$work/endsnap/summary.json"; }
fi
check end_needs_snapshots 2 'needs --snapshots' -- "$bin" run "$work/two.toml" --out "$work/endsnap2" -q --end-at-last-snapshot

# runout derive prints SPEC §3's check values for the thesis scenes (k_U/m* of the small pair,
# dt, steps per t*), and the table in text.
for case in "8_33_25 1.062e8 4.88e-5" "4_40 5.10e7 7.05e-5" "3_60 3.82e7 8.14e-5" "2_50 2.55e7 9.96e-5"; do
  set -- $case
  "$bin" derive "$src/examples/thesis_$1.toml" --json >"$work/derive.json" &&
  /usr/bin/python3 - "$work/derive.json" "$2" "$3" <<'PY' || bad "derive thesis_$1"
import json, sys
j = json.load(open(sys.argv[1]))
row = next(r for r in j["contacts"] if r["pair"] == "small among small")
assert abs(row["k_unload_over_m_star"] / float(sys.argv[2]) - 1) < 2e-3, row
assert abs(j["dt"] / float(sys.argv[3]) - 1) < 2e-3, j["dt"]
assert round(j["steps_per_t_star"]) == 2266, j["steps_per_t_star"]
assert abs(row["k_load"] / row["k_unload"] - 0.04) < 1e-12 and row["k_tangential"] == row["k_load"], row
PY
done
check derive_text 0 '2266 steps per t*' -- "$bin" derive "$src/examples/thesis_4_40.toml"
check derive_bad_key 1 'contact.normal_model' -- "$bin" derive --set contact.normal_model=foo
# runout keys prints the flat tables as TOML with their defaults: with one species it is a scene
# whose derived setup (stiffnesses, time step, counts) is that of an all-default scene.
"$bin" keys >"$work/keys.toml" && printf '\n[species.disc]\ndiameter = 1.0\narea_share = 1.0\n' >>"$work/keys.toml"
printf '[species.disc]\ndiameter = 1.0\narea_share = 1.0\n[avalanche]\n' >"$work/defaults.toml"
check keys_table 0 'dt_fraction = 0.1 +# number in \[0.0001, 1\]' -- cat "$work/keys.toml"
if [ "$("$bin" derive "$work/keys.toml" 2>&1 | sed 1d)" = "$("$bin" derive "$work/defaults.toml" 2>&1 | sed 1d)" ]; then
  ok
else
  bad "keys_as_scene: the listed defaults derive another setup"
fi

# A tiny polydisperse pile (lognormal by area in three classes) runs to rest; its summary
# reports every class, and a saved state renders.
cat >"$work/poly.toml" <<'EOF'
[species.grains]
distribution = "lognormal"
median = 0.6
sigma = 0.4
min = 0.4
max = 1.0
classes = 3
area_share = 1.0
[avalanche]
incline_length = 8.0
pile_width = 5.0
floor_length = 40.0
wall_height = 15.0
reference_large_count = 30
[rest]
ek_threshold = 1e-4
hold = 2.0
max_time = 300.0
EOF
check polydisperse 0 'mu_global' -- "$bin" run "$work/poly.toml" --out "$work/poly" -q --states 0,10
/usr/bin/python3 - "$work/poly" <<'PY' || bad "polydisperse summary"
import json, sys, tomllib
d = sys.argv[1]
j = json.load(open(d + "/summary.json"))
names = ["grains_1", "grains_2", "grains_3"]
assert j["at_rest"] and sorted(j["counts"]) == names and sorted(j["mean_height_over_d"]) == names, j
assert sum(j["counts"].values()) == j["n_large"] + j["n_small"] and j["n_large"] == j["counts"]["grains_3"], j
assert all(h is not None and h > 0 for h in j["mean_height_over_d"].values()), j["mean_height_over_d"]
species = tomllib.load(open(d + "/scene.resolved.toml", "rb"))["species"]
assert sorted(species) == names and abs(sum(s["area_share"] for s in species.values()) - 1) < 1e-12, species
assert species["grains_1"]["max"] == species["grains_2"]["min"], species
PY
if [ -e "$(dirname "$bin")/runout_pictures.so" ]; then
  check render_state 0 'wrote' -- "$bin" render "$work/poly/states/state_t0010.00.bin" -o "$work/poly10.png" --size 320x180
fi

finish
