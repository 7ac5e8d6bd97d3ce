#!/usr/bin/env bash
# Installs missing Debian packages, builds (Release) and runs the main job: the oscillating
# water drop of seed 000 §IV-D, cleaned and control runs, writing VTK, CSV and PNG charts under
# out/water_drop/. Extra arguments go to the water_drop program (see build/bin/water_drop --help).
set -euo pipefail
cd "$(dirname "$0")/.."
./scripts/install_deps.sh
./scripts/build.sh
exec ./build/bin/water_drop --out out/water_drop "$@"
