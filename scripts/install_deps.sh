#!/usr/bin/env bash
# Installs the Debian 12 packages sphark needs, only those missing. Run as root (or with sudo).
set -euo pipefail
pkgs=(cmake g++ make pkg-config
      libsundials-dev libeigen3-dev libvtk9-dev zlib1g-dev
      libgtest-dev libgmock-dev libbenchmark-dev libnanoflann-dev
      python3-matplotlib python3-numpy python3-vtk9 xvfb xauth)
missing=()
for p in "${pkgs[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -eq 0 ]; then
  echo "install_deps: all ${#pkgs[@]} packages present"
  exit 0
fi
echo "install_deps: installing ${missing[*]}"
SUDO=""
[ "$(id -u)" -eq 0 ] || SUDO="sudo"
export DEBIAN_FRONTEND=noninteractive
$SUDO apt-get update -qq
$SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}"
