#!/usr/bin/env bash
# Installs the Debian packages edgevio builds against. Idempotent: apt-get runs
# only when a package is missing. Non-interactive; run as root (or with sudo).
# Usage: scripts/setup.sh [--test | --fuzz]
set -euo pipefail

packages=(
  cmake g++ make
  libeigen3-dev libyaml-cpp-dev libcli11-dev zlib1g-dev libdeflate-dev libbz2-dev liblz4-dev
  libopencv-core-dev libopencv-imgproc-dev libopencv-imgcodecs-dev libopencv-calib3d-dev
  libgtest-dev libbenchmark-dev
)
# Node.js builds nothing, but npm installs three.js, which the viewer's page
# bundles (web/package.json); a Node.js already installed (any vendor) will do.
command -v npm >/dev/null 2>&1 || packages+=(nodejs npm)
# --test adds what only the tests use: Debian's ROS 1 Python bag tools, the
# independent writer and reader the bag tests check edgevio against, and
# Debian's chromium for the viewer's browser tests.
[ "${1:-}" = "--test" ] && packages+=(python3-rosbag python3-sensor-msgs python3-nav-msgs chromium)
# --fuzz: clang and its libFuzzer runtime (scripts/fuzz.sh).
[ "${1:-}" = "--fuzz" ] && packages+=(clang libclang-rt-14-dev)

missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -gt 0 ]; then
  echo "setup: installing ${missing[*]}"
  sudo=""
  [ "$(id -u)" -eq 0 ] || sudo="sudo"
  export DEBIAN_FRONTEND=noninteractive
  $sudo apt-get update -qq
  $sudo apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
fi

# The npm packages of web/package-lock.json (three.js; with them the tests'
# MCAP reader and browser driver), installed again only when the lock changed.
# No browser is downloaded: the tests drive Debian's chromium.
web="$(cd "$(dirname "$0")/.." && pwd)/web"
stamp="$web/node_modules/.edgevio-lock"
if ! cmp -s "$web/package-lock.json" "$stamp" 2>/dev/null; then
  echo "setup: installing the npm packages of web/package-lock.json"
  (cd "$web" && npm ci --no-audit --no-fund --loglevel=error >/dev/null)
  cp "$web/package-lock.json" "$stamp"
fi
