#!/usr/bin/env bash
# What seeing a run costs: the real-time factor (sequence seconds per wall
# second, from summary.json) of the same offline run with nothing, with the
# alignment pictures (the default), with an MCAP recording, with the live
# viewer's stream read by curl (the server's own cost), and with the live
# page open in a headless chromium on the same machine (software WebGL: the
# browser's cost too); runs alternate, N rounds (default 3),
# so that a machine's drift hits every variant alike. Prints each run and the
# medians. Usage: bench/viewer_cost.sh DATA [N]   (DATA: e.g. out/demo/data)
# VARIANTS="pictures served" runs only those (default: all five).
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
exe="$root/build/release/edgevio"
data="$1"
rounds="${2:-3}"
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
rtf() { sed -n 's/.*"realtime_factor": \([0-9.]*\).*/\1/p' "$1/summary.json"; }
variants="${VARIANTS:-none pictures mcap served browser}"
declare -A results cpus
for round in $(seq "$rounds"); do
  for variant in $variants; do
    out="$work/$variant-$round"
    # CPU seconds (user + system) of the edgevio process: steadier than wall time on a shared VM.
    timed="/usr/bin/time -f %U+%S -o $out.cpu"
    case "$variant" in
      none) $timed "$exe" run "$data" --out "$out" --pictures-every 0 >/dev/null 2>&1 ;;
      pictures) $timed "$exe" run "$data" --out "$out" >/dev/null 2>&1 ;;
      mcap) $timed "$exe" run "$data" --out "$out" --mcap "$work/run.mcap" >/dev/null 2>&1 ;;
      served)
        $timed "$exe" run "$data" --out "$out" --view 0 >/dev/null 2>"$work/err" &
        pid=$!
        until grep -q "viewer: " "$work/err" 2>/dev/null; do sleep 0.05; done
        curl -s -N "$(grep -o 'http://[0-9.:]*/' "$work/err")events" >/dev/null || true
        wait "$pid" ;;
      browser) node "$root/bench/view_client.mjs" "$exe" "$data" "$out" >/dev/null ;;
    esac
    first="$work/$(echo $variants | cut -d' ' -f1)-1"
    cmp -s "$out/trajectory.csv" "$first/trajectory.csv" || { echo "$variant: the trajectory differs from the first run's" >&2; exit 1; }
    cpu=$( [ -f "$out.cpu" ] && tail -1 "$out.cpu" | awk -F+ '{print $1 + $2}' || echo "-")
    echo "round $round $variant: real-time factor $(rtf "$out"), CPU $cpu s"
    results[$variant]+="$(rtf "$out") "
    cpus[$variant]+="$cpu "
  done
done
for variant in $variants; do
  median=$(echo "${results[$variant]}" | tr ' ' '\n' | grep . | sort -g | awk '{a[NR]=$1} END {print a[int((NR+1)/2)]}')
  cpu_median=$(echo "${cpus[$variant]}" | tr ' ' '\n' | grep -v '^-*$' | sort -g | awk '{a[NR]=$1} END {print (NR ? a[int((NR+1)/2)] : "-")}')
  echo "median $variant: real-time factor $median, CPU $cpu_median s"
done
