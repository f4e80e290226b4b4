#!/usr/bin/env bash
# CI's share of the thesis grid (scripts/check_thesis_grid.sh; the whole grid is in
# docs/results/grid.md). It covers every way the thesis cases used to fail with the defaults:
# the three bidisperse D/d = 8.33 piles lost small discs through the back wall while growing
# (seed 1; prepared here for seeds 1 and 2), and D/d = 4, %A_p = 10 lost a disc through the floor
# in the flow (seed 1) and never settled (seed 3) (run to rest here for seeds 1 to 3).
#   tests/thesis_grid_ci.sh RUNOUT_BINARY SOURCE_DIR
set -euo pipefail
bin="$1"; src="$2"
out="$(mktemp -d)"
trap 'rm -rf "$out"' EXIT
status=0
bash "$src/scripts/check_thesis_grid.sh" --bin "$bin" --jobs 2 --seeds "1 2" --prepare-only \
  --cases "thesis_8_33_10 thesis_8_33_25 thesis_8_33_50" "$out/prepare" || status=1
bash "$src/scripts/check_thesis_grid.sh" --bin "$bin" --jobs 2 --seeds "1 2 3" \
  --cases "thesis_4_10" "$out/flow" || status=1
exit $status
