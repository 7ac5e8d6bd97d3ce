#!/usr/bin/env bash
# scripts/install_deps.sh never removes a package: its decision on simulated apt transcripts
# (no root, no network: apt-get, apt-cache and dpkg-query are stubs). Run by ctest.
set -euo pipefail
cd "$(dirname "$0")/../.."
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
fails=0
check() {  # check <description> <command...>: the command must succeed
  local what=$1; shift
  if "$@"; then echo "ok: $what"; else echo "FAILED: $what"; fails=$((fails + 1)); fi
}

# --- transcripts in apt-get -s format (Debian 12) ----------------------------------------------
cat > "$tmp/nothing_to_remove.txt" <<'T'
NOTE: This is only a simulation!
      apt-get needs root privileges for real execution.
Reading package lists...
The following NEW packages will be installed:
  libvtk9-dev python3-vtk9
0 upgraded, 2 newly installed, 0 to remove and 0 not upgraded.
Inst python3-vtk9 (9.1.0+really9.1.0+dfsg2-5+deb12u1 Debian:12.15/oldstable [amd64])
Inst libvtk9-dev (9.1.0+really9.1.0+dfsg2-5+deb12u1 Debian:12.15/oldstable [amd64])
Conf python3-vtk9 (9.1.0+really9.1.0+dfsg2-5+deb12u1 Debian:12.15/oldstable [amd64])
Conf libvtk9-dev (9.1.0+really9.1.0+dfsg2-5+deb12u1 Debian:12.15/oldstable [amd64])
T
cat > "$tmp/removes_paraview.txt" <<'T'
Reading package lists...
The following packages will be REMOVED:
  python3-paraview
The following NEW packages will be installed:
  libvtk9-dev python3-vtk9
0 upgraded, 2 newly installed, 1 to remove and 0 not upgraded.
Remv python3-paraview [5.11.0+dfsg-1+b1]
Inst python3-vtk9 (9.1.0+really9.1.0+dfsg2-5+deb12u1 Debian:12.15/oldstable [amd64])
Inst libvtk9-dev (9.1.0+really9.1.0+dfsg2-5+deb12u1 Debian:12.15/oldstable [amd64])
Conf python3-vtk9 (9.1.0+really9.1.0+dfsg2-5+deb12u1 Debian:12.15/oldstable [amd64])
Conf libvtk9-dev (9.1.0+really9.1.0+dfsg2-5+deb12u1 Debian:12.15/oldstable [amd64])
T
# apt-cache show: the fields of the real packages
cat > "$tmp/apt-cache" <<'T'
#!/usr/bin/env bash
case "${@: -1}" in
  python3-paraview) printf 'Package: python3-paraview\nReplaces: paraview-python\nConflicts: python3-vtk9\nBreaks: paraview-python\n' ;;
  python3-vtk9) printf 'Package: python3-vtk9\nReplaces: python3-vtk6, python3-vtk7\nBreaks: python3-vtk6, python3-vtk7\n' ;;
  libvtk9-dev) printf 'Package: libvtk9-dev\nDepends: python3-vtk9 (= 9.1.0), libvtk9.1 (= 9.1.0)\n' ;;
  *) exit 100 ;;
esac
T
# apt-get: `-s install` prints the transcript in $PLAN; every call is logged
cat > "$tmp/apt-get" <<'T'
#!/usr/bin/env bash
echo "apt-get $*" >> "$LOG"
[ "$1" = "-s" ] && cat "$PLAN"
exit 0
T
# dpkg-query: everything installed but libvtk9-dev and python3-vtk9
cat > "$tmp/dpkg-query" <<'T'
#!/usr/bin/env bash
case "${@: -1}" in libvtk9-dev|python3-vtk9) exit 1 ;; *) printf 'install ok installed' ;; esac
T
chmod +x "$tmp/apt-cache" "$tmp/apt-get" "$tmp/dpkg-query"
export APT_GET="$tmp/apt-get" APT_CACHE="$tmp/apt-cache" DPKG_QUERY="$tmp/dpkg-query" SPHARK_SUDO="" LOG="$tmp/log"

# --- the decision, as functions ----------------------------------------------------------------
source scripts/install_deps.sh
check "nothing to remove: no removals parsed" test -z "$(apt_plan_removals < "$tmp/nothing_to_remove.txt")"
check "nothing to remove: accepted" apt_check_no_removals libvtk9-dev python3-vtk9 < "$tmp/nothing_to_remove.txt"
check "would remove python3-paraview: parsed" test "$(apt_plan_removals < "$tmp/removes_paraview.txt")" = python3-paraview
check "the conflict is found from the removed package's Conflicts" \
  test "$(apt_plan_conflicts python3-paraview "$(apt_plan_installs < "$tmp/removes_paraview.txt")")" = \
       "python3-paraview conflicts with python3-vtk9"
if apt_check_no_removals libvtk9-dev python3-vtk9 < "$tmp/removes_paraview.txt" 2> "$tmp/message"; then
  check "would remove python3-paraview: refused" false
else
  check "would remove python3-paraview: refused" true
fi
check "the message names the package, the conflict and the choices" bash -c "
  grep -q 'would REMOVE: python3-paraview' '$tmp/message' &&
  grep -q 'because python3-paraview conflicts with python3-vtk9' '$tmp/message' &&
  grep -q 'nothing was changed' '$tmp/message' &&
  grep -q 'keep them' '$tmp/message' && grep -q 'sudo apt-get install libvtk9-dev python3-vtk9' '$tmp/message'"

# --- the whole script ---------------------------------------------------------------------------
: > "$LOG"
if PLAN="$tmp/removes_paraview.txt" bash scripts/install_deps.sh > "$tmp/out" 2> "$tmp/err"; then rc=0; else rc=$?; fi
check "a plan that removes a package: exit non-zero" test "$rc" -ne 0
check "... after simulating, and never installing" bash -c "
  grep -q -- '-s install --no-install-recommends libvtk9-dev python3-vtk9' '$LOG' && ! grep -q '^apt-get install' '$LOG'"
: > "$LOG"
check "a plan without removals: exit 0" env PLAN="$tmp/nothing_to_remove.txt" bash scripts/install_deps.sh > "$tmp/out" 2> "$tmp/err"
check "... installs the missing packages with --no-remove" \
  grep -q -- '^apt-get install -y -qq --no-install-recommends --no-remove libvtk9-dev python3-vtk9$' "$LOG"

echo "$fails failed"
[ "$fails" -eq 0 ]
