#!/usr/bin/env bash
# The main job on the shipped example: install, build, encode a point cloud,
# decode every level, print sizes and per-level counts.
# README command (a); its name and arguments stay fixed as the codec grows.
set -euo pipefail
cd "$(dirname "$0")/.."

bash scripts/install-deps.sh
cmake -S . -B build -G Ninja -DCMAKE_BUILD_TYPE=Release
cmake --build build

out=build/example
mkdir -p "$out"
build/bin/dbss encode examples/double-torus.xyz -o "$out/double-torus.dbss" --dump-stages "$out/stages"
levels=$(build/bin/dbss info "$out/double-torus.dbss" --json | sed -n 's/^ *"levels": \([0-9]*\),$/\1/p')
for level in $(seq 0 "${levels:-0}"); do
  build/bin/dbss decode "$out/double-torus.dbss" --level "$level" -o "$out/double-torus-level$level.ply"
done
build/bin/dbss info "$out/double-torus.dbss"
