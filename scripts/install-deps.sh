#!/usr/bin/env bash
# Installs what runout needs to build and test on Debian 12 (run as root). Idempotent.
set -euo pipefail
export DEBIAN_FRONTEND=noninteractive
packages=(
  build-essential cmake python3 python3-matplotlib
  python3-ase lammps python3-vtk9
  libeigen3-dev libtomlplusplus-dev libcli11-dev nlohmann-json3-dev
  libgtest-dev
  clang libclang-rt-14-dev libomp-dev
  parallel slurm-wlm munge chromium procps
  pkg-config libosmesa6-dev libpng-dev libfreetype-dev fonts-dejavu-core libcairo2-dev libisal-dev libyuv-dev
  poppler-utils librsvg2-bin
  libavcodec-dev libavformat-dev libavutil-dev libswscale-dev
)
missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q 'install ok installed' || missing+=("$p")
done
if [ ${#missing[@]} -gt 0 ]; then
  apt-get update -qq
  apt-get install -y -qq --no-install-recommends "${missing[@]}"
fi
