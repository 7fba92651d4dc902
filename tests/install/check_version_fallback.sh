#!/usr/bin/env bash
# ctest version_fallback: cmake/build_version.cmake names the git checkout when there is one,
# and falls back to the bare project version in a tree without .git (a release tarball).
# Usage: check_version_fallback.sh SOURCE_DIR SCRATCH_DIR PROJECT_VERSION
set -euo pipefail
src=$1 scratch=$2 version=$3
rm -rf "$scratch" && mkdir -p "$scratch/tarball"
tarball=$(cmake -DPROJECT_SOURCE_DIR="$scratch/tarball" -DPROJECT_VERSION="$version" -P "$src/cmake/build_version.cmake" 2>&1)
[ "$tarball" = "-- shudder version: $version" ] || { echo "FAIL without .git: '$tarball'"; exit 1; }
if command -v git >/dev/null && [ -e "$src/.git" ]; then
  checkout=$(cmake -DPROJECT_SOURCE_DIR="$src" -DPROJECT_VERSION="$version" -P "$src/cmake/build_version.cmake" 2>&1)
  case "$checkout" in "-- shudder version: $version (git "*")") ;; *) echo "FAIL in the checkout: '$checkout'"; exit 1;; esac
fi
echo "ok: $tarball / ${checkout:-no git checkout}"
