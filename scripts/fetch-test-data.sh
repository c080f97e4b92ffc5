#!/usr/bin/env bash
# Fetches real meshes and scans from Debian's libcgal-demo package (its
# data.tar.gz) into test-data/ (not committed).  Tests that need them skip
# when they are absent, or fail under CI=true (tests/test_data.h).  Needs
# network access to the Debian archive.
set -euo pipefail
cd "$(dirname "$0")/.."
dest=test-data
# The files the tests and benchmarks use, as paths inside data.tar.gz.
files=(
  data/meshes/bunny00.off
  data/meshes/fandisk.off
  data/meshes/armadillo.off                      # rd_bench's true surfaces (with fandisk)
  data/meshes/eight.off
  data/meshes/knot1.off
  data/meshes/elephant.off                       # mesh input (issue 18)
  data/meshes/elephant-with-holes.off
  data/meshes/blobby_3cc.off
  data/meshes/camel.off                          # mesh input's needle rule (control_needle_test)
  data/meshes/cow.off                            # mesh input's control size choice (mesh_control_choice_test)
  data/meshes/anchor.off                         # grid_handles_test (four handles opening at one grid)
  data/meshes/couplingdown.off                   # crease_pieces_test (a coarse faceted part whose tags come in pieces)
  data/points_3/kitten.xyz
  data/points_3/hippo1.ply
  data/points_3/half.xyz
  data/points_3/building.ply
  data/points_3/oni.ply
  data/points_3/fin90_with_PCA_normals.xyz
  data/points_3/blobby.xyz
  data/points_3/sphere_20k.xyz
)
missing=()
for f in "${files[@]}"; do
  [ -f "$dest/$f" ] || missing+=("$f")
done
if [ "${#missing[@]}" -eq 0 ]; then
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
# Only the named files (the whole archive is large); the missing ones only,
# so files already there are left as they are.
tar -xzf "$tarball" -C "$dest" "${missing[@]}" || {
  echo "fetch-test-data: data.tar.gz lacks some of: ${missing[*]}" >&2
  exit 1
}
echo "fetch-test-data: unpacked ${#missing[@]} file(s) into $dest/"
