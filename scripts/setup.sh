#!/usr/bin/env bash
# Installs the Debian packages edgevio builds against. Idempotent: apt-get runs
# only when a package is missing. Non-interactive; run as root (or with sudo).
set -euo pipefail

packages=(
  cmake g++ make
  libeigen3-dev libyaml-cpp-dev libcli11-dev zlib1g-dev libdeflate-dev
  libopencv-core-dev libopencv-imgproc-dev libopencv-imgcodecs-dev libopencv-calib3d-dev
  libgtest-dev libbenchmark-dev
)

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
