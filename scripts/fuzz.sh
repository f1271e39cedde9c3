#!/usr/bin/env bash
# Fuzzes the readers of user files (tests/fuzz/fuzz_targets.h) with libFuzzer.
# Usage: scripts/fuzz.sh [SECONDS_PER_TARGET] [TARGET...]   (default 60 s, every target)
# Builds build/fuzz with clang (address + undefined sanitizers, installing
# clang with scripts/setup.sh --fuzz), then runs each target from its seeds
# (built in code, and the real files of ../shared/data where it is there:
# EDGEVIO_DATA_DIR), keeping its corpus in out/fuzz/corpus/<target> between runs. A crash, a
# sanitizer report, a leak, an input over 2 GiB of memory or one that takes
# over 10 s stops the target; its input is saved as out/fuzz/<target>-crash-*
# (copy it to tests/fuzz/regressions/<target>/ once fixed: the unit tests
# replay those). Prints one line per target and exits 1 if any found one.
set -euo pipefail
cd "$(dirname "$0")/.."
seconds=${1:-60}
shift || true

bash scripts/setup.sh --fuzz
cmake -S . -B build/fuzz -DCMAKE_CXX_COMPILER=clang++ -DCMAKE_BUILD_TYPE=RelWithDebInfo \
      -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O1 -g1" -DEDGEVIO_FUZZ=ON -DEDGEVIO_BUILD_BENCH=OFF >/dev/null
cmake --build build/fuzz -j"$(nproc 2>/dev/null || echo 2)" --target edgevio_fuzz
fuzz=build/fuzz/tests/fuzz/edgevio_fuzz

shared=${EDGEVIO_DATA_DIR:-../shared/data}
# Real files of a target's kind from the shared data, cut to the fuzzer's
# largest input (the first 64 KiB of a long CSV are still a valid file).
shared_seeds() {
  case $1 in
    trajectory) ls "$shared"/trajectories/*/*/groundtruth* "$shared"/trajectories/uzhfpv/*.txt "$shared"/eval_reference/* ;;
    imu_csv) ls "$shared"/trajectories/euroc/*/imu0.csv "$shared"/euroc/*/mav0/imu0/data.csv ;;
    euroc_camera) ls "$shared"/euroc/*/mav0/cam?/sensor.yaml ;;
  esac 2>/dev/null || true
}

targets=("$@")
[ ${#targets[@]} -gt 0 ] || mapfile -t targets < <(EDGEVIO_FUZZ_TARGET=list "$fuzz" | cut -f1)
mkdir -p out/fuzz
found=0
printf '%-14s %8s %10s %8s %6s  %s\n' target seconds executions corpus cover result
for t in "${targets[@]}"; do
  corpus=out/fuzz/corpus/$t
  log=out/fuzz/$t.log
  mkdir -p "$corpus"
  for f in $(shared_seeds "$t"); do head -c 65536 "$f" >"$corpus/shared-$(echo "$f" | md5sum | cut -c1-12)"; done
  status=0
  EDGEVIO_FUZZ_TARGET=$t EDGEVIO_FUZZ_SEEDS=$corpus ASAN_OPTIONS=detect_leaks=1 \
    "$fuzz" "$corpus" -max_total_time="$seconds" -rss_limit_mb=2048 -timeout=10 -max_len=65536 \
    -artifact_prefix="out/fuzz/$t-" -print_final_stats=1 >"$log" 2>&1 || status=$?
  execs=$(sed -n 's/^stat::number_of_executed_units: *//p' "$log" | tail -1)
  cover=$(grep -o 'cov: [0-9]*' "$log" | tail -1 | cut -d' ' -f2)
  units=$(find "$corpus" -type f | wc -l)
  result=ok
  if [ "$status" -ne 0 ]; then
    result="FOUND: $(grep -m1 -E '==ERROR|SUMMARY|deadly signal|uncaught|timeout|out-of-memory' "$log" || echo "exit $status") (see $log)"
    found=1
  fi
  printf '%-14s %8s %10s %8s %6s  %s\n' "$t" "$seconds" "${execs:-?}" "$units" "${cover:-?}" "$result"
done
exit $found
