#!/usr/bin/env bash
# The thesis grid (SPEC §5, table 3.1): every pile of examples/thesis_*.toml, prepared with its
# defaults and run to rest, for several seeds, cases side by side at one thread each. Prints
# one Markdown row per case and exits non-zero if any case fails (an error, or not at rest).
#
#   scripts/check_thesis_grid.sh [--bin build/apps/runout] [--seeds "1 2 3"] [--jobs 2]
#                                [--cases "thesis_4_10 thesis_8_33_25"] [--prepare-only] OUT_DIR
#
# --prepare-only settles each pile and stops just after release (the flow is not run).
# OUT_DIR/grid.md gets the table, the command and the total wall time; OUT_DIR/<case>/ the runs.
set -euo pipefail
here="$(cd "$(dirname "$0")/.." && pwd)"
bin="$here/build/apps/runout"
seeds="1 2 3"
jobs=2
cases=""
prepare_only=0
while [ $# -gt 1 ]; do
  case "$1" in
    --bin) bin="$2"; shift 2 ;;
    --seeds) seeds="$2"; shift 2 ;;
    --jobs) jobs="$2"; shift 2 ;;
    --cases) cases="$2"; shift 2 ;;
    --prepare-only) prepare_only=1; shift ;;
    *) echo "check_thesis_grid.sh: unknown option $1" >&2; exit 2 ;;
  esac
done
[ $# -eq 1 ] || { sed -n 2,10p "$0" >&2; exit 2; }
out="$1"
[ -x "$bin" ] || { echo "check_thesis_grid.sh: no runout binary at $bin (build first, or --bin)" >&2; exit 2; }
if [ -z "$cases" ]; then
  cases="$(cd "$here/examples" && ls thesis_*.toml | sed 's/\.toml$//' | sort -t_ -k2,2n -k3,3n -k4,4n | tr '\n' ' ')"
fi
mkdir -p "$out"
export bin out prepare_only here

one_case() {  # scene seed -> one TSV line: name rc wall_seconds
  local scene="$1" seed="$2" dir="$out/${1}_s${2}" start end rc=0
  rm -rf "$dir"
  mkdir -p "$dir"
  local extra=()
  [ "$prepare_only" = 1 ] && extra=(--set output.end_time=0.05)
  start=$(date +%s%N)
  "$bin" run "$here/examples/$scene.toml" --out "$dir/run" --seed "$seed" --threads 1 --no-cache \
    --quiet "${extra[@]}" > "$dir/stdout.txt" 2> "$dir/stderr.txt" || rc=$?
  end=$(date +%s%N)
  printf '%s\t%s\t%s\t%s\n' "$scene" "$seed" "$rc" "$(( (end - start) / 1000000 ))"
}
export -f one_case

t0=$(date +%s)
for scene in $cases; do for seed in $seeds; do printf '%s %s\n' "$scene" "$seed"; done; done |
  xargs -P "$jobs" -L 1 bash -c 'one_case "$0" "$1"' > "$out/cases.tsv"
t1=$(date +%s)

# One row per case, in grid order, from each run's summary.json (python3's standard library).
status=0
/usr/bin/env python3 - "$out" "$prepare_only" "$((t1 - t0))" "$jobs" <<'EOF' || status=$?
import json, os, sys
out, prepare_only, total, jobs = sys.argv[1], sys.argv[2] == "1", int(sys.argv[3]), sys.argv[4]
rows = [l.rstrip("\n").split("\t") for l in open(os.path.join(out, "cases.tsv")) if l.strip()]
order = {}
for scene, seed, rc, wall in rows:
    order[(scene, int(seed))] = (int(rc), float(wall) / 1000.0)
def key(k):
    parts = k[0].split("_")  # thesis_<D/d with _ for .>_<share>
    ratio = float(".".join(parts[1:-1]))
    return (ratio, int(parts[-1]), k[1])
fails = 0
lines = ["| D/d | %A_p | seed | discs | preparation s | flow s | mu_global | t*_rest | at_rest | settled at t* | E_k/E_p undamped | result |",
         "|---|---|---|---|---|---|---|---|---|---|---|---|"]
for k in sorted(order, key=key):
    scene, seed = k
    rc, wall = order[k]
    parts = scene.split("_")
    ratio, share = ".".join(parts[1:-1]), parts[-1]
    summary = os.path.join(out, f"{scene}_s{seed}", "run", "summary.json")
    err = open(os.path.join(out, f"{scene}_s{seed}", "stderr.txt")).read().strip().splitlines()
    ok = rc == 0 and os.path.exists(summary)
    if ok:
        s = json.load(open(summary))
        prep = s.get("preparation") or {}
        at_rest = bool(s["at_rest"])
        ok = at_rest or prepare_only
        fmt = lambda v, f: ("%" + f) % v if isinstance(v, (int, float)) else "null"
        flow = s["wall_seconds"]
        lines.append("| %s | %s | %d | %d | %.1f | %s | %s | %s | %s | %s | %s | %s |" % (
            ratio, share, seed, s["n_large"] + s["n_small"], s["preparation_seconds"],
            "-" if prepare_only else "%.1f" % flow,
            "-" if prepare_only else fmt(s["mu_global"], ".4f"),
            "-" if prepare_only else fmt(s["t_star_rest"], ".1f"),
            "-" if prepare_only else ("yes" if at_rest else "no"),
            fmt(prep.get("t_star_settled"), ".1f"), fmt(prep.get("ek_over_ep_undamped"), ".1e"),
            "ok" if ok else "FAILED"))
    else:
        why = err[-1] if err else "exit %d" % rc
        lines.append("| %s | %s | %d | - | - | - | - | - | - | - | - | FAILED (exit %d): %s |" % (
            ratio, share, seed, rc, why.replace("|", "/")[:300]))
    fails += 0 if ok else 1
table = "\n".join(lines)
print(table)
with open(os.path.join(out, "grid.md.tmp"), "w") as f:
    f.write(table + "\n\n%d cases, %d failed; total wall time %d s (%d min) with %s cases side by side, one thread each.\n"
            % (len(order), fails, total, total // 60, jobs))
os.replace(os.path.join(out, "grid.md.tmp"), os.path.join(out, "grid.md"))
print("%d cases, %d failed; total wall time %d s" % (len(order), fails, total))
sys.exit(1 if fails else 0)
EOF
exit $status
