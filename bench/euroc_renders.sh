#!/usr/bin/env bash
# Renders a synthetic stereo sequence along each real EuRoC trajectory in
# ../shared/data/trajectories/euroc/ with the real IMU log replayed, runs
# edgevio on each in the given modes, and evaluates all runs (SE(3) alignment).
#
#   bench/euroc_renders.sh OUT_DIR [MODE ...]        (default modes: edge-only edge+imu)
#
# OUT_DIR/data/<sequence>/ holds the ASL folders (rendered once, reused),
# OUT_DIR/runs/<sequence>-<mode>/ the run folders, OUT_DIR/report.md the table.
# Rendering of the next sequence overlaps the runs of the previous one (2 cores).
set -euo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
out="${1:?usage: bench/euroc_renders.sh OUT_DIR [MODE ...]}"
shift
modes=("$@")
[ ${#modes[@]} -eq 0 ] && modes=(edge-only edge+imu)
data="${EDGEVIO_DATA_DIR:-$here/../shared/data}/trajectories/euroc"
[ -d "$data" ] || { echo "error: $data not found (set EDGEVIO_DATA_DIR)"; exit 2; }
bin="$here/build/release/edgevio"
[ -x "$bin" ] || { echo "error: $bin not built (run ./scripts/test.sh or ./edgevio first)"; exit 2; }
mkdir -p "$out/data" "$out/runs"
sequences=()
for d in "$data"/*/; do sequences+=("$(basename "$d")"); done

(
  for s in "${sequences[@]}"; do
    mkdir -p "$out/data/$s"
    # The recomputed per-frame ground truth where it exists (EuRoC's original
    # V1_01 is off by ~5 deg, which the real IMU would contradict), else the 200 Hz file.
    traj="$data/$s/groundtruth.csv"
    [ -f "$traj" ] || traj="$data/$s/groundtruth_tum.txt"
    if [ ! -f "$out/data/$s/.done" ]; then
      "$bin" simulate --out "$out/data/$s" --trajectory "$traj" --imu "$data/$s/imu0.csv" \
        > "$out/data/$s.simulate.log" 2>&1 || { echo "simulate $s failed: see $out/data/$s.simulate.log"; touch "$out/data/$s/.failed"; continue; }
      touch "$out/data/$s/.done"
    fi
  done
) &
renderer=$!

for s in "${sequences[@]}"; do
  while [ ! -f "$out/data/$s/.done" ] && [ ! -f "$out/data/$s/.failed" ]; do sleep 5; done
  [ -f "$out/data/$s/.failed" ] && continue
  for m in "${modes[@]}"; do
    "$bin" run "$out/data/$s" --out "$out/runs/$s-$m" --mode "$m" > "$out/runs/$s-$m.log" 2>&1 || true
    tail -n 2 "$out/runs/$s-$m.log" | head -n 1
  done
done
wait "$renderer"
"$bin" eval --results "$out/runs"
