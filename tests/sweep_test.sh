#!/usr/bin/env bash
# runout sweep end to end on the tiny sweep (examples/sweeps/tiny.toml, four cases of a 60-disc
# pile): run locally, through GNU parallel (when installed), and killed with SIGKILL and run
# again; all three give the same results.csv bytes. Bad sweep files are refused by name and
# nothing already computed is touched.
set -uo pipefail
bin=$1 src=$2
source "$src/tests/lib.sh"
sweep=$src/examples/sweeps/tiny.toml
cache=(--cache-dir "$work/cache")

"$bin" sweep "$sweep" --out "$work/local" --jobs 2 "${cache[@]}" 2>"$work/local.err" && ok || bad "local sweep: $(tail -3 "$work/local.err")"
[ "$(grep -c '^seed' "$work/local/results.csv")" -eq 4 ] && ok || bad "results.csv has not 4 rows"
grep -q "\[4/4\]" "$work/local.err" && grep -q "mu_global = " "$work/local.err" && ok || bad "progress lines: $(cat "$work/local.err")"
grep -q '^30,2,' "$work/local/points.csv" && ok || bad "points.csv: $(head -2 "$work/local/points.csv" | cut -c1-80)"

# runout plot: every figure as PNG and PDF; each PNG is read back by matplotlib's reader.
"$bin" plot "$work/local" >"$work/plot.out" 2>"$work/plot.err" && ok || bad "runout plot: $(tail -3 "$work/plot.err")"
[ "$(ls "$work/local/figures"/*.png 2>/dev/null | wc -l)" -eq 8 ] && [ "$(ls "$work/local/figures"/*.pdf 2>/dev/null | wc -l)" -eq 8 ] &&
  ok || bad "figures: $(ls "$work/local/figures" 2>&1)"
/usr/bin/python3 - "$work"/local/figures/*.png <<'PY' && ok || bad "a figure is not a readable PNG of a sensible size"
import sys
import matplotlib.image as im
for p in sys.argv[1:]:
    a = im.imread(p)
    assert a.shape[0] > 300 and a.shape[1] > 500, (p, a.shape)
    assert a[..., :3].std() > 0.05, (p, "blank")
PY
head -c 5 "$work/local/figures/fig4_1_mu_vs_share.pdf" | grep -q "%PDF-" && ok || bad "fig4_1 PDF"
# The study's frames: the cases of the first seed kept their states at the strip times up to
# their end (the tiny pile rests before t* = 100), those of seed 2 none; every picture's JSON
# says which window it shows, and the deposit's centroid lies inside its window; the picture
# highlights a basal layer exactly when the summary measured one.
[ -e "$work/local/cases/seed1_pct30/states/state_t0000.00.bin" ] && [ ! -e "$work/local/cases/seed2_pct30/states" ] &&
  [ ! -e "$work/local/cases/seed1_pct30/.partial" ] && ok || bad "states: $(ls -a "$work/local/cases/"*)"
[ -e "$work/local/figures/strips/strip_seed1_pct30.png" ] && [ ! -e "$work/local/figures/strips/strip_seed2_pct30.png" ] &&
  ok || bad "strips: $(ls "$work/local/figures/strips" 2>&1)"
/usr/bin/python3 - "$work/local" <<'PY' && ok || bad "frames.json does not describe the frames"
import json, os, sys
import matplotlib.image as im
d = sys.argv[1]
frames = json.load(open(os.path.join(d, "figures/frames/frames.json")))["cases"]
assert len(frames) == 4, len(frames)
for c in frames:
    seed1 = c["case"].startswith("seed1")
    assert ("strip" in c) == seed1, c
    if seed1:
        times = [json.load(open(os.path.join(d, "figures/frames", e["png"][:-4] + ".json")))["t_star"] for e in c["strip"]]
        assert times[:-1] == sorted(times[:-1]) and times[0] == 0 and times[-1] > times[-2], times
        assert c["strip"][-1]["at_rest"] and not c["strip"][0]["at_rest"]
    info = json.load(open(os.path.join(d, "figures/frames", c["deposit"]["png"][:-4] + ".json")))
    x0, x1, y0, y1 = info["extent"]
    cx, cy = c["deposit"]["centroid"]
    h = json.load(open(os.path.join(d, "cases", c["case"], "summary.json")))["H_layer_over_d"]
    assert x0 < cx < x1 and y0 < cy < y1 and (c["deposit"]["layer_discs"] > 0) == (h > 0), (info, c, h)
    img = im.imread(os.path.join(d, "figures/frames", c["deposit"]["png"]))
    assert img.shape[1] == info["width"] == 1600 and img.shape[0] == info["height"], img.shape
    assert [e["label"] for e in info["legend"]] == ["basal layer", "other small", "large"], info["legend"]
PY
# The report: headless Chromium loads it from disk (no network), its script counts the images
# that loaded, and a screenshot is taken.
if command -v chromium >/dev/null; then
  title=$(timeout 120 chromium --headless --no-sandbox --disable-gpu --virtual-time-budget=5000 --dump-dom \
          "file://$work/local/report.html" 2>/dev/null | grep -o "<title>[^<]*</title>")
  [ "$title" = "<title>images: 8/8</title>" ] && ok || bad "report.html in Chromium: $title (want images: 8/8)"
  timeout 120 chromium --headless --no-sandbox --disable-gpu --hide-scrollbars --window-size=1200,1600 \
    --screenshot="$work/report.png" "file://$work/local/report.html" >/dev/null 2>&1
  [ "$(stat -c %s "$work/report.png" 2>/dev/null || echo 0)" -gt 20000 ] && ok || bad "no screenshot of report.html"
else
  bad "chromium not installed (scripts/install-deps.sh installs it): report.html not checked"
fi

# Run again: every case is complete, nothing is run, results.csv is the same.
cp "$work/local/results.csv" "$work/first.csv"
"$bin" sweep "$sweep" --out "$work/local" "${cache[@]}" 2>"$work/again.err" && grep -q "0 to run" "$work/again.err" &&
  cmp -s "$work/local/results.csv" "$work/first.csv" && ok || bad "a second run changed something: $(cat "$work/again.err")"

# GNU parallel: the job list, run by parallel, then gathered.
if command -v parallel >/dev/null; then
  "$bin" sweep "$sweep" --out "$work/par" --emit parallel "${cache[@]}" >/dev/null && ok || bad "--emit parallel"
  parallel --jobs 2 <"$work/par/jobs.txt" >/dev/null 2>&1 && ok || bad "parallel run"
  "$bin" sweep "$sweep" --out "$work/par" --gather 2>/dev/null && cmp -s "$work/par/results.csv" "$work/first.csv" &&
    ok || bad "GNU parallel results.csv differs from the local one"
else
  echo "note: GNU parallel not installed; its route not tested"
fi

# SIGKILL of the sweep once its first case is done, so that it lands in a later one, then the
# sweep again. (A fixed 1.3 s once did this; on a fast host the whole sweep ends in ~1 s and the
# kill found nothing to kill.)
"$bin" sweep "$sweep" --out "$work/killed" --jobs 1 "${cache[@]}" 2>/dev/null &
pid=$!
until_written "$work/killed/cases/*/summary.json" $pid || bad "the sweep ended or stalled before its first case was done"
kill -9 $pid; wait $pid 2>/dev/null
[ "$(ls "$work"/killed/cases/*/summary.json 2>/dev/null | wc -l)" -lt 4 ] && ok || bad "the sweep ended before it was killed"
# The case it ran gets SIGTERM (PR_SET_PDEATHSIG) and writes its checkpoint: wait until it is gone
# (pgrep: procps, in scripts/install-deps.sh). One still running after 60 s is a fault of its own,
# not a reason for the restart below to race it.
case_gone() { ! pgrep -f -- "$work/killed/cases" >/dev/null; }
for _ in $(seq 6000); do case_gone && break; sleep 0.01; done
case_gone && ok || bad "the killed sweep's case still runs 60 s after SIGKILL of the sweep"
"$bin" sweep "$sweep" --out "$work/killed" --jobs 2 "${cache[@]}" 2>"$work/killed.err" &&
  cmp -s "$work/killed/results.csv" "$work/first.csv" && ok || bad "killed + restarted results.csv differs: $(tail -3 "$work/killed.err")"
# ... and the states it saved along the way are the uninterrupted run's, byte for byte.
for c in seed1_pct30 seed1_pct50; do
  (cd "$work/local/cases/$c/states" && sha256sum state_t*.bin) >"$work/states.sum"
  (cd "$work/killed/cases/$c/states" && sha256sum -c --quiet "$work/states.sum") && ok ||
    bad "killed + restarted states of $c differ from the uninterrupted ones"
done

# Bad sweeps: named by file and key; the folder of a finished sweep is left as it was.
before=$(tree_sum "$work/local" ! -name '*.log')
bad_sweep() {  # NAME WANT_EXIT TEXT BODY
  printf '%s\n' "$4" >"$work/$1.toml"
  cp "$src/examples/sweeps/tiny_pile.toml" "$work/"
  out=$("$bin" sweep "$work/$1.toml" --out "$work/local" "${cache[@]}" 2>&1); rc=$?
  [ $rc -eq "$2" ] && grep -qF -- "$3" <<<"$out" && ok || bad "$1: exit $rc (want $2): $out"
}
bad_sweep unknown_axis 1 "axes.colour: unknown axis" $'base = "tiny_pile.toml"\n[axes]\ncolour = [1, 2]'
bad_sweep empty_axis 1 "axes.seed: is empty" $'base = "tiny_pile.toml"\n[axes]\nseed = []'
bad_sweep share_range 1 "axes.small_share: value 120 is out of the allowed range [0, 100]" $'base = "tiny_pile.toml"\n[axes]\nsmall_share = [10, 120]'
bad_sweep bad_scene_key 1 "case seed1_diameter-" $'base = "tiny_pile.toml"\n[axes]\nseed = [1]\n"species.small.diameter" = [-1.0]'
bad_sweep other_sweep 2 "holds another sweep" $'base = "tiny_pile.toml"\n[axes]\nseed = [1, 2, 3]'
[ "$(tree_sum "$work/local" ! -name '*.log')" = "$before" ] && ok || bad "a refused sweep changed the folder"
out=$("$bin" sweep "$sweep" --out "$work/local" --case 9 2>&1); rc=$?
[ $rc -eq 2 ] && grep -q "neither a case name nor an index" <<<"$out" && ok || bad "--case 9: exit $rc: $out"

# A sweep not over %A_p (a polydisperse pile over sigma): mu against the axis, the segregation
# class by class (each class's diameter from summary.json), the flow strip and the deposits.
"$bin" sweep "$src/examples/sweeps/tiny_poly.toml" --out "$work/poly" --jobs 2 "${cache[@]}" 2>/dev/null &&
  "$bin" plot "$work/poly" >/dev/null 2>&1 &&
  [ "$(cd "$work/poly/figures" && ls mu_vs_species_grains_sigma.png segregation_by_class.png fig3_4_flow_sequence.png deposits.png 2>/dev/null | wc -l)" -eq 4 ] &&
  head -1 "$work/poly/results.csv" | grep -q "diameters.grains_3" && ok || bad "polydisperse sweep figures: $(ls "$work/poly/figures" 2>&1)"

# Last (it rewrites DIR/report.html): without the picture module the figures are still drawn,
# and the message says the frames are not.
out=$(RUNOUT_PICTURES_MODULE="$work/none.so" "$bin" plot "$work/local" --out "$work/nomodule" 2>&1) &&
  grep -q "frames were not drawn" <<<"$out" && [ "$(ls "$work/nomodule"/*.png | wc -l)" -eq 6 ] && ok ||
  bad "plot without the picture module: $out"

finish
