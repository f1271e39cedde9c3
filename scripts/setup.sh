#!/usr/bin/env bash
# Installs the Debian packages edgevio builds against. Idempotent: apt-get runs
# only when a package is missing. Non-interactive; run as root (or with sudo).
# Usage: scripts/setup.sh [--test]
set -euo pipefail

packages=(
  cmake g++ make
  libeigen3-dev libyaml-cpp-dev libcli11-dev zlib1g-dev libdeflate-dev libbz2-dev liblz4-dev
  libopencv-core-dev libopencv-imgproc-dev libopencv-imgcodecs-dev libopencv-calib3d-dev
  libgtest-dev libbenchmark-dev
)
# --test adds what only the tests use: Debian's ROS 1 Python bag tools, the
# independent writer and reader the bag tests check edgevio against.
[ "${1:-}" = "--test" ] && packages+=(python3-rosbag python3-sensor-msgs python3-nav-msgs)

missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
[ ${#missing[@]} -eq 0 ] && exit 0

echo "setup: installing ${missing[*]}"
sudo=""
[ "$(id -u)" -eq 0 ] || sudo="sudo"
export DEBIAN_FRONTEND=noninteractive
$sudo apt-get update -qq
$sudo apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
