#!/usr/bin/env bash
# cmake/build_info.cmake: the commit and modified state of a git checkout, "unknown" for a
# tree without .git (a tarball), also one unpacked inside another repository; the header is
# rewritten only when a value changes. Run by ctest.
set -euo pipefail
cd "$(dirname "$0")/../.."
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
fails=0
check() {
  local what=$1; shift
  if "$@"; then echo "ok: $what"; else echo "FAILED: $what"; fails=$((fails + 1)); fi
}
generate() {  # generate <source dir> <header>
  cmake -DSOURCE_DIR="$1" -DOUTPUT="$2" -DBUILD_TYPE=Release -DVERSION=0.1 -DSANITIZE=OFF -P "$1/cmake/build_info.cmake"
}
value() { sed -n "s/^#define $1 \"\(.*\)\"$/\1/p" "$2"; }
copy_tree() { mkdir -p "$1/cmake" && cp cmake/build_info.cmake cmake/build_info.hpp.in "$1/cmake/" && echo a > "$1/file.txt"; }
git_() { git -C "$1" -c user.name=test -c user.email=test@example.com "${@:2}"; }

tarball="$tmp/tarball"
copy_tree "$tarball"
generate "$tarball" "$tmp/h1.hpp"
check "a tree without .git: commit unknown" test "$(value SPHARK_GIT_COMMIT "$tmp/h1.hpp")" = unknown
check "a tree without .git: modified unknown" test "$(value SPHARK_GIT_MODIFIED "$tmp/h1.hpp")" = unknown
check "build type and version" test "$(value SPHARK_BUILD_TYPE "$tmp/h1.hpp") $(value SPHARK_VERSION "$tmp/h1.hpp")" = "Release 0.1"

repo="$tmp/repo"
copy_tree "$repo"
git_ "$repo" init -q && git_ "$repo" add -A && git_ "$repo" commit -qm first
generate "$repo" "$tmp/h2.hpp"
check "a clean checkout: its commit" test "$(value SPHARK_GIT_COMMIT "$tmp/h2.hpp")" = "$(git -C "$repo" rev-parse HEAD)"
check "a clean checkout: not modified" test "$(value SPHARK_GIT_MODIFIED "$tmp/h2.hpp")" = no
stamp=$(stat -c %y "$tmp/h2.hpp"); sleep 1.1
generate "$repo" "$tmp/h2.hpp"
check "unchanged values: the header is not rewritten" test "$(stat -c %y "$tmp/h2.hpp")" = "$stamp"
echo b > "$repo/file.txt"
generate "$repo" "$tmp/h2.hpp"
check "an edited file: modified" test "$(value SPHARK_GIT_MODIFIED "$tmp/h2.hpp")" = yes
git_ "$repo" checkout -q file.txt && echo new > "$repo/untracked.cpp"
generate "$repo" "$tmp/h2.hpp"
check "an untracked file: modified" test "$(value SPHARK_GIT_MODIFIED "$tmp/h2.hpp")" = yes

outer="$tmp/outer"
mkdir -p "$outer" && git_ "$outer" init -q && echo x > "$outer/x" && git_ "$outer" add -A && git_ "$outer" commit -qm outer
copy_tree "$outer/sphark-0.1"
generate "$outer/sphark-0.1" "$tmp/h3.hpp"
check "a tarball unpacked inside another repository: unknown" test "$(value SPHARK_GIT_COMMIT "$tmp/h3.hpp")" = unknown

echo "$fails failed"
[ "$fails" -eq 0 ]
