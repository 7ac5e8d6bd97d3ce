#!/usr/bin/env bash
# Installs the Debian 12 packages sphark needs, only those missing. Run as root (or with sudo).
#
# It never removes a package: it first simulates the install (apt-get -s); if apt would remove
# anything (e.g. ParaView's Python, python3-paraview, conflicts with python3-vtk9, which
# libvtk9-dev depends on), it stops before changing anything, names the packages and the
# conflict and the choices, and exits 1. The install itself runs with --no-remove as well.
#
# The functions below are sourced by tests/scripts/install_deps_test.sh (the decision on a
# simulated apt transcript, without root or network); APT_GET, APT_CACHE, DPKG_QUERY and
# SPHARK_SUDO replace the commands there.
set -euo pipefail

SPHARK_PACKAGES=(cmake g++ make pkg-config
                 libsundials-dev libeigen3-dev libvtk9-dev zlib1g-dev
                 libgtest-dev libgmock-dev libbenchmark-dev libnanoflann-dev libhwy-dev
                 openmpi-bin libopenmpi-dev libsundials-nvecparallel-mpi6
                 python3-matplotlib python3-numpy python3-vtk9 xvfb xauth)
APT_GET=${APT_GET:-apt-get}
APT_CACHE=${APT_CACHE:-apt-cache}
DPKG_QUERY=${DPKG_QUERY:-dpkg-query}

# The packages an `apt-get -s install` transcript (stdin) would remove / install, one a line.
apt_plan_removals() { awk '$1 == "Remv" { print $2 }'; }
apt_plan_installs() { awk '$1 == "Inst" { print $2 }'; }

# Whether package $1 declares Conflicts or Breaks on package $2 (apt-cache show).
apt_declares_conflict() {
  "$APT_CACHE" show --no-all-versions "$1" 2>/dev/null | awk -v p="$2" '
    /^(Conflicts|Breaks):/ {
      sub(/^[^:]*:/, "")
      n = split($0, alt, /[,|]/)
      for (k = 1; k <= n; ++k) { split(alt[k], w, " "); if (w[1] == p) found = 1 }
    }
    END { exit !found }'
}

# "A conflicts with B" for every package B the plan removes and A it installs, where either
# declares a conflict with the other. $1: removals, $2: installs (one a line).
apt_plan_conflicts() {
  local r i
  for r in $1; do
    for i in $2; do
      if apt_declares_conflict "$i" "$r"; then echo "$i conflicts with $r"
      elif apt_declares_conflict "$r" "$i"; then echo "$r conflicts with $i"; fi
    done
  done
}

# Reads an `apt-get -s install <packages>` transcript on stdin. Returns 0 if it removes
# nothing; otherwise prints why and what to do to stderr and returns 1.
apt_check_no_removals() {
  local plan removals installs conflicts
  plan=$(cat)
  removals=$(printf '%s\n' "$plan" | apt_plan_removals)
  [ -z "$removals" ] && return 0
  installs=$(printf '%s\n' "$plan" | apt_plan_installs)
  conflicts=$(apt_plan_conflicts "$removals" "$installs")
  {
    echo "install_deps: stopped, nothing was changed: installing $* would REMOVE: $(echo $removals)"
    [ -n "$conflicts" ] && printf '  because %s\n' "$conflicts"
    echo "  sphark never removes a package. Your choices:"
    echo "  - keep them: build sphark in a container, a VM or on another machine (ParaView's GUI, package"
    echo "    paraview, installs next to sphark's packages; its Python, python3-paraview, does not);"
    echo "  - let sphark's packages replace them: sudo apt-get install $*"
    echo "    (apt lists what it removes and asks first), then run this script again."
  } >&2
  return 1
}

main() {
  local missing=() p
  for p in "${SPHARK_PACKAGES[@]}"; do
    "$DPKG_QUERY" -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
  done
  if [ ${#missing[@]} -eq 0 ]; then
    echo "install_deps: all ${#SPHARK_PACKAGES[@]} packages present"
    return 0
  fi
  local sudo
  if [ -n "${SPHARK_SUDO+set}" ]; then sudo=$SPHARK_SUDO; elif [ "$(id -u)" -eq 0 ]; then sudo=""; else sudo="sudo"; fi
  export DEBIAN_FRONTEND=noninteractive
  $sudo "$APT_GET" update -qq
  local plan
  if ! plan=$("$APT_GET" -s install --no-install-recommends "${missing[@]}" 2>&1); then
    printf 'install_deps: apt-get cannot install %s:\n%s\n' "${missing[*]}" "$plan" >&2
    return 1
  fi
  printf '%s\n' "$plan" | apt_check_no_removals "${missing[@]}" || return 1
  echo "install_deps: installing ${missing[*]}"
  $sudo "$APT_GET" install -y -qq --no-install-recommends --no-remove "${missing[@]}"
}

if [ "${BASH_SOURCE[0]}" = "$0" ]; then
  main "$@"
fi
