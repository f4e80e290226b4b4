#!/usr/bin/env bash
# Bounded fuzzing in CI: builds the libFuzzer targets with clang (ASan + UBSan) in BUILD/fuzz
# and runs each from the committed seed corpus for SECONDS (default 45). A crash, a leak, a
# sanitizer report or an input slower than 10 s fails the test; the input is kept in
# BUILD/fuzz/findings. The long runs are in docs/reliability.md.
set -euo pipefail
src=$1 build=$2 seconds=${3:-45}
command -v clang++ >/dev/null || { echo "fuzz_ci: clang++ not found (scripts/install-deps.sh installs it)"; exit 1; }
cmake -S "$src" -B "$build/fuzz" -DCMAKE_CXX_COMPILER=clang++ -DRUNOUT_FUZZ=ON -DRUNOUT_NATIVE=OFF \
  -DRUNOUT_BUILD_RENDER=OFF -DRUNOUT_BUILD_TESTS=OFF -DRUNOUT_BUILD_APPS=OFF >"$build/fuzz.configure.log"
cmake --build "$build/fuzz" -j2 >"$build/fuzz.build.log" 2>&1 || { tail -30 "$build/fuzz.build.log"; exit 1; }
mkdir -p "$build/fuzz/findings"
status=0
for target in scene checkpoint; do
  corpus=$(mktemp -d)  # new inputs go here: the committed corpus stays as it is
  if ! (cd "$build/fuzz/findings" && OMP_NUM_THREADS=1 "$build/fuzz/fuzz/fuzz_$target" \
        -max_total_time="$seconds" -timeout=10 -rss_limit_mb=4096 -print_final_stats=1 \
        "$corpus" "$src/fuzz/corpus/$target" 2>"$build/fuzz/$target.log"); then
    echo "FAIL fuzz_$target:"; grep -E "ERROR|runtime error|SUMMARY|Test unit written" "$build/fuzz/$target.log" || tail -20 "$build/fuzz/$target.log"
    status=1
  else
    echo "fuzz_$target: $(grep -E '^stat::number_of_executed_units' "$build/fuzz/$target.log" | awk '{print $2}') inputs in ${seconds} s, no finding"
  fi
  rm -rf "$corpus"
done
exit $status
