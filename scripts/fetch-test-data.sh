#!/usr/bin/env bash
# Fetches real meshes and scans from Debian's libcgal-demo package (its
# data.tar.gz) into test-data/ (not committed).  Tests that need them skip
# cleanly when they are absent.  Needs network access to the Debian archive.
set -euo pipefail
cd "$(dirname "$0")/.."
dest=test-data
if [ -f "$dest/data/meshes/bunny00.off" ]; then
  echo "fetch-test-data: $dest already present"
  exit 0
fi
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
( cd "$work" && apt-get download libcgal-demo >/dev/null 2>&1 ) || {
  echo "fetch-test-data: apt-get download libcgal-demo failed (run 'apt-get update' first?)" >&2
  exit 1
}
dpkg-deb -x "$work"/libcgal-demo_*.deb "$work/pkg"
tarball=$(find "$work/pkg" -name data.tar.gz | head -n 1)
[ -n "$tarball" ] || { echo "fetch-test-data: no data.tar.gz in libcgal-demo" >&2; exit 1; }
mkdir -p "$dest"
tar -xzf "$tarball" -C "$dest" data/meshes/bunny00.off data/meshes/fandisk.off data/points_3/kitten.xyz 2>/dev/null ||
  tar -xzf "$tarball" -C "$dest"
echo "fetch-test-data: unpacked into $dest/"
