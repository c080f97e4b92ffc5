#!/usr/bin/env bash
# Installs dbss's build and test dependencies from Debian 12 packages.
# Runs apt-get only when something is missing, so repeated runs are quick.
set -euo pipefail

packages=(
  build-essential cmake ninja-build pkg-config   # toolchain
  clang libclang-rt-14-dev                       # second compiler, sanitizers, libFuzzer
  libdraco-dev libzstd-dev                       # container payloads (decoder)
  libtinygltf-dev nlohmann-json3-dev             # glTF reading and writing (io); header-only
  libnanoflann-dev libeigen3-dev                 # KD-tree queries, quadrics (encoder)
  libopenmesh-dev                                # QEM decimation (encoder); differential tests
  catch2                                         # tests (Catch2 v2)
  libcgal-dev                                    # rd_bench's peers only (reconstruction); header-only
  nodejs npm                                     # the Khronos glTF validator (tests/gltf, npm ci)
)
# Optional, for scripts/plot-rd.py's plots: apt-get install python3-matplotlib

missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -eq 0 ]; then
  echo "install-deps: all ${#packages[@]} packages present"
  exit 0
fi

sudo=""
if [ "$(id -u)" -ne 0 ]; then
  command -v sudo >/dev/null || { echo "install-deps: need root or sudo to install: ${missing[*]}" >&2; exit 1; }
  sudo="sudo"
fi
echo "install-deps: installing ${missing[*]}"
$sudo apt-get update -qq
DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq --no-install-recommends "${missing[@]}"
