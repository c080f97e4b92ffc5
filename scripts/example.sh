#!/usr/bin/env bash
# The main job on the shipped example: install, build, run.
# README command (a); its name and arguments stay fixed as the codec grows.
set -euo pipefail
cd "$(dirname "$0")/.."

bash scripts/install-deps.sh
cmake -S . -B build -G Ninja -DCMAKE_BUILD_TYPE=Release
cmake --build build

mkdir -p build/example
# Until the encoder lands (issues 5 and 6) the job is the container round
# trip: a Draco control mesh and three levels written, verified and read back.
build/bin/dbss-container-example build/example/torus.dbss
build/bin/dbss info build/example/torus.dbss
