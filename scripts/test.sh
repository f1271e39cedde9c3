#!/usr/bin/env bash
# Builds edgevio and runs every test (the README's test command; .ci/run calls it).
#  1. installs missing Debian packages (scripts/setup.sh --test, idempotent);
#  2. Release build with warnings as errors, then all tests (ctest);
#  3. address+undefined sanitizer build, then the unit tests again;
#  4. thread sanitizer build, then the tests of every edgevio thread (the
#     pipeline's three offline and in real time, shutdown on errors, the
#     live server, the simulator's and renderer's workers);
#  5. libFuzzer on every reader of user files, briefly (scripts/fuzz.sh:
#     clang build of the readers; a crash or sanitizer report fails).
# Set EDGEVIO_SKIP_SANITIZE=1 to skip steps 3 to 5 during development.
set -euo pipefail
cd "$(dirname "$0")/.."
jobs=$(nproc 2>/dev/null || echo 2)

bash scripts/setup.sh --test
# Each stage's title with the minutes since the start: where CI's time goes.
stage() { printf '== %s == (at %d min %02d s)\n' "$1" $((SECONDS / 60)) $((SECONDS % 60)); }

stage "Release build (-Werror)"
cmake -S . -B build/release -DCMAKE_BUILD_TYPE=Release -DEDGEVIO_WERROR=ON >/dev/null
cmake --build build/release -j"$jobs"
stage "All tests"
(cd build/release && ctest --output-on-failure -j"$jobs")

if [ "${EDGEVIO_SKIP_SANITIZE:-0}" != "1" ]; then
  stage "Sanitizer build (address, undefined)"
  # -O1 -g1: UBSan's checks at -O2 multiply the compile time of Eigen-heavy
  # files (the sliding window: 110 s at -O2 -g, 52 s at -O1 -g1, on 2 cores
  # where the Release build takes 22 s); line tables are enough for the
  # sanitizers' stack traces.
  cmake -S . -B build/sanitize -DCMAKE_BUILD_TYPE=RelWithDebInfo -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O1 -g1 -DNDEBUG" \
        -DEDGEVIO_WERROR=ON -DEDGEVIO_SANITIZE=ON -DEDGEVIO_BUILD_BENCH=OFF >/dev/null
  cmake --build build/sanitize -j"$jobs" --target edgevio_unit_tests
  stage "Unit tests under sanitizers"
  (cd build/sanitize && ASAN_OPTIONS=detect_leaks=1 UBSAN_OPTIONS=print_stacktrace=1 \
     ctest --output-on-failure -j"$jobs" -L unit)

  stage "Thread sanitizer build"
  cmake -S . -B build/tsan -DCMAKE_BUILD_TYPE=RelWithDebInfo -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O1 -g1 -DNDEBUG" \
        -DEDGEVIO_WERROR=ON -DEDGEVIO_TSAN=ON -DEDGEVIO_BUILD_BENCH=OFF >/dev/null
  cmake --build build/tsan -j"$jobs" --target edgevio_thread_tests
  stage "Threads under the thread sanitizer"
  (cd build/tsan && TSAN_OPTIONS="halt_on_error=1 suppressions=$PWD/../../tests/tsan_suppressions.txt" \
     ctest --output-on-failure -j"$jobs" -L thread)

  stage "Fuzzing every reader (libFuzzer, 5 s a target)"
  bash scripts/fuzz.sh 5
fi
stage "Done"
